// Unit tests of the worker's drawing model (web/src/manikin_model.ts): capsules from a
// snapshot's flattened end points and the welcome's radii, contacts named and the deepest
// kept, malformed poses drawing nothing, and the panel's lines.

import assert from 'node:assert/strict';
import path from 'node:path';
import { test } from 'node:test';
import { fileURLToPath, pathToFileURL } from 'node:url';

const here = path.dirname(fileURLToPath(import.meta.url));
const M = await import(pathToFileURL(path.join(here, '..', '..', '..', 'target', 'web-unit', 'manikin_model.js')).href);

const data = { who: 'the 5th-percentile woman', stature: 1.523, segments: ['head', 'trunk', 'right forearm'], radii: [0.087, 0.107, 0.03] };
const names = { parts: ['radiator', 'frame'], hoses: ['coolant'] };
const pose = (over = {}) => ({
  time: 1.25,
  capsules: [0, 0, 1.6, 0, 0, 1.6, 0, 0, 0.8, 0, 0, 1.3, 0.3, -0.2, 1.0, 0.5, -0.2, 1.1],
  contacts: [],
  arms: [{ hand: 4, shortfall: 0.1204 }, null],
  rula: 5,
  reba: 7,
  posture_class: 'bent_trunk',
  ...over,
});

test('capsules take their end points from six numbers each and radii from the welcome', () => {
  const caps = M.manikinCapsules(data, pose(), names);
  assert.equal(caps.length, 3);
  assert.deepEqual(caps[1], { segment: 'trunk', a: [0, 0, 0.8], b: [0, 0, 1.3], radius: 0.107, contact: null });
  assert.deepEqual(caps[2].a, [0.3, -0.2, 1.0]);
  assert.deepEqual(caps[2].b, [0.5, -0.2, 1.1]);
});

test('a contact names its part or hose; the deepest of a segment is kept', () => {
  const caps = M.manikinCapsules(data, pose({
    contacts: [
      { segment: 2, obstacle: 'part', index: 1, depth: 0.004 },
      { segment: 2, obstacle: 'hose', index: 0, depth: 0.012 },
      { segment: 1, obstacle: 'part', index: 0, depth: 0.02 },
      { segment: 9, obstacle: 'part', index: 0, depth: 0.5 },
    ],
  }), names);
  assert.deepEqual(caps[2].contact, { obstacle: 'hose', name: 'coolant', depth: 0.012 });
  assert.deepEqual(caps[1].contact, { obstacle: 'part', name: 'radiator', depth: 0.02 });
  assert.equal(caps[0].contact, null);
});

test('a pose that does not fit the body draws nothing', () => {
  assert.deepEqual(M.manikinCapsules(data, pose({ capsules: [0, 0, 0] }), names), []);
  const bad = pose();
  bad.capsules[4] = Number.NaN;
  assert.deepEqual(M.manikinCapsules(data, bad, names), []);
  assert.deepEqual(M.manikinCapsules({ ...data, radii: [0.1] }, pose(), names), []);
});

test('the panel lines: scores and class, reach shortfall in mm, contacts', () => {
  const p = pose({ contacts: [{ segment: 1, obstacle: 'part', index: 0, depth: 0.0204 }], arms: [{ hand: 4, shortfall: 0.1204 }, { hand: 5, shortfall: 2e-5 }] });
  const lines = M.manikinLines(data, p, M.manikinCapsules(data, p, names));
  assert.deepEqual(lines, [
    'the 5th-percentile woman at t = 1.25 s: RULA 5, REBA 7, bent trunk',
    'right arm: hand 4 out of reach by 120 mm',
    'left arm: hand 5 reached',
    "trunk 20 mm inside 'radiator'",
  ]);
  assert.deepEqual(M.manikinLines(data, undefined, []), ['the 5th-percentile woman: not posed yet']);
});

test('a step or turn is seen from the stance or the step count; old recordings never step', () => {
  const at = (position, forward = [1, 0, 0], steps = 0) => pose({ stance: { position, forward }, steps });
  assert.equal(M.stepped(at([0, 0, 0]), at([0, 0, 0])), false, 'same stance');
  assert.equal(M.stepped(at([0, 0, 0]), at([0.25, 0, 0], [1, 0, 0], 1)), true, 'a step forward');
  assert.equal(M.stepped(at([0, 0, 0]), at([0, 0, 0], [0, 1, 0], 1)), true, 'a turn in place');
  assert.equal(M.stepped(at([0, 0, 0], [1, 0, 0], 1), at([0, 0, 0], [1, 0, 0], 2)), true, 'a step there and back between snapshots');
  assert.equal(M.stepped(pose(), at([1, 0, 0])), false, 'no stance before');
  assert.equal(M.stepped(undefined, at([1, 0, 0])), false, 'not posed before');
});

