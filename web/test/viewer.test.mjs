// End-to-end tests of the browser viewer: `pliant serve` (the real binary, embedded
// viewer) driven in headless Chromium (SwiftShader WebGL) through playwright-core.
// Run: npm run test:e2e (PLIANT_BIN overrides the binary, default target/release/pliant).
// Every wait is for a condition, bounded only by the hang guard (HANG_GUARD_MS, the pages'
// default timeout): nothing depends on how fast the machine is.

import assert from 'node:assert/strict';
import { existsSync, mkdirSync, readFileSync } from 'node:fs';
import path from 'node:path';
import { after, before, describe, test } from 'node:test';
import { framesDrawn, launchBrowser, openViewer, repo, simulated, sleep, startServer } from './harness.mjs';

/** Software rendering is slow at full quality: most tests use the cheap mode. */
const LOW = { width: 1024, height: 640, query: '?quality=low' };

let server;
let browser;

before(async () => {
  server = await startServer();
  browser = await launchBrowser();
});

after(async () => {
  await browser?.close();
  await server?.stop();
});

/** Classifies the canvas pixels in the page (read back from the WebGL drawing buffer). */
async function pixelClasses(page) {
  return page.evaluate(() => {
    const canvas = document.querySelector('#view canvas');
    const gl = canvas.getContext('webgl2') ?? canvas.getContext('webgl');
    const w = gl.drawingBufferWidth;
    const h = gl.drawingBufferHeight;
    const px = new Uint8Array(w * h * 4);
    gl.readPixels(0, 0, w, h, gl.RGBA, gl.UNSIGNED_BYTE, px);
    let hose = 0;
    let part = 0;
    const colours = new Set();
    for (let i = 0; i < px.length; i += 4) {
      const r = px[i], g = px[i + 1], b = px[i + 2];
      if (b > 80 && b > r + 50 && b > g + 50) hose++; // force colour c = 0: blue
      const lo = Math.min(r, g, b), hi = Math.max(r, g, b);
      if (lo > 90 && hi - lo < 60) part++; // light grey / beige parts
      colours.add((r >> 3) * 1024 + (g >> 3) * 32 + (b >> 3));
    }
    return { total: w * h, hose, part, distinct: colours.size };
  });
}

/** Resets the shared session and waits for the viewer to show the reset. */
async function resetSession(page) {
  const epoch = await page.evaluate(() => window.pliant.snapshot.epoch);
  await page.evaluate(() => window.pliant.send({ type: 'reset' }));
  await page.waitForFunction((e) => window.pliant.shown?.epoch > e, epoch);
}

/** Waits until hose `h` has come to rest (after a reset it falls under gravity first):
 *  it moves less than 1 mm in 0.2 s of simulated time, within 20 s of simulated time. */
async function settled(page, h) {
  const nodes = () => page.evaluate((h) => window.pliant.hoseNodes(h), h);
  let prev = await nodes();
  for (let i = 0; i < 100; i++) {
    await simulated(page, 0.2);
    const now = await nodes();
    if (moved(prev, now) < 0.001) return now;
    prev = now;
  }
  throw new Error(`hose ${h} did not come to rest`);
}

/** Waits until node `k` of hose `h` is more than `d` [m] away from `p`. */
async function nodeMoved(page, h, k, p, d) {
  await page.waitForFunction(([h, k, p, d]) => {
    const n = window.pliant.hoseNodes(h)[k];
    return n !== undefined && Math.hypot(n[0] - p[0], n[1] - p[1], n[2] - p[2]) > d;
  }, [h, k, p, d]);
}

const dist = (a, b) => Math.hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]);

/** Largest displacement between two node lists. */
const moved = (a, b) => Math.max(...a.map((p, i) => dist(p, b[i])));

