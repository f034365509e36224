// Viewer latency benchmark (not a test): from sending a hand `move` to (a) the first
// snapshot that shows it (the hand's target) and (b) the end of the requestAnimationFrame
// callback that first draws that snapshot, measured in the page with performance.now().
// Runs `pliant serve` ($PLIANT_BIN, default target/release/pliant) on loopback and headless
// Chromium (software WebGL: SwiftShader), in the cheap and the full rendering mode.
// Usage: npm run bench:latency [-- --moves 60 --interval 100]

import { launchBrowser, median, openViewer, percentile, sleep, startServer } from '../test/harness.mjs';

const arg = (name, dflt) => {
  const i = process.argv.indexOf(`--${name}`);
  return i > 0 ? Number(process.argv[i + 1]) : dflt;
};
const MOVES = arg('moves', 60);
const INTERVAL_MS = arg('interval', 100);

const CONFIGS = [
  { name: 'low quality, 800x500', width: 800, height: 500, query: '?quality=low' },
  { name: 'full quality, 1280x800', width: 1280, height: 800, query: '' },
  // a small canvas: little software rendering per frame
  { name: 'low quality, 400x250', width: 400 + 320, height: 250, query: '?quality=low' },
  // the simulation paused after the grab: the same path without its thread's CPU load
  { name: 'low quality, sim paused', width: 800, height: 500, query: '?quality=low', pause: true },
];

const server = await startServer();
const browser = await launchBrowser();
const rows = [];
try {
  for (const cfg of CONFIGS) {
    const { page } = await openViewer(browser, server.url, cfg);
    // frame rate while idle
    const f0 = await page.evaluate(() => window.pliant.frames);
    await sleep(2000);
    const fps = ((await page.evaluate(() => window.pliant.frames)) - f0) / 2;
    // grab the free end of the last hose
    await page.evaluate(() => window.pliant.send({ type: 'reset' }));
    await sleep(2500);
    const end = await page.evaluate(() => {
      const p = window.pliant;
      const nodes = p.hoseNodes(p.welcome.session.hoses.length - 1);
      const e = nodes[nodes.length - 1];
      p.send({ type: 'grab', hand_id: p.mouseHandId, position: e });
      return e;
    });
    await sleep(300);
    if (cfg.pause) await page.evaluate(() => window.pliant.send({ type: 'pause' }));
    await sleep(100);
    await page.evaluate(() => window.pliant.clearLatency());
    for (let i = 0; i < MOVES; i++) {
      const dz = 0.01 + 0.02 * (i % 2); // alternate 1 and 3 cm above the grab point
      await page.evaluate(([e, dz]) => {
        const p = window.pliant;
        p.send({ type: 'move', hand_id: p.mouseHandId, position: [e[0], e[1], e[2] + dz] });
      }, [end, dz]);
      await sleep(INTERVAL_MS);
    }
    await sleep(500);
    const samples = await page.evaluate(() => window.pliant.latency());
    await page.evaluate(() => window.pliant.send({ type: 'release', hand_id: window.pliant.mouseHandId }));
    if (cfg.pause) await page.evaluate(() => window.pliant.send({ type: 'resume' }));
    await page.close();
    const snap = samples.map((s) => s.snapshot);
    const frame = samples.map((s) => s.frame);
    rows.push({ config: cfg.name, fps, n: samples.length, sent: MOVES, snap, frame });
  }
} finally {
  await browser.close();
  await server.stop();
}

const f = (x) => x.toFixed(1);
console.log(`move → snapshot and move → drawn frame, ${MOVES} moves ${INTERVAL_MS} ms apart, loopback, headless Chromium (SwiftShader)`);
console.log('config                     fps   n    snapshot median / p95 [ms]   frame median / p95 [ms]');
for (const r of rows) {
  console.log(
    `${r.config.padEnd(26)} ${r.fps.toFixed(0).padStart(4)} ${String(r.n).padStart(3)}    ${f(median(r.snap)).padStart(6)} / ${f(percentile(r.snap, 95)).padStart(6)}              ${f(median(r.frame)).padStart(6)} / ${f(percentile(r.frame, 95)).padStart(6)}`,
  );
}
for (const r of rows) {
  const ok = median(r.frame) <= 2 * (1000 / 60);
  console.log(`goal move → frame ≤ 2 frames at 60 Hz (33.3 ms), median, ${r.config}: ${ok ? 'met' : 'not met'}`);
}
console.log(JSON.stringify(rows.map((r) => ({
  config: r.config, fps: r.fps, samples: r.n,
  snapshot_ms: { median: median(r.snap), p95: percentile(r.snap, 95) },
  frame_ms: { median: median(r.frame), p95: percentile(r.frame, 95) },
}))));