test('a step is drawn as a glide with a smooth start and stop', () => {
  const from = M.manikinCapsules(data, pose(), names);
  const to = M.manikinCapsules(data, pose({ capsules: pose().capsules.map((x, i) => (i % 3 === 0 ? x + 0.4 : x)) }), names);
  assert.deepEqual(M.glide(from, to, 0), from);
  assert.deepEqual(M.glide(from, to, 1), to);
  assert.deepEqual(M.glide(from, to, 7), to, 'clamped');
  const half = M.glide(from, to, 0.5);
  half.forEach((c, i) => {
    assert.ok(Math.abs(c.a[0] - (from[i].a[0] + 0.2)) < 1e-12, `half way: ${c.a}`);
    assert.equal(c.segment, to[i].segment);
  });
  // slow at the start: a tenth of the time covers 2.8 % of the way
  assert.ok(Math.abs(M.glide(from, to, 0.1)[0].a[0] - (from[0].a[0] + 0.4 * 0.028)) < 1e-12);
  assert.deepEqual(M.glide(from.slice(1), to, 0.5), to, 'another body: no glide');
});

// A seated 50th-percentile man as the server sends him (docs/worker.md, "Sitting"): the
// pelvis between the hips 0.505 m up, the thigh level to the knee 0.43 m ahead, the shank
// straight down to the ankle; the seat a box from the floor to 0.435 m under the hips.
const seated = {
  data: { who: 'the 50th-percentile man', stature: 1.756, segments: ['pelvis', 'right thigh', 'right shank'], radii: [0.105, 0.07, 0.049] },
  pose: pose({
    capsules: [0, -0.084, 0.505, 0, 0.084, 0.505, 0, -0.084, 0.505, 0.43, -0.084, 0.505, 0.43, -0.084, 0.505, 0.43, -0.084, 0.068],
    posture_class: 'sitting',
    arms: [null, null],
    seat: { centre: [0.12, 0, 0.2175], size: [0.45, 0.308, 0.435], forward: [1, 0, 0], up: [0, 0, 1] },
  }),
};

test('a seated pose: thighs level, knees bent at a right angle, the seat under the thighs', () => {
  const caps = M.manikinCapsules(seated.data, seated.pose, names);
  const [thigh, shank] = [caps[1], caps[2]];
  assert.equal(thigh.a[2], thigh.b[2]);
  const t = thigh.b.map((x, k) => x - thigh.a[k]);
  const s = shank.b.map((x, k) => x - shank.a[k]);
  assert.equal(t[0] * s[0] + t[1] * s[1] + t[2] * s[2], 0);
  const box = M.seatBox(seated.pose);
  assert.deepEqual(box.left, [0, 1, 0]);
  const top = box.centre[2] + 0.5 * box.size[2];
  assert.ok(Math.abs(top - 0.435) < 1e-12 && top < thigh.a[2]);
  // the box ends in front of the hips and short of the knee
  const front = box.centre[0] + 0.5 * box.size[0];
  assert.ok(front > thigh.a[0] && front < thigh.b[0]);
  assert.deepEqual(M.manikinLines(seated.data, seated.pose, caps).slice(0, 2), [
    'the 50th-percentile man at t = 1.25 s: RULA 5, REBA 7, sitting',
    'seated, the seat 435 mm high',
  ]);
});

test('no seat standing; a malformed seat draws none', () => {
  assert.equal(M.seatBox(pose()), null);
  assert.equal(M.seatBox(undefined), null);
  for (const bad of [
    { ...seated.pose.seat, size: [0.45, 0, 0.435] },
    { ...seated.pose.seat, centre: [0, Number.NaN, 0] },
    { ...seated.pose.seat, forward: [1, 0, 1] },
    { ...seated.pose.seat, up: [1, 0, 0] },
  ]) {
    assert.equal(M.seatBox({ ...seated.pose, seat: bad }), null, JSON.stringify(bad));
  }
  assert.equal(M.manikinLines(data, pose({ posture_class: 'sitting_bent_trunk' }), [])[0].endsWith('sitting with bent trunk'), true);
});