describe('viewer', () => {
  test('the page loads from the binary and renders the scene', async () => {
    const res = await fetch(server.url);
    assert.equal(res.status, 200);
    const html = await res.text();
    assert.match(html, /<script type="module"/, 'the embedded viewer, not the how-to-build page');
    const { page, logs } = await openViewer(browser, server.url);
    try {
      const w = await page.evaluate(() => window.pliant.welcome);
      assert.ok(w.session.hoses.length >= 1);
      await framesDrawn(page, 10);
      const c = await pixelClasses(page);
      assert.ok(c.hose > 500, `hose-coloured pixels: ${c.hose}`);
      assert.ok(c.part > 5000, `part-coloured pixels: ${c.part}`);
      assert.ok(c.distinct > 50, `distinct colours: ${c.distinct} (a uniform image has 1)`);
      assert.ok(c.hose + c.part < c.total, 'not all one class');
      const title = await page.textContent('#scene-name');
      assert.match(title, /hose/);
      assert.ok(!logs.some((l) => l.startsWith('pageerror')), logs.join('\n'));
      // a screenshot for people: the lower hose's free end pulled up by a hand, so that
      // the force colour and the panel show
      const hose = w.session.hoses.length - 1;
      const nodes = await page.evaluate((h) => window.pliant.hoseNodes(h), hose);
      const end = nodes[nodes.length - 1];
      await page.evaluate(([p]) => {
        const id = window.pliant.mouseHandId;
        window.pliant.send({ type: 'grab', hand_id: id, position: p });
        window.pliant.send({ type: 'move', hand_id: id, position: [p[0] + 0.05, p[1] + 0.1, p[2] + 0.12] });
      }, [end]);
      // the colour follows the hand's force against its push/pull limit (twist and bending
      // are guidance only, SPEC I4): a hand lifting the end carries a small share of it
      await page.waitForFunction(() => (window.pliant.shown?.hoses ?? []).some((h) => h.colour > 0.02));
      await simulated(page, 1.5);
      const dir = path.join(repo, 'target', 'e2e');
      mkdirSync(dir, { recursive: true });
      await page.screenshot({ path: path.join(dir, 'viewer.png') });
    } finally {
      await page.close();
    }
  });

  test('dragging a hose with the mouse moves it and the panel shows the hand force', async () => {
    const { page } = await openViewer(browser, server.url, LOW);
    try {
      await resetSession(page);
      // a node near the free end of the last hose (the first node is fixed)
      const hose = (await page.evaluate(() => window.pliant.welcome.session.hoses.length)) - 1;
      const before = await settled(page, hose);
      const k = before.length - 2;
      const at = await page.evaluate(([p]) => window.pliant.screenOf(p), [before[k]]);
      assert.equal(await page.locator('#hands .hand').count(), 0);
      await page.mouse.move(at.x, at.y);
      await page.mouse.down();
      for (let i = 1; i <= 10; i++) {
        await page.mouse.move(at.x + 4 * i, at.y - 8 * i);
        await sleep(30);
      }
      const handId = await page.evaluate(() => window.pliant.mouseHandId);
      const pick = await page.evaluate(() => window.pliant.lastPick);
      assert.ok(pick !== null && pick.hose === hose, `pointer-down at ${JSON.stringify(at)} picked ${JSON.stringify(pick)}`);
      await page.waitForFunction(
        (id) => (window.pliant.snapshot?.hands ?? []).some((h) => h.hand_id === id && Math.hypot(...h.force) > 0.1),
        handId,
      );
      // the hand reaches its target: the node has moved and the panel shows the force
      await nodeMoved(page, hose, k, before[k], 0.02);
      await page.waitForFunction(
        (id) => Number(document.querySelector(`#hands .hand[data-hand="${id}"] .force`)?.getAttribute('data-value')) > 0.1,
        handId,
      );
      const during = await page.evaluate((h) => window.pliant.hoseNodes(h), hose);
      assert.ok(moved(before, during) > 0.02, `hose moved ${moved(before, during)} m`);
      assert.ok(dist(before[k], during[k]) > 0.02, `grabbed node moved ${dist(before[k], during[k])} m`);
      // the panel shows a non-zero force for the hand
      const force = Number(await page.getAttribute(`#hands .hand[data-hand="${handId}"] .force`, 'data-value'));
      assert.ok(force > 0.1, `panel force ${force} N`);
      const text = await page.textContent(`#hands .hand[data-hand="${handId}"] .force`);
      assert.match(text, /Force [1-9]\d*\.\d N|Force 0\.[1-9] N/);
      await page.mouse.up();
      await page.waitForFunction((id) => !(window.pliant.snapshot?.hands ?? []).some((h) => h.hand_id === id), handId);
    } finally {
      await page.close();
    }
  });

  test('the emulated headset (iwer) grabs, moves and releases hoses with both controllers', async () => {
    const { page, logs } = await openViewer(browser, server.url, { ...LOW, query: '?xr=emulate&quality=low' });
    try {
      await page.locator('#enter-vr:not([disabled])').waitFor();
      await resetSession(page);
      await page.click('#enter-vr');
      await page.waitForFunction(() => window.pliant.inVr).catch((e) => {
        throw new Error(`${e.message}\n${logs.join('\n')}`);
      });
      const nHoses = await page.evaluate(() => window.pliant.welcome.session.hoses.length);
      const lower = nHoses - 1;
      const nodesBefore = await settled(page, lower);
      const k = nodesBefore.length - 2;
      // right controller onto a node of the lower hose, left onto the upper hose's middle
      const target = {
        right: await page.evaluate(([p]) => window.pliant.threeOf(p), [nodesBefore[k]]),
        left: null,
      };
      if (nHoses > 1) {
        const upper = await page.evaluate(() => window.pliant.hoseNodes(0));
        target.left = await page.evaluate(([p]) => window.pliant.threeOf(p), [upper[Math.floor(upper.length / 2) + 2]]);
      }
      await page.evaluate((t) => {
        const d = window.pliantXrDevice;
        for (const side of ['left', 'right']) {
          if (t[side] === null) continue;
          d.controllers[side].position.set(...t[side]);
        }
      }, target);
      await framesDrawn(page, 5);
      // the grip sits at an offset from the controller's origin: correct for it once
      const offsets = await page.evaluate((t) => {
        const d = window.pliantXrDevice;
        const grips = window.pliant.xrGrips();
        const out = {};
        for (const side of ['left', 'right']) {
          if (t[side] === null) continue;
          const g = grips.reduce((a, b) => (Math.hypot(...a.position.map((x, i) => x - t[side][i])) < Math.hypot(...b.position.map((x, i) => x - t[side][i])) ? a : b));
          out[side] = g.position.map((x, i) => t[side][i] - x);
          const p = d.controllers[side].position;
          d.controllers[side].position.set(p.x + out[side][0], p.y + out[side][1], p.z + out[side][2]);
        }
        return out;
      }, target);
      await framesDrawn(page, 5);
      // the grips are where the test put them (XR space = three.js space)
      const grips = await page.evaluate(() => window.pliant.xrGrips());
      void offsets;
      const placed = grips.map((g) => Math.min(...Object.values(target).filter(Boolean).map((t) => dist(g.position, t))));
      assert.ok(placed.every((d) => d < 0.05), `grips at ${JSON.stringify(grips)}, wanted ${JSON.stringify(target)}`);
      // the right controller's A button: its grip goes from firm to axial (the left keeps firm)
      await page.evaluate(() => window.pliantXrDevice.controllers.right.updateButtonValue('a-button', 1));
      await page.waitForFunction(() => window.pliant.xrGripChoices.includes('axial'));
      await page.evaluate(() => window.pliantXrDevice.controllers.right.updateButtonValue('a-button', 0));
      await framesDrawn(page, 3);
      assert.deepEqual((await page.evaluate(() => window.pliant.xrGripChoices)).sort(), ['axial', 'firm']);
      // squeeze both
      await page.evaluate((t) => {
        for (const side of ['left', 'right']) if (t[side] !== null) window.pliantXrDevice.controllers[side].updateButtonValue('squeeze', 1);
      }, target);
      const ids = await page.evaluate(() => window.pliant.xrHandIds);
      const wanted = target.left === null ? 1 : 2;
      await page.waitForFunction(
        ([ids, n]) => (window.pliant.snapshot?.hands ?? []).filter((h) => ids.includes(h.hand_id)).length === n,
        [ids, wanted],
      );
      // move the right controller up 15 cm and sideways 10 cm
      await page.evaluate((t) => {
        const c = window.pliantXrDevice.controllers.right;
        c.position.set(c.position.x + 0.1, c.position.y + 0.15, c.position.z);
      }, target);
      await page.waitForFunction(
        ([ids]) => (window.pliant.snapshot?.hands ?? []).some((h) => ids.includes(h.hand_id) && Math.hypot(...h.force) > 0.1),
        [ids],
      );
      await nodeMoved(page, lower, k, nodesBefore[k], 0.05);
      const nodesAfter = await page.evaluate((h) => window.pliant.hoseNodes(h), lower);
      assert.ok(dist(nodesBefore[k], nodesAfter[k]) > 0.05, `grabbed node moved ${dist(nodesBefore[k], nodesAfter[k])} m`);
      const hands = await page.evaluate(() => window.pliant.snapshot.hands);
      assert.ok(hands.some((h) => h.hose === lower), JSON.stringify(hands));
      // the grip chosen on the controller reached the server
      assert.equal(hands.find((h) => h.hose === lower).grip, 'axial', JSON.stringify(hands));
      if (target.left !== null) assert.equal(hands.find((h) => h.hose !== lower).grip, 'firm');
      // release both
      await page.evaluate(() => {
        for (const side of ['left', 'right']) window.pliantXrDevice.controllers[side].updateButtonValue('squeeze', 0);
      });
      await page.waitForFunction(([ids]) => !(window.pliant.snapshot?.hands ?? []).some((h) => ids.includes(h.hand_id)), [ids]);
    } finally {
      await page.close();
    }
  });
});

