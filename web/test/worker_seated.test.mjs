// End-to-end test of the seated worker in the viewer: `pliant serve` (the real binary) on
// a scene with a seated `[worker]` (test/fixtures/worker_seated.toml). A hand grabbing
// the hose's end at table height poses him on the server; the viewer draws his capsules
// with the thighs level over a grey seat box whose top is at the seat height, and the
// panel says he sits. Every wait is for a condition (HANG_GUARD_MS only stops a hung
// test); nothing depends on the machine's speed.

import assert from 'node:assert/strict';
import path from 'node:path';
import { describe, test } from 'node:test';
import { openViewer, repo, sharedSession } from './harness.mjs';

const scene = path.join(repo, 'web', 'test', 'fixtures', 'worker_seated.toml');

const shared = sharedSession([scene]);
const END = [0.45, -0.2, 0.72];

describe('seated worker', () => {
  test('a seated worker is drawn on his seat, thighs level, and the panel says he sits', async () => {
    const { page, logs } = await openViewer(shared.browser, shared.server.url, { width: 900, height: 600, query: '?quality=low' });
    try {
      const id = await page.evaluate(() => window.pliant.mouseHandId);
      assert.ok(await page.evaluate(([id, p]) => window.pliant.send({ type: 'grab', hand_id: id, position: p }), [id, END]));
      await page.waitForFunction(
        (id) => window.pliant.manikin().visible && window.pliant.manikin().lines.includes('right arm: hand ' + id + ' reached'),
        id,
      );
      const m = await page.evaluate(() => window.pliant.manikin());
      assert.ok(m.lines[0].endsWith(', sitting'), m.lines.join('\n'));
      assert.ok(m.lines.includes('seated, the seat 435 mm high'), m.lines.join('\n'));
      // the thighs level, from the hips to the knees in front
      const thigh = m.capsules.find((c) => c.segment === 'right thigh');
      assert.ok(Math.abs(thigh.a[2] - thigh.b[2]) < 1e-9 && thigh.b[0] > thigh.a[0] + 0.3, JSON.stringify(thigh));
      // the seat box drawn, its top at the seat height (three.js space: y up, the box's
      // height its third length)
      const seat = m.seat;
      assert.ok(seat.visible, JSON.stringify(seat));
      const posed = await page.evaluate(() => window.pliant.snapshot.worker.seat);
      assert.ok(Math.abs(posed.centre[2] + 0.5 * posed.size[2] - 0.435) < 1e-9, JSON.stringify(posed));
      assert.deepEqual(seat.size.map((x) => Number(x.toFixed(9))), posed.size.map((x) => Number(x.toFixed(9))));
      assert.ok(!logs.some((l) => l.startsWith('pageerror')), logs.join('\n'));
    } finally {
      await page.close();
    }
  });
});
