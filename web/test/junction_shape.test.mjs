// End-to-end test of a junction body with a shape in the viewer: `pliant serve` (the real
// binary) on a tee whose body is a box part (`body = { …, part = "tee_box" }`), the two
// hoses fixed at their far ends so the tee sags. The viewer draws the box, not a hub, and
// the box rides on the body: its drawn centre stays on the mean of the body's outlet nodes
// as the tee sags, and it never shows where the part was drawn in the scene once the body
// has moved. Every wait is for a condition (HANG_GUARD_MS only stops a hung test).

import assert from 'node:assert/strict';
import { mkdtempSync, writeFileSync } from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { describe, test } from 'node:test';
import { dist, openViewer, sharedSession } from './harness.mjs';

const dir = mkdtempSync(path.join(os.tmpdir(), 'pliant-junction-shape-'));
const scene = path.join(dir, 'tee.toml');
writeFileSync(scene, `
format = "pliant-scene"
version = 1
length_unit = "mm"

[[hoses]]
name = "a"
material = "hose1"
elements = 8
start = [-300, 0, 400]
path = [{ line = { to = [-10, 0, 400] } }]

[[hoses]]
name = "b"
material = "hose1"
elements = 8
start = [10, 0, 400]
path = [{ line = { to = [300, 0, 400] } }]

[[parts]]
name = "tee_box"
box = { size = [20, 12, 12] }
position = [0, 0, 400]

[[junctions]]
name = "tee"
ends = [{ hose = "a", end = "end" }, { hose = "b", end = "start" }]
body = { mass_kg = 0.02, centre_of_mass = [0, 0, 400], inertia_kg_m2 = [4e-7, 9e-7, 9e-7], part = "tee_box" }

[[timeline]]
action = "fix"
hose = "a"
node = 0

[[timeline]]
action = "fix"
hose = "b"
node = -1
`);

const shared = sharedSession([scene]);


describe('junction shape', () => {
  test('a shaped junction body is drawn as its part and rides on its outlets', async () => {
    const { page } = await openViewer(shared.browser, shared.server.url, { width: 800, height: 600, query: '?quality=low' });
    try {
      const session = await page.evaluate(() => window.pliant.welcome.session);
      assert.equal(session.junction_bodies.length, 1);
      assert.equal(session.junction_bodies[0].shape, 0, 'the body names part 0 as its shape');
      // no hub or arms: the body is drawn as its part
      assert.deepEqual(await page.evaluate(() => window.pliant.objects('junction:')), []);

      const boxAtOutlets = () =>
        page.evaluate(() => {
          const s = window.pliant.shown;
          const body = window.pliant.welcome.session.junction_bodies[0];
          const pts = body.outlets.map((o) => s.hoses[o.hose].positions[o.node]);
          const mean = [0, 1, 2].map((d) => pts.reduce((m, p) => m + p[d], 0) / pts.length);
          const box = window.pliant.objects('part:tee_box');
          return { mean, box: box.map((b) => b.centre), visible: box.map((b) => b.visible), time: s.time };
        });
      // the tee sags under gravity: wait until the body is 5 mm below its drawn height
      await page.waitForFunction(() => {
        const s = window.pliant.shown;
        const o = window.pliant.welcome.session.junction_bodies[0].outlets[0];
        return s.hoses[o.hose].positions[o.node][2] < 0.4 - 0.005;
      });
      const first = await boxAtOutlets();
      await page.waitForFunction((t) => window.pliant.shown.time > t && window.pliant.frames > 0, first.time);
      const later = await boxAtOutlets();
      for (const seen of [first, later]) {
        assert.equal(seen.box.length, 1, 'one box drawn');
        assert.ok(seen.visible[0], 'the box is visible');
        // the box's drawn centre is the body's centre: the outlets' mean (they lie
        // symmetric about it), within the drawing's float precision
        assert.ok(dist(seen.mean, seen.box[0]) < 1e-4, `box ${seen.box[0]} vs outlets ${seen.mean} at t = ${seen.time}`);
        assert.ok(seen.box[0][2] < 0.4 - 0.005, `the box went down with the body: ${seen.box[0]}`);
      }
    } finally {
      await page.close();
    }
  });
});
