// End-to-end test of moving parts in the viewer: `pliant serve` (the real binary) on a
// door that a client turns with `rotate_part` and lifts with `move_part`; the snapshots
// carry the door's pose, the viewer draws the door's mesh at it and the hose end mounted
// on the door with it. Every wait is for a condition (HANG_GUARD_MS only stops a hung
// test); nothing depends on the machine's speed.

import assert from 'node:assert/strict';
import { mkdtempSync, writeFileSync } from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { describe, test } from 'node:test';
import { openViewer, sharedSession } from './harness.mjs';

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
    await page.waitForFunction(() => (window.pliant.snapshot?.notice ?? '').includes('no part named "lid" (parts: body, door)'));
    await page.close();
  });
});
