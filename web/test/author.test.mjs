// Scene authoring in the viewer (docs/authoring.md), end to end: from a
// scene with a part (a bench) and no hose of its own, the Author mode builds a hose route
// by clicking points on the part's surface with the mouse, picks its material, undoes and
// redoes, moves a point, adds a clip and a stub, shows the loader's error for a wrong
// section, saves (the TOML download), and the saved file — opened again in a freshly
// loaded page — runs: the hose exists and moves. Every wait is for a condition.

import assert from 'node:assert/strict';
import { mkdirSync, readFileSync } from 'node:fs';
import path from 'node:path';
import { after, before, describe, test } from 'node:test';
import { dist, launchBrowser, openViewer, repo, simulated, startServer } from './harness.mjs';

const FIXTURE = path.join(repo, 'web', 'test', 'fixtures', 'author_start.toml');
const LOW = { width: 1100, height: 760, query: '?quality=low' };
const TOP = 0.32; // the bench's top face [m]

let server;
let browser;

before(async () => {
  server = await startServer([FIXTURE]);
  browser = await launchBrowser();
});

after(async () => {
  await browser?.close();
  await server?.stop();
});


/** A real mouse click on the screen position of world point `p`. */
async function clickAt(page, p) {
  const at = await page.evaluate((p) => window.pliant.screenOf(p), p);
  await page.mouse.click(at.x, at.y);
}

const nPoints = (page) => page.evaluate(() => window.pliant.author.points(0).length);

