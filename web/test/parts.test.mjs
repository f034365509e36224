// End-to-end test of moving parts in the viewer: `pliant serve` (the real binary) on a
// door that a client turns with `rotate_part` and lifts with `move_part`; the snapshots
// carry the door's pose, the viewer draws the door's mesh at it and the hose end mounted
// on the door with it. A hatch whose hinge the scene's timeline describes (a live session
// starts from the timeline's leading fixes only: the hatch stays shut) gets a hinge slider
// in the panel and a handle (a ring about the hinge) in the view: dragging either turns the
// hatch in the server's snapshot, and the stub on the hatch is drawn with it. Every wait is for a condition (HANG_GUARD_MS only stops a hung test); nothing
// depends on the machine's speed.

import assert from 'node:assert/strict';
import { mkdtempSync, writeFileSync } from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { describe, test } from 'node:test';
import { framesDrawn, openViewer, sharedSession } from './harness.mjs';

/** The hatch's turn about +x [deg] in the newest snapshot's part poses (null: no pose). */
function hatchAngle() {
  const p = (window.pliant.snapshot?.part_poses ?? []).find((q) => q.part === 2);
  return p === undefined ? null : (2 * Math.atan2(p.rotation[0], p.rotation[3]) * 180) / Math.PI;
}

const dir = mkdtempSync(path.join(os.tmpdir(), 'pliant-parts-'));
const scene = path.join(dir, 'door.toml');
writeFileSync(scene, `
format = "pliant-scene"
version = 1
length_unit = "mm"

[simulation]
gravity = [0, 0, 0]

[[hoses]]
name = "h"
material = "hose3"
start = [0, 0, 300]
path = [{ line = { to = [300, 0, 300] } }]

[[parts]]
name = "body"
box = { size = [40, 40, 40] }
position = [-40, 0, 260]

[[parts]]
name = "door"
box = { size = [20, 20, 20] }
position = [320, 0, 260]
movable = true

[[timeline]]
action = "fix"
hose = "h"
node = 0

[[timeline]]
action = "fix"
hose = "h"
node = -1
part = "door"

[[parts]]
name = "hatch"
box = { size = [100, 100, 10] }
position = [150, 250, 300]

[[stubs]]
name = "hatch stub"
origin = [150, 250, 320]
axis = [0, 0, -1]
length = 20
diameter = 30
part = "hatch"

[[timeline]]
action = "rotate_part"      # a run opens the hatch on this hinge (about x, 0 … 40°); a live session starts shut
part = "hatch"
axis = [1, 0, 0]
point = [150, 200, 300]
to_deg = 40
duration_s = 0.5
wait = false
`);

const shared = sharedSession([scene]);
const PIN = [0.5, 0, 0.3];

