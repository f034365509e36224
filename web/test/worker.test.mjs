// End-to-end test of the worker in the viewer and of AR: `pliant serve` (the real binary)
// on a scene with a `[worker]` (test/fixtures/worker_bar.toml) standing behind a bar that reaches into his trunk. A hand
// grabbing the hose poses the worker on the server; the viewer draws his capsules (the
// trunk red: it is inside the bar), follows the hand as it moves, and lists reach and the
// posture scores in the panel. The emulated headset (iwer) offers `immersive-ar`: the
// viewer enters it, drops its own backdrop, stands the scene on the real floor, and a
// controller grabs a hose as in VR; the emulator has no surfaces to hit (no synthetic
// environment), so the floor placement stays and the table placement is driven directly. Every wait is for a condition (HANG_GUARD_MS only
// stops a hung test); nothing depends on the machine's speed.

import assert from 'node:assert/strict';
import path from 'node:path';
import { describe, test } from 'node:test';
import { framesDrawn, openViewer, repo, sharedSession } from './harness.mjs';

const scene = path.join(repo, 'web', 'test', 'fixtures', 'worker_bar.toml');

const shared = sharedSession([scene]);
const END = [0.5, -0.25, 1.1];

describe('worker and AR', () => {
  test('a hand on the hose poses the worker: capsules drawn, the trunk red in the bar, the panel scores him', async () => {
    const { page, logs } = await openViewer(shared.browser, shared.server.url, { width: 900, height: 600, query: '?quality=low' });
    try {
      const w = await page.evaluate(() => window.pliant.welcome.session.worker);
      assert.equal(w.who, 'the 50th-percentile man');
      assert.equal(w.segments.length, 14);
      const id = await page.evaluate(() => window.pliant.mouseHandId);
      assert.ok(await page.evaluate(([id, p]) => window.pliant.send({ type: 'grab', hand_id: id, position: p }), [id, END]));
      // the worker stands where the scene placed him from the start: wait until his right
      // arm follows the grabbing hand, not only until he is drawn
      await page.waitForFunction(
        (id) => window.pliant.manikin().visible && window.pliant.manikin().capsules.length === 14 && window.pliant.manikin().lines.includes('right arm: hand ' + id + ' reached'),
        id,
      );
      const m = await page.evaluate(() => window.pliant.manikin());
      const trunk = m.capsules.find((c) => c.segment === 'trunk');
      assert.equal(trunk.contact?.name, 'bar', JSON.stringify(trunk));
      // where he stands, as the scene placed him (no steps in this scene)
      const posed = await page.evaluate(() => window.pliant.snapshot.worker);
      assert.deepEqual(posed.stance, { position: [0, 0, 0], forward: [1, 0, 0] });
      assert.equal(posed.steps, 0);
      // the trunk's axis is the vertical through the feet: 90 mm from the bar's face
      assert.ok(Math.abs(trunk.contact.depth - (w.radii[2] - 0.09)) < 1e-6, JSON.stringify(trunk));
      assert.ok(m.lines[0].startsWith('the 50th-percentile man at t = ') && /RULA \d, REBA \d+/.test(m.lines[0]), m.lines.join('\n'));
      assert.ok(m.lines.includes('right arm: hand ' + id + ' reached'), m.lines.join('\n'));
      assert.ok(m.lines.includes(`trunk ${(1e3 * trunk.contact.depth).toFixed(0)} mm inside 'bar'`), m.lines.join('\n'));
      // the right forearm ends at the wrist, near the hand
      const before = await page.evaluate(() => window.pliant.manikin().capsules.find((c) => c.segment === 'right forearm').b);
      assert.ok(Math.hypot(...before.map((x, i) => x - END[i])) < 0.15, `wrist ${before}`);
      // the hand heads 150 mm up (the hose, fixed 200 mm away, lets it rise part of
      // that): the drawn wrist follows
      assert.ok(await page.evaluate(([id, p]) => window.pliant.send({ type: 'move', hand_id: id, position: [p[0], p[1], p[2] + 0.15] }), [id, END]));
      await page.waitForFunction((z) => window.pliant.manikin().capsules.find((c) => c.segment === 'right forearm').b[2] > z + 0.05, before[2]);
      assert.ok(!logs.some((l) => l.startsWith('pageerror')), logs.join('\n'));
      await page.evaluate((id) => window.pliant.send({ type: 'release', hand_id: id }), id);
    } finally {
      await page.close();
    }
  });

  test('the emulated headset offers AR: the scene stands on the real floor and a controller grabs the hose', async () => {
    const { page, logs } = await openViewer(shared.browser, shared.server.url, { width: 900, height: 600, query: '?xr=emulate&quality=low' });
    try {
      await page.locator('#enter-ar:not([disabled])').waitFor();
      assert.equal(await page.textContent('#enter-ar'), 'Enter AR');
      await page.click('#enter-ar');
      await page.waitForFunction(() => window.pliant.inVr && window.pliant.xrMode === 'immersive-ar').catch((e) => {
        throw new Error(`${e.message}\n${logs.join('\n')}`);
      });
      assert.equal(await page.evaluate(() => window.pliant.backgroundShown), false);
      assert.ok(Math.abs(await page.evaluate(() => window.pliant.sceneLowest)) < 1e-6, 'the lowest point on the floor');
      // the right controller's grip onto the hose's middle node (its grip sits at an
      // offset from the controller's origin: corrected once)
      const nodes = await page.evaluate(() => window.pliant.hoseNodes(0));
      const target = await page.evaluate(([p]) => window.pliant.threeOf(p), [nodes[Math.floor(nodes.length / 2)]]);
      await page.evaluate((t) => window.pliantXrDevice.controllers.right.position.set(...t), target);
      await framesDrawn(page, 5);
      await page.evaluate((t) => {
        const grips = window.pliant.xrGrips();
        const g = grips.reduce((a, b) => (Math.hypot(...a.position.map((x, i) => x - t[i])) < Math.hypot(...b.position.map((x, i) => x - t[i])) ? a : b));
        const c = window.pliantXrDevice.controllers.right.position;
        c.set(c.x + t[0] - g.position[0], c.y + t[1] - g.position[1], c.z + t[2] - g.position[2]);
      }, target);
      await framesDrawn(page, 5);
      const ids = await page.evaluate(() => window.pliant.xrHandIds);
      await page.evaluate(() => window.pliantXrDevice.controllers.right.updateButtonValue('squeeze', 1));
      await page.waitForFunction((ids) => (window.pliant.snapshot?.hands ?? []).some((h) => ids.includes(h.hand_id) && h.hose === 0), ids);
      await page.evaluate(() => window.pliantXrDevice.controllers.right.updateButtonValue('squeeze', 0));
      await page.waitForFunction((ids) => !(window.pliant.snapshot?.hands ?? []).some((h) => ids.includes(h.hand_id)), ids);
      // the emulated device offers `hit-test` but, without a synthetic environment (IWER's
      // SEM), no surface: the scene stays on the floor; standing it on a surface as select
      // on the reticle does puts its lowest point there
      await page.waitForFunction(() => window.pliant.xrHitTest === 'unavailable');
      assert.ok(Math.abs(await page.evaluate(() => window.pliant.sceneLowest)) < 1e-6, 'still on the floor');
      await page.evaluate(() => window.pliant.xrStandOn([0.2, 0.75, -1.0]));
      assert.ok(Math.abs((await page.evaluate(() => window.pliant.sceneLowest)) - 0.75) < 1e-6, 'on the table');
      assert.ok(!logs.some((l) => l.startsWith('pageerror')), logs.join('\n'));
      // leaving AR brings the backdrop back
      await page.evaluate(() => document.getElementById('enter-ar').click());
      await page.waitForFunction(() => !window.pliant.inVr && window.pliant.backgroundShown);
    } finally {
      await page.close();
    }
  });
});