describe('panel', () => {
  test('the ergonomic profile is selectable and the limits follow it', async () => {
    const { page } = await openViewer(browser, server.url, LOW);
    try {
      const before = await page.evaluate(() => window.pliant.snapshot.ergonomics);
      const other = before.population === 'women' ? 'men' : 'women';
      await page.selectOption('#population', other);
      await page.selectOption('#posture', 'sitting');
      await page.waitForFunction(
        (o) => window.pliant.snapshot.ergonomics.population === o && window.pliant.snapshot.ergonomics.push_posture === 'sitting',
        other,
      );
      // a held hand is judged against the new limits: the pull limit changes with them
      const nodes = await page.evaluate(() => window.pliant.hoseNodes(window.pliant.welcome.session.hoses.length - 1));
      const id = await page.evaluate(() => window.pliant.mouseHandId);
      await page.evaluate(([p, id]) => window.pliant.send({ type: 'grab', hand_id: id, position: p }), [nodes[nodes.length - 1], id]);
      await page.waitForFunction((id) => window.pliant.snapshot.hands.some((h) => h.hand_id === id && h.force_limit > 0), id);
      const limitA = await page.evaluate((id) => window.pliant.snapshot.hands.find((h) => h.hand_id === id).torque_limit, id);
      await page.selectOption('#population', before.population);
      await page.waitForFunction(
        ([id, l]) => window.pliant.snapshot.hands.some((h) => h.hand_id === id && h.torque_limit !== l),
        [id, limitA],
      );
      await page.evaluate((id) => window.pliant.send({ type: 'release', hand_id: id }), id);
      // a bad value comes back as an error
      await page.evaluate(() => window.pliant.send({ type: 'set_ergonomics', posture: 'lying' }));
      await page.waitForFunction(() => window.pliant.errors.some((e) => e.code === 'invalid_value' && /posture/.test(e.message)));
      await page.selectOption('#posture', before.push_posture);
    } finally {
      await page.close();
    }
  });

  test('opening a scene file loads it; a broken one reports the loader error and the session keeps running', async () => {
    const { page } = await openViewer(browser, server.url, LOW);
    try {
      const oldName = await page.evaluate(() => window.pliant.welcome.session.scene);
      // broken: the loader's message comes back, the old scene stays
      await page.setInputFiles('#open-scene', { name: 'broken.toml', mimeType: 'text/plain', buffer: Buffer.from('format = "pliant-scene"\nversion = 1\nname = 3\n') });
      await page.waitForFunction(() => window.pliant.errors.some((e) => e.code === 'invalid_scene'));
      const err = await page.evaluate(() => window.pliant.errors.find((e) => e.code === 'invalid_scene').message);
      assert.match(err, /broken\.toml/);
      assert.match(await page.textContent('#message'), /invalid_scene/);
      const t0 = await page.evaluate(() => window.pliant.snapshot.time);
      await page.waitForFunction((t) => window.pliant.snapshot.time > t, t0);
      assert.equal(await page.evaluate(() => window.pliant.welcome.session.scene), oldName);
      // a good one: examples/demo.toml (one hose)
      const file = path.join(repo, 'examples', 'demo.toml');
      const wanted = /name = "([^"]+)"/.exec(readFileSync(file, 'utf8'))[1];
      await page.setInputFiles('#open-scene', file);
      await page.waitForFunction((n) => window.pliant.welcome?.session.scene === n && window.pliant.shown !== null, wanted);
      assert.equal(await page.evaluate(() => window.pliant.welcome.session.hoses.length), 1);
      await page.waitForFunction(() => window.pliant.shown.hoses.length === 1);
      // back to the demo for the other tests
      await page.setInputFiles('#open-scene', path.join(repo, 'examples', 'engine_bay.toml'));
      await page.waitForFunction((n) => window.pliant.welcome?.session.scene === n, oldName);
    } finally {
      await page.close();
    }
  });

  test('the Report button writes the session report on the server, replayed from its input log', async () => {
    const { page } = await openViewer(browser, server.url, LOW);
    try {
      await resetSession(page);
      const id = await page.evaluate(() => window.pliant.mouseHandId);
      const nodes = await page.evaluate(() => window.pliant.hoseNodes(window.pliant.welcome.session.hoses.length - 1));
      const end = nodes[nodes.length - 1];
      await page.evaluate(([p, id]) => {
        window.pliant.send({ type: 'grab', hand_id: id, position: p });
        window.pliant.send({ type: 'move', hand_id: id, position: [p[0], p[1], p[2] + 0.05] });
      }, [end, id]);
      await page.waitForFunction((id) => window.pliant.snapshot.hands.some((h) => h.hand_id === id), id);
      await simulated(page, 0.3);
      const before = await page.evaluate(() => window.pliant.reports.length);
      await page.click('#report');
      await page.waitForFunction((n) => window.pliant.reports.length > n, before);
      const folder = await page.evaluate(() => window.pliant.reports[window.pliant.reports.length - 1]);
      const dir = path.isAbsolute(folder) ? folder : path.join(repo, folder);
      for (const f of ['report.html', 'report.json', 'summary.json', 'hands.csv', 'inputs.jsonl']) {
        assert.ok(existsSync(path.join(dir, f)), `${f} in ${dir}`);
      }
      const report = JSON.parse(readFileSync(path.join(dir, 'report.json'), 'utf8'));
      assert.ok(report.run.hand_peaks.some((h) => h.hand === id), 'the report judges the hand that acted');
      await page.evaluate((id) => window.pliant.send({ type: 'release', hand_id: id }), id);
    } finally {
      await page.close();
    }
  });

  test('a recorded session downloads as JSON and replays', async () => {
    const { page } = await openViewer(browser, server.url, LOW);
    try {
      await resetSession(page);
      await page.click('#record');
      const received = await page.evaluate(() => window.pliant.snapshots);
      const id = await page.evaluate(() => window.pliant.mouseHandId);
      const nodes = await page.evaluate(() => window.pliant.hoseNodes(window.pliant.welcome.session.hoses.length - 1));
      const end = nodes[nodes.length - 1];
      await page.evaluate(([p, id]) => {
        window.pliant.send({ type: 'grab', hand_id: id, position: p });
        window.pliant.send({ type: 'move', hand_id: id, position: [p[0], p[1], p[2] + 0.15] });
      }, [end, id]);
      // recorded: more than 10 snapshots, the newest with the hand lifting the hose
      await page.waitForFunction(
        ([n, id]) => window.pliant.snapshots > n + 20 && window.pliant.snapshot.hands.some((h) => h.hand_id === id),
        [received, id],
      );
      await simulated(page, 0.5);
      const download = page.waitForEvent('download');
      await page.click('#record');
      const file = await (await download).path();
      const rec = JSON.parse(readFileSync(file, 'utf8'));
      assert.equal(rec.format, 'pliant-recording');
      assert.ok(rec.frames.length > 10, `${rec.frames.length} frames`);
      assert.ok(rec.frames.some((f) => f.snapshot.hands.some((h) => h.hand_id === id)), 'the hand is in the recording');
      await page.evaluate((id) => window.pliant.send({ type: 'release', hand_id: id }), id);
      // replay the file: the viewer shows the recorded snapshots, not the live ones
      await page.setInputFiles('#replay-file', file);
      await page.waitForFunction(() => window.pliant.replaying);
      const recordedTimes = rec.frames.map((f) => f.snapshot.time);
      await page.waitForFunction(
        ([lo, hi]) => window.pliant.shown && window.pliant.shown.time >= lo && window.pliant.shown.time <= hi && window.pliant.shown.hands.length > 0,
        [Math.min(...recordedTimes), Math.max(...recordedTimes)],
      );
      assert.ok(await page.isVisible('#replay-bar'));
      // paused at the end of the recording, a click on a finding with a time goes back to
      // the first recorded snapshot at or after that time
      await page.click('#replay-play');
      await page.$eval('#replay-slider', (el) => { el.value = '1000'; el.dispatchEvent(new Event('input')); });
      const last = rec.frames[rec.frames.length - 1].snapshot.time;
      await page.waitForFunction((t) => window.pliant.shown.time === t, last);
      // the earliest finding
      const times = await page.$$eval('#findings .finding[data-time]', (rows) => rows.map((r) => Number(r.dataset.time)));
      assert.ok(times.length > 0, 'findings with a time');
      const findingTime = Math.min(...times);
      const k = rec.frames.findIndex((f) => f.snapshot.time >= findingTime);
      const sameInstant = rec.frames.filter((f) => f.t === rec.frames[k].t).map((f) => f.snapshot.time);
      assert.ok(!sameInstant.includes(last), `the finding (t = ${findingTime} s) is before the recording's end (${last} s)`);
      await page.locator(`#findings .finding[data-time="${findingTime}"]`).first().click();
      await page.waitForFunction((ts) => ts.includes(window.pliant.shown.time), sameInstant);
      assert.equal(await page.evaluate(() => window.pliant.mode), 'replay');
      await page.click('#live');
      await page.waitForFunction(() => !window.pliant.replaying && window.pliant.shown !== null);
      assert.equal(await page.evaluate(() => window.pliant.mode), 'live');
    } finally {
      await page.close();
    }
  });
});