describe('moving parts', () => {
  test('a door turned and lifted by a client is drawn at its pose with the hose end on it', async () => {
    const { page } = await openViewer(shared.browser, shared.server.url, { width: 800, height: 600, query: '?quality=low' });
    // the movable door is in every snapshot's part poses, at the identity to begin with
    await page.waitForFunction(() => (window.pliant.snapshot?.part_poses ?? []).some((p) => p.part === 1));
    const start = await page.evaluate(() => window.pliant.partPoses()[1]);
    assert.deepEqual(start.rotation, [0, 0, 0, 1]);
    assert.ok(await page.evaluate((pin) => window.pliant.send({
      type: 'rotate_part', part: 'door', axis: [0, 0, 1], point: pin, to_deg: 60, duration_s: 0.3,
    }), PIN));
    // turned: the snapshot's pose, the drawn mesh and the mounted end all at 60°
    const half = Math.PI / 6;
    await page.waitForFunction((c) => {
      const p = (window.pliant.shown?.part_poses ?? []).find((q) => q.part === 1);
      return p !== undefined && Math.abs(p.rotation[3] - c) < 1e-9;
    }, Math.cos(half));
    await page.waitForFunction((c) => Math.abs(window.pliant.partPoses()[1].rotation[3] - c) < 1e-6, Math.cos(half));
    const drawn = await page.evaluate(() => window.pliant.partPoses());
    assert.ok(Math.abs(drawn[1].rotation[2] - Math.sin(half)) < 1e-6, JSON.stringify(drawn[1]));
    assert.deepEqual(drawn[0].rotation, [0, 0, 0, 1], 'the body stands still');
    const end = await page.evaluate(() => window.pliant.hoseNodes(0).at(-1));
    const expected = [PIN[0] - 0.2 * Math.cos(2 * half), -0.2 * Math.sin(2 * half), 0.3];
    assert.ok(Math.hypot(...end.map((x, k) => x - expected[k])) < 1e-4, `end ${end}, expected ${expected}`);
    // lifted by 10 mm
    assert.ok(await page.evaluate(() => window.pliant.send({ type: 'move_part', part: 'door', by: [0, 0, 0.01], duration_s: 0.2 })));
    await page.waitForFunction(() => Math.abs(window.pliant.hoseNodes(0).at(-1)[2] - 0.31) < 1e-4);
    // an unknown part: the simulation's refusal comes back as the notice
    assert.ok(await page.evaluate(() => window.pliant.send({ type: 'move_part', part: 'lid', by: [0, 0, 0.01], duration_s: 0.2 })));
    await page.waitForFunction(() => (window.pliant.snapshot?.notice ?? '').includes('no part named "lid" (parts: body, door, hatch)'));
    await page.close();
  });

  test("dragging the hatch's hinge slider, or its handle in the view, turns it in the server's snapshot; its stub goes with it", async () => {
    const { page } = await openViewer(shared.browser, shared.server.url, { width: 1000, height: 700, query: '?quality=low' });
    await page.addScriptTag({ content: `window.hatchAngle = ${hatchAngle.toString()};` });
    // the hatch's row: a slider over the timeline's hinge, 0 … 40°, at 0° (shut)
    const slider = page.locator('input.part-slider[data-part="hatch"]');
    await slider.scrollIntoViewIfNeeded();
    await page.waitForFunction(() => window.pliant.partControls().some((c) => c.part === 'hatch' && c.slider === 0 && c.coordinate === 0));
    assert.equal(await slider.isDisabled(), false);
    // drag the thumb from its left end three quarters of the way; the value let go at
    // (read when the slider reports the change: the panel's own listener ran before)
    await slider.evaluate((s) => s.addEventListener('change', () => (window.sliderLetGo = Number(s.value))));
    const box = await slider.boundingBox();
    const y = box.y + box.height / 2;
    await page.mouse.move(box.x + 4, y);
    await page.mouse.down();
    for (let k = 1; k <= 10; k++) await page.mouse.move(box.x + 4 + (k * (box.width * 0.75 - 4)) / 10, y);
    await page.mouse.up();
    const value = await page.evaluate(() => window.sliderLetGo);
    assert.ok(value > 650 && value < 850, `slider at ${value}`);
    const target = (40 * value) / 1000;
    // the server turns the hatch to the slider's angle (the snapshot, not the viewer, says so)
    await page.waitForFunction((t) => { const a = window.hatchAngle(); return a !== null && Math.abs(a - t) < 1e-6; }, target);
    // the stub on the hatch is drawn where the hatch's pose carries it
    await page.waitForFunction((t) => {
      const p = (window.pliant.shown?.part_poses ?? []).find((q) => q.part === 2);
      return p !== undefined && Math.abs((2 * Math.atan2(p.rotation[0], p.rotation[3]) * 180) / Math.PI - t) < 1e-6;
    }, target);
    const { stub, pose } = await page.evaluate(() => ({
      stub: window.pliant.fasteners().find((f) => f.name === 'stub:hatch stub').origin,
      pose: window.pliant.shown.part_poses.find((q) => q.part === 2),
    }));
    // a turn by a about x through the hinge point [0.15, 0.2, 0.3] takes the mouth
    // [0.15, 0.25, 0.32] to the point + R(a)·[0, 0.05, 0.02]
    assert.ok(Math.abs(pose.rotation[1]) + Math.abs(pose.rotation[2]) < 1e-12, 'a turn about x only');
    const a = 2 * Math.atan2(pose.rotation[0], pose.rotation[3]);
    const expected = [0.15, 0.2 + 0.05 * Math.cos(a) - 0.02 * Math.sin(a), 0.3 + 0.05 * Math.sin(a) + 0.02 * Math.cos(a)];
    assert.ok(Math.hypot(...stub.map((x, k) => x - expected[k])) < 1e-9, `stub at ${stub}, expected ${expected} (pose ${JSON.stringify(pose)})`);
    // the hatch's handle in the view: a ring about the hinge axis; dragging it along the
    // ring turns the hatch too, in the server's snapshot
    await page.click('.part-control[data-part="hatch"] .part-handle-button');
    await page.evaluate(() => window.pliant.lookAt([0.15, 0.2, 0.3], 0.5));
    await framesDrawn(page, 3);
    const view = await page.evaluate(() => document.querySelector('#view').getBoundingClientRect().toJSON());
    const ring = await page.evaluate(() => window.pliant.partHandlePoints('Z'));
    assert.ok(ring.length > 0, 'the handle is shown');
    const centre = { x: ring.reduce((a, p) => a + p.x, 0) / ring.length, y: ring.reduce((a, p) => a + p.y, 0) / ring.length };
    const inside = ring.filter((p) => p.x > view.left + 40 && p.x < view.right - 40 && p.y > view.top + 40 && p.y < view.bottom - 40);
    assert.ok(inside.length > 0, 'the ring is in the view');
    // the ring's point farthest from its centre on screen: a drag across the radius there
    // moves along the ring
    const grip = inside.reduce((b, p) => (Math.hypot(p.x - centre.x, p.y - centre.y) > Math.hypot(b.x - centre.x, b.y - centre.y) ? p : b));
    const r = Math.hypot(grip.x - centre.x, grip.y - centre.y);
    const along = { x: -(grip.y - centre.y) / r, y: (grip.x - centre.x) / r };
    const before = await page.evaluate(() => window.hatchAngle());
    await page.mouse.move(grip.x, grip.y);
    await page.waitForFunction(() => window.pliant.partHandleHovered);
    await page.mouse.down();
    for (let k = 1; k <= 10; k++) await page.mouse.move(grip.x + along.x * 6 * k, grip.y + along.y * 6 * k);
    await page.mouse.up();
    const move = await page.evaluate(() => window.pliant.lastPartMove);
    assert.equal(move.type, 'rotate_part');
    assert.equal(move.part, 'hatch');
    assert.deepEqual(move.axis, [1, 0, 0]);
    assert.ok(move.to_deg >= 0 && move.to_deg <= 40 && Math.abs(move.to_deg - before) > 1, `the handle turned the hatch from ${before}° to ${move.to_deg}°`);
    await page.waitForFunction((t) => Math.abs(window.hatchAngle() - t) < 1e-6, move.to_deg);
    await page.close();
  });
});