describe('author mode', () => {
  test('builds a hose route from nothing, saves it, and the saved scene runs', async () => {
    let { page, logs } = await openViewer(browser, server.url, LOW);
    try {
      await page.click('#author-mode');
      await page.waitForFunction(() => window.pliant.author.active && window.pliant.author.state !== null);
      // from nothing: the bench stays, the scene's own hose goes
      await page.click('#author-clear');
      await page.waitForFunction(() => window.pliant.author.state.base.hoses.length === 0 && window.pliant.author.state.hoses.length === 0);
      await page.selectOption('#author-material', 'hose4');
      assert.equal(await page.inputValue('#author-d-outer'), '15');
      await page.click('#tool-hose');
      // four clicks on the bench's top face
      const clicks = [[-0.2, -0.05, TOP], [0, 0.05, TOP], [0.2, -0.05, TOP], [0.26, 0.08, TOP]];
      for (let i = 0; i < clicks.length; i++) {
        await clickAt(page, clicks[i]);
        await page.waitForFunction((n) => window.pliant.author.points(0).length === n, i + 1);
      }
      const pts = await page.evaluate(() => window.pliant.author.points(0));
      // each point lies on the surface lifted by the hose's outer radius (7.5 mm)
      for (let i = 0; i < clicks.length; i++) {
        const want = [clicks[i][0], clicks[i][1], TOP + 0.0075];
        assert.ok(dist(pts[i], want) < 0.002, `point ${i} at ${pts[i]}, wanted ${want}`);
      }
      // undo and redo, by keyboard and by buttons
      await page.keyboard.press('Control+z');
      await page.waitForFunction(() => window.pliant.author.points(0).length === 3);
      await page.keyboard.press('Control+Shift+z');
      await page.waitForFunction(() => window.pliant.author.points(0).length === 4);
      await page.click('#author-undo');
      await page.waitForFunction(() => window.pliant.author.points(0).length === 3);
      assert.ok(await page.evaluate(() => window.pliant.author.canRedo));
      await page.click('#author-redo');
      await page.waitForFunction(() => window.pliant.author.points(0).length === 4);
      await page.click('#author-undo');
      await page.waitForFunction(() => window.pliant.author.points(0).length === 3);
      await page.keyboard.press('Enter'); // finish the hose
      // move the last point out beyond the bench's edge (what dragging its handle does):
      // the end will hang over the edge
      await page.click('#tool-move');
      const last = (await page.evaluate(() => window.pliant.author.points(0)))[2];
      await clickAt(page, last); // selects the handle (the gizmo appears on it)
      await page.waitForFunction(() => window.pliant.author.state !== null);
      await page.evaluate(() => window.pliant.author.movePoint(0, 2, [0.42, 0.0, 0.36]));
      await page.waitForFunction(() => window.pliant.author.points(0)[2][0] > 0.4);
      await page.keyboard.press('Control+z');
      await page.waitForFunction(() => window.pliant.author.points(0)[2][0] < 0.3);
      await page.keyboard.press('Control+Shift+z');
      await page.waitForFunction(() => window.pliant.author.points(0)[2][0] > 0.4);
      // a rotating clip on the route and a stub beside the start
      await page.click('#tool-clip');
      await page.selectOption('#author-clip-type', 'rotating');
      await clickAt(page, [-0.1, 0.0, TOP]);
      await page.waitForFunction(() => window.pliant.author.state.clips.length === 1);
      const clip = await page.evaluate(() => window.pliant.author.state.clips[0]);
      assert.equal(clip.type, 'rotating');
      assert.equal(clip.hose, 'hose1');
      assert.ok(Math.abs(clip.opening[2] - 1) < 1e-6, `opening along the top face's normal: ${clip.opening}`);
      assert.ok(Math.abs(clip.orientation[2]) < 1e-6, 'the clip lies along the hose, in the surface');
      await page.click('#tool-stub');
      await clickAt(page, [-0.27, 0.12, TOP]);
      await page.waitForFunction(() => window.pliant.author.state.stubs.length === 1);
      const stub = await page.evaluate(() => window.pliant.author.state.stubs[0]);
      assert.deepEqual(stub.axis.map((x) => Math.round(x) + 0), [0, 0, -1], 'axis into the surface');
      assert.equal(stub.end, 'start');
      await page.click('#tool-hose');
      // "along a CAD curve": with snapping on, a click 3 mm from the bench's front edge
      // lands on the edge (then undone)
      await page.check('#author-snap');
      await clickAt(page, [0.1, -0.147, TOP]);
      await page.waitForFunction(() => window.pliant.author.state.hoses.length === 2);
      const snapped = await page.evaluate(() => window.pliant.author.points(1)[0]);
      assert.ok(Math.abs(snapped[1] + 0.15) < 1e-4 && Math.abs(snapped[2] - (TOP + 0.0075)) < 1e-4, `snapped to the edge: ${snapped}`);
      assert.ok(Math.abs(snapped[0] - 0.1) < 0.01, `along the edge: ${snapped}`);
      await page.keyboard.press('Control+z');
      await page.waitForFunction(() => window.pliant.author.state.hoses.length === 1 && window.pliant.author.state.clips.length === 1);
      await page.uncheck('#author-snap');
      // a screenshot of the mode for people (docs/authoring.md)
      const dir = path.join(repo, 'target', 'e2e');
      mkdirSync(dir, { recursive: true });
      await page.screenshot({ path: path.join(dir, 'author.png') });

      // a wrong section: the loader's error, naming the field, is shown in the page
      await page.fill('#author-d-inner', '20');
      await page.dispatchEvent('#author-d-inner', 'change');
      await page.waitForFunction(() => window.pliant.author.state.hoses[0].section?.d_inner === 0.02);
      await page.fill('#author-name', 'bench route');
      await page.click('#author-save');
      await page.waitForFunction(() => /refused/.test(document.querySelector('#author-message').textContent));
      const msg = await page.textContent('#author-message');
      assert.match(msg, /bench_route\.toml/);
      assert.match(msg, /hoses\[0\]\.section\.d_inner = 20 mm/);
      assert.equal(await page.evaluate(() => window.pliant.welcome.session.scene), 'Authoring bench', 'the old session runs on');

      // the library section again, then save: the download is the scene file
      await page.selectOption('#author-material', 'hose4');
      await page.waitForFunction(() => window.pliant.author.state.hoses[0].section === null);
      const download = page.waitForEvent('download');
      await page.click('#author-save');
      const file = await (await download).path();
      const toml = readFileSync(file, 'utf8');
      assert.equal(toml, await page.evaluate(() => window.pliant.author.lastToml));
      assert.match(toml, /\[\[hoses\]\]\nname = "hose1"\nmaterial = "hose4"\nstart = \[/);
      const start = JSON.parse(/\nstart = (\[[^\]]*\])/.exec(toml)[1]);
      assert.ok(dist(start, [-200, -50, 327.5]) < 0.01, `start = ${start} (mm)`);
      const spline = /spline = \{ through = \[(\[[^\]]*\])\], to = \[420, 0, 360\] \}/.exec(toml);
      assert.ok(spline !== null, toml);
      assert.ok(dist(JSON.parse(spline[1]), [0, 50, 327.5]) < 0.01, spline[1]);
      assert.match(toml, /\[\[parts\]\]\nname = "bench"/);
      assert.match(toml, /type = "rotating"/);
      assert.match(toml, /action = "fix"\nhose = "hose1"\nnode = 0/);
      assert.doesNotMatch(toml, /placeholder/);
      // ... and it runs in the session
      await page.waitForFunction(() => window.pliant.welcome.session.scene === 'bench route' && window.pliant.shown !== null);
      await page.waitForFunction(() => /running/.test(document.querySelector('#author-message').textContent));
      assert.deepEqual(await page.evaluate(() => window.pliant.welcome.session.hoses.map((h) => h.name)), ['hose1']);
      assert.equal(await page.evaluate(() => window.pliant.welcome.session.fasteners.length), 2);
      await page.close();

      // a fresh page; the session back at the bench; the saved file opened from disk
      ({ page, logs } = await openViewer(browser, server.url, LOW));
      await page.setInputFiles('#open-scene', FIXTURE);
      await page.waitForFunction(() => window.pliant.welcome.session.scene === 'Authoring bench' && window.pliant.shown?.hoses.length === 1);
      await page.setInputFiles('#open-scene', { name: 'bench_route.toml', mimeType: 'text/plain', buffer: Buffer.from(toml) });
      await page.waitForFunction(() => window.pliant.welcome.session.scene === 'bench route' && window.pliant.shown !== null);
      assert.deepEqual(await page.evaluate(() => window.pliant.welcome.session.hoses.map((h) => h.name)), ['hose1']);
      // it moves: the end drawn at [420, 0, 360] mm, beyond the bench's edge, falls
      // (compared with where it was drawn: the machine may be slow to show the first
      // snapshots, by when the hose may have come to rest); the start is fixed
      await page.waitForFunction(() => {
        const n = window.pliant.hoseNodes(0);
        const e = n[n.length - 1];
        return e !== undefined && Math.hypot(e[0] - 0.42, e[1], e[2] - 0.36) > 0.01 && e[2] < 0.35;
      });
      const n1 = await page.evaluate(() => window.pliant.hoseNodes(0));
      assert.ok(dist(n1[0], pts[0]) < 0.003, `the fixed start stays at the first click: ${n1[0]}`);
      // and it is simulated live: a hand lifts its end by 10 cm
      const id = await page.evaluate(() => window.pliant.mouseHandId);
      const end = n1[n1.length - 1];
      await page.evaluate(([p, id]) => {
        window.pliant.send({ type: 'grab', hand_id: id, position: p });
        window.pliant.send({ type: 'move', hand_id: id, position: [p[0], p[1], p[2] + 0.1] });
      }, [end, id]);
      await page.waitForFunction((z) => {
        const n = window.pliant.hoseNodes(0);
        return n[n.length - 1][2] > z + 0.05;
      }, end[2]);
      await page.evaluate((id) => window.pliant.send({ type: 'release', hand_id: id }), id);
      await simulated(page, 0.1);
      assert.ok(!logs.some((l) => l.startsWith('pageerror')), logs.join('\n'));
      // back to the bench for whoever comes next
      await page.setInputFiles('#open-scene', FIXTURE);
      await page.waitForFunction(() => window.pliant.welcome.session.scene === 'Authoring bench');
    } finally {
      await page.close();
    }
  });
});
