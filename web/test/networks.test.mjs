// End-to-end test of drawing harness networks in the viewer: `pliant serve` (the real
// binary) on a tee — three hoses joined by a junction body whose outlets lie apart, one
// hose under tape with a corrugated tube over part of it. The protections are drawn over
// their stretches and the body at its outlets, following them as the tee sags and in a
// replay. Every wait is for a condition (HANG_GUARD_MS only stops a hung test); nothing
// depends on the machine's speed.

import assert from 'node:assert/strict';
import { mkdtempSync, writeFileSync } from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { describe, test } from 'node:test';
import { dist, openViewer, sharedSession } from './harness.mjs';

const dir = mkdtempSync(path.join(os.tmpdir(), 'pliant-networks-'));
const scene = path.join(dir, 'tee.toml');
writeFileSync(scene, `
format = "pliant-scene"
version = 1
length_unit = "mm"

[[hoses]]
name = "a"
material = "hose1"
section = { d_inner = 0, d_outer = 10 }
elements = 12
start = [-300, 0, 400]
path = [{ line = { to = [-15, 0, 400] } }]
spans = [{ from = 60, to = 240, min_bend_radius = 60, section = { d_inner = 0, d_outer = 14 } }]
protections = [{ kind = "tape", from = 0, to = 285 }, { kind = "corrugated_tube", from = 60, to = 240 }]

[[hoses]]
name = "b"
material = "hose1"
section = { d_inner = 0, d_outer = 10 }
elements = 12
start = [15, 0, 400]
path = [{ line = { to = [300, 0, 400] } }]

[[hoses]]
name = "c"
material = "hose1"
section = { d_inner = 0, d_outer = 10 }
elements = 12
start = [0, -15, 400]
path = [{ line = { to = [0, -300, 400] } }]

[[junctions]]
name = "tee"
ends = [{ hose = "a", end = "end" }, { hose = "b", end = "start" }, { hose = "c", end = "start" }]
body = { mass_kg = 0.05 }

[[timeline]]
action = "fix"
hose = "a"
node = 0

[[timeline]]
action = "fix"
hose = "b"
node = -1

[[timeline]]
action = "fix"
hose = "c"
node = -1
`);

const shared = sharedSession([scene]);


describe('networks', () => {
  test('protections are drawn over their stretches and the junction body at its outlets', async () => {
    const { page } = await openViewer(shared.browser, shared.server.url, { width: 800, height: 600, query: '?quality=low' });
    try {
      const session = await page.evaluate(() => window.pliant.welcome.session);
      const a = session.hoses[0];
      assert.ok(Math.abs(a.length - 0.285) < 1e-9, `length ${a.length}`);
      assert.deepEqual(
        a.protections.map((p) => [p.kind, Math.round(p.from * 1e6) / 1e6, Math.round(p.to * 1e6) / 1e6]),
        [['tape', 0, 0.285], ['corrugated_tube', 0.06, 0.24]],
      );
      assert.deepEqual(session.hoses[1].protections, []);
      assert.equal(session.junction_bodies.length, 1);
      assert.deepEqual(session.junction_bodies[0].outlets, [{ hose: 0, node: 12 }, { hose: 1, node: 0 }, { hose: 2, node: 0 }]);

      // the two protections of hose a are drawn, the tube over the middle of the hose
      const covers = await page.evaluate(() => window.pliant.objects('protection:'));
      assert.deepEqual(covers.map((c) => c.name).sort(), ['protection:a:corrugated_tube', 'protection:a:tape']);
      const tube = covers.find((c) => c.name.endsWith('corrugated_tube'));
      const tape = covers.find((c) => c.name.endsWith('tape'));
      assert.ok(tube.vertices > 0 && tube.vertices < tape.vertices, `${tube.vertices} vs ${tape.vertices}`);
      // the tube covers 60 … 240 mm of hose a (from x = −300 mm): its middle is at x ≈ −150 mm
      assert.ok(Math.abs(tube.centre[0] + 0.15) < 0.01, `tube centre ${tube.centre}`);

      // the body: a hub and three arms, at the mean of its outlet nodes in the shown snapshot
      const hubAtOutlets = () =>
        page.evaluate(() => {
          const s = window.pliant.shown;
          const body = window.pliant.welcome.session.junction_bodies[0];
          const pts = body.outlets.map((o) => s.hoses[o.hose].positions[o.node]);
          const mean = [0, 1, 2].map((d) => pts.reduce((m, p) => m + p[d], 0) / pts.length);
          const hub = window.pliant.objects('junction:tee').find((o) => o.name === 'junction:tee');
          return { mean, hub: hub.centre, parts: window.pliant.objects('junction:tee').length, time: s.time };
        });
      await page.waitForFunction(() => window.pliant.frames > 2);
      const first = await hubAtOutlets();
      assert.equal(first.parts, 4, 'hub and three arms');
      assert.ok(dist(first.mean, first.hub) < 1e-4, `hub ${first.hub} vs outlets ${first.mean}`);
      // the tee sags under gravity (23 mm at rest, from the outlets' drawn height of
      // 400 mm): the body follows its outlets down. The session may have run for a while
      // before the page opened, so the sag is measured from the scene, not from `first`.
      await page.waitForFunction(() => {
        const hub = window.pliant.objects('junction:tee').find((o) => o.name === 'junction:tee');
        return hub.centre[2] < 0.4 - 0.005;
      });
      await page.waitForFunction((t) => window.pliant.shown.time > t && window.pliant.frames > 0, first.time);
      const later = await hubAtOutlets();
      assert.ok(later.time > first.time);
      assert.ok(dist(later.mean, later.hub) < 1e-4, `hub ${later.hub} vs outlets ${later.mean}`);

      // in a replay too: a recording whose last frame has the whole tee 0.1 m higher
      const liftedTime = await page.evaluate(() => {
        const s = window.pliant.shown;
        const lifted = { ...s, time: s.time + 1, hoses: s.hoses.map((h) => ({ ...h, positions: h.positions.map(([x, y, z]) => [x, y, z + 0.1]) })) };
        const frames = [{ t: 0, snapshot: s }, { t: 0.05, snapshot: lifted }];
        window.pliant.replay(JSON.stringify({ format: 'pliant-recording', version: 1, welcome: window.pliant.welcome, frames }));
        return lifted.time;
      });
      await page.waitForFunction((t) => window.pliant.replaying && window.pliant.shown?.time === t, liftedTime);
      await page.waitForFunction(() => window.pliant.frames > 0);
      const replayed = await hubAtOutlets();
      assert.ok(dist(replayed.mean, replayed.hub) < 1e-4, `replayed hub ${replayed.hub} vs outlets ${replayed.mean}`);
      assert.ok(replayed.hub[2] > later.hub[2] + 0.05, `${replayed.hub[2]} vs ${later.hub[2]}`);
      const replayedCovers = await page.evaluate(() => window.pliant.objects('protection:'));
      assert.equal(replayedCovers.length, 2);
    } finally {
      await page.close();
    }
  });
});
