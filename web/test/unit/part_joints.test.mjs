// Unit tests of how parts move in the viewer (web/src/part_joints.ts): the sliders made
// from the welcome's joints, the slider ↔ joint coordinate mapping, the coordinate of a part
// pose, the messages a slider sends, and where a stub or clip on a moving part is drawn.

import assert from 'node:assert/strict';
import path from 'node:path';
import { test } from 'node:test';
import { fileURLToPath, pathToFileURL } from 'node:url';

const here = path.dirname(fileURLToPath(import.meta.url));
const J = await import(pathToFileURL(path.join(here, '..', '..', '..', 'target', 'web-unit', 'part_joints.js')).href);

/** A unit quaternion [x, y, z, w] turning `deg` about the unit axis `a`. */
const quat = (a, deg) => {
  const h = (deg * Math.PI) / 360;
  return [a[0] * Math.sin(h), a[1] * Math.sin(h), a[2] * Math.sin(h), Math.cos(h)];
};
const close = (a, b, tol, what) => {
  assert.equal(a.length, b.length, what);
  a.forEach((x, i) => assert.ok(Math.abs(x - b[i]) <= tol, `${what}: ${a} vs ${b}`));
};

const D = Math.PI / 180;
const box = { bounds_min: [0, 0, 0], bounds_max: [0.01, 0.01, 0.01], vertices: [], triangles: [] };
/** A welcome's parts as the server sends them (docs/protocol.md "welcome"): SI units. */
const parts = [
  { name: 'body', ...box, joint: null, scripted: false, movable: false, parent: null },
  { name: 'lid', ...box, joint: { kind: 'hinge', axis: [0, 0, 1], point: [0.6, 0, 0.3], range: [-10 * D, 70 * D] }, scripted: true, movable: false, parent: null },
  { name: 'seat', ...box, joint: { kind: 'slide', direction: [0, 1, 0], range: [0, 0.25] }, scripted: true, movable: false, parent: null },
  { name: 'door', ...box, joint: { kind: 'hinge', axis: [0, 0, 1], point: [0.5, 0, 0.3], range: [-20 * D, 70 * D] }, scripted: false, movable: true, parent: null },
  { name: 'drawer', ...box, joint: { kind: 'slide', direction: [0, 0, 1], range: [-0.03, 0.12] }, scripted: false, movable: true, parent: null },
  { name: 'flap', ...box, joint: null, scripted: false, movable: true, parent: null },
  { name: 'handle', ...box, joint: null, scripted: false, movable: false, parent: 1 },
  {
    name: 'engine', ...box, scripted: true, movable: false, parent: null,
    joint: { kind: 'periodic', centre: [0, 0, 0], translation: [{ amplitude: 0, frequency: 0, phase: 0 }, { amplitude: 0, frequency: 0, phase: 0 }, { amplitude: 0.002, frequency: 25, phase: 0 }], rotation: [{ amplitude: 0.02, frequency: 12, phase: 0 }, { amplitude: 0, frequency: 0, phase: 0 }, { amplitude: 0, frequency: 0, phase: 0 }] },
  },
  { name: 'arm', ...box, joint: { kind: 'sampled_path', centre: [0, 0, 0], time_range: [0.5, 4] }, scripted: true, movable: false, parent: null },
];

test("the welcome's joints make the sliders: hinge ranges in degrees, slides in metres, scripted motions shown", () => {
  const c = J.partControls(parts);
  assert.deepEqual(c.map((x) => x.name), ['lid', 'seat', 'door', 'drawer', 'flap', 'engine', 'arm'], 'still parts and parts carried only by their parent have no row');
  const [lid, seat, door, drawer, flap, engine, arm] = c;
  assert.deepEqual([lid.part, lid.scripted, lid.movable], [1, true, false]);
  assert.equal(lid.joint.kind, 'hinge');
  close(lid.joint.point, [0.6, 0, 0.3], 0, 'hinge point as sent');
  close([lid.joint.min, lid.joint.max], [-10, 70], 1e-12, 'hinge range in degrees');
  assert.equal(seat.joint.kind, 'slide');
  close([seat.joint.min, seat.joint.max], [0, 0.25], 0, 'slide travel in metres');
  assert.deepEqual([door.part, door.scripted, door.movable], [3, false, true]);
  close([door.joint.min, door.joint.max], [-20, 70], 1e-12, "the timeline's hinge range");
  close(drawer.joint.direction, [0, 0, 1], 0, 'slide direction');
  close([drawer.joint.min, drawer.joint.max], [-0.03, 0.12], 0, "the timeline's slide range");
  // movable without a joint: a free handle, no slider
  assert.deepEqual([flap.joint, flap.movable], [null, true]);
  // a periodic motion and a sampled path: no slider, described
  assert.equal(engine.joint, null);
  assert.equal(engine.motion, 'periodic motion, 25 Hz, 12 Hz');
  assert.equal(arm.joint, null);
  assert.equal(arm.motion, 'sampled path, 0.50 … 4.00 s');
});

test('a range that is a point or has no end gives the default slider range; old welcomes give no rows', () => {
  const still = { ...parts[1], joint: { ...parts[1].joint, range: [0, 0] } };
  const endless = { ...parts[2], joint: { ...parts[2].joint, range: null } };
  const [h, s] = J.partControls([still, endless]);
  assert.deepEqual([h.joint.min, h.joint.max], [-J.DEFAULT_HINGE_RANGE_DEG, J.DEFAULT_HINGE_RANGE_DEG]);
  assert.deepEqual([s.joint.min, s.joint.max], [-J.DEFAULT_SLIDE_RANGE_M, J.DEFAULT_SLIDE_RANGE_M]);
  // a recording made before the welcome carried joints
  assert.deepEqual(J.partControls([{ name: 'door', ...box }]), []);
  assert.deepEqual(J.partControls([]), []);
});

test('the slider maps linearly onto the joint range, clamped, and back', () => {
  const hinge = { kind: 'hinge', axis: [0, 0, 1], point: [0, 0, 0], min: -20, max: 70 };
  assert.equal(J.sliderToCoordinate(hinge, 0), -20);
  assert.equal(J.sliderToCoordinate(hinge, J.SLIDER_STEPS), 70);
  assert.equal(J.sliderToCoordinate(hinge, J.SLIDER_STEPS / 2), 25);
  assert.equal(J.sliderToCoordinate(hinge, -5), -20, 'clamped below');
  assert.equal(J.sliderToCoordinate(hinge, 2 * J.SLIDER_STEPS), 70, 'clamped above');
  assert.equal(J.coordinateToSlider(hinge, 0), Math.round((20 / 90) * J.SLIDER_STEPS));
  assert.equal(J.coordinateToSlider(hinge, 100), J.SLIDER_STEPS);
  assert.equal(J.coordinateToSlider(hinge, -100), 0);
  for (let v = 0; v <= J.SLIDER_STEPS; v += 37) assert.equal(J.coordinateToSlider(hinge, J.sliderToCoordinate(hinge, v)), v, `round trip at ${v}`);
});

test('the coordinate of a pose: the turn about the hinge axis, the travel along the slide', () => {
  const hinge = { kind: 'hinge', axis: [0, 0, 1], point: [0, 0, 0], min: 0, max: 90 };
  const pose = (rotation, translation = [0, 0, 0]) => ({ part: 0, translation, rotation });
  assert.equal(J.coordinateOfPose(hinge, null), 0);
  for (const deg of [0, 30, 60, 89.5, -45, 179]) {
    assert.ok(Math.abs(J.coordinateOfPose(hinge, pose(quat([0, 0, 1], deg))) - deg) < 1e-9, `${deg}°`);
  }
  assert.ok(Math.abs(J.coordinateOfPose(hinge, pose(quat([0, 0, -1], 30))) + 30) < 1e-9, 'a turn about −z is negative about +z');
  assert.ok(Math.abs(J.coordinateOfPose(hinge, pose(quat([0, 0, 1], 200))) + 160) < 1e-9, 'wrapped into (−180, 180]');
  const slide = { kind: 'slide', direction: [0, 1, 0], min: 0, max: 0.25 };
  assert.equal(J.coordinateOfPose(slide, pose([0, 0, 0, 1], [0.1, 0.12, 0])), 0.12);
});

test('a slider sends rotate_part to the angle, or move_part to the offset, at the joint speed', () => {
  const hinge = { kind: 'hinge', axis: [0, 0, 1], point: [0.5, 0, 0.3], min: 0, max: 90 };
  assert.deepEqual(J.jointMessage('door', hinge, 45, 0), {
    type: 'rotate_part', part: 'door', axis: [0, 0, 1], to_deg: 45, duration_s: 45 / J.HINGE_SPEED_DEG_S, point: [0.5, 0, 0.3],
  });
  const m = J.jointMessage('door', hinge, 44, 43.9);
  assert.equal(m.duration_s, J.MIN_MOVE_S, 'a small step still takes the shortest move');
  const slide = { kind: 'slide', direction: [0, 1, 0], min: 0, max: 0.25 };
  const s = J.jointMessage('seat', slide, 0.2, 0.05);
  assert.deepEqual(s.to, [0, 0.2, 0]);
  assert.equal(s.type, 'move_part');
  assert.ok(Math.abs(s.duration_s - 0.15 / J.SLIDE_SPEED_M_S) < 1e-12);
});

test('a handle dragged adds its turn about the hinge axis, or its shift along the slide, within the range', () => {
  const hinge = { kind: 'hinge', axis: [0, 0, 1], point: [0, 0, 0], min: -20, max: 70 };
  assert.ok(Math.abs(J.draggedCoordinate(hinge, 10, quat([0, 0, 1], 30), [0, 0, 0]) - 40) < 1e-9);
  assert.ok(Math.abs(J.draggedCoordinate(hinge, 10, quat([0, 0, -1], 15), [0.3, 0, 0]) + 5) < 1e-9, 'a shift does not turn a hinge');
  assert.equal(J.draggedCoordinate(hinge, 60, quat([0, 0, 1], 30), [0, 0, 0]), 70, 'clamped to the range');
  // a turn about a tilted axis counts with its part about the hinge axis: 2·atan2(q⃗·â, w)
  const tilted = [0, Math.sin(0.3), Math.cos(0.3)];
  const q = quat(tilted, 40);
  const want = (2 * Math.atan2(q[2], q[3]) * 180) / Math.PI;
  assert.ok(Math.abs(J.draggedCoordinate(hinge, 0, q, [0, 0, 0]) - want) < 1e-9);
  const slide = { kind: 'slide', direction: [0, 1, 0], min: 0, max: 0.25 };
  assert.ok(Math.abs(J.draggedCoordinate(slide, 0.1, [0, 0, 0, 1], [0.5, 0.05, 0]) - 0.15) < 1e-12, 'only the shift along the slide counts');
  assert.equal(J.draggedCoordinate(slide, 0.1, [0, 0, 0, 1], [0, -1, 0]), 0, 'clamped to the range');
});

test('a stub or clip on a part is carried by its pose: R·p + t', () => {
  // 90° about z moves x onto y
  close(J.carry({ part: 0, translation: [1, 2, 3], rotation: quat([0, 0, 1], 90) }, [1, 0, 0]), [1, 3, 3], 1e-12, '90° about z');
  // against the rotation matrix of a general unit quaternion
  const a = [1, 2, -2].map((x) => x / 3);
  const [x, y, z, w] = quat(a, 73);
  const R = [
    [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
    [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
    [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)],
  ];
  const p = [0.3, -0.7, 1.1];
  const t = [0.01, 0.02, -0.5];
  const want = R.map((row, i) => row[0] * p[0] + row[1] * p[1] + row[2] * p[2] + t[i]);
  close(J.carry({ part: 0, translation: t, rotation: [x, y, z, w] }, p), want, 1e-12, 'general rotation');
  close(J.carry({ part: 0, translation: [0, 0, 0], rotation: [0, 0, 0, 1] }, p), p, 0, 'identity');
});

test("each fastener is carried by the part the welcome names for it", () => {
  const fasteners = [{ name: 's1', part: 3 }, { name: 's2', part: null }, { name: 'c1', part: 2 }, { name: 'old' }];
  assert.deepEqual(J.fastenerCarriers(fasteners), [3, -1, 2, -1]);
});

/** P_parent ∘ P_own, as the server composes a child's world pose. */
const compose = (parent, own) => {
  const [ax, ay, az, aw] = parent.rotation;
  const [bx, by, bz, bw] = own.rotation;
  return {
    part: own.part,
    translation: J.carry(parent, own.translation),
    rotation: [aw * bx + ax * bw + ay * bz - az * by, aw * by - ax * bz + ay * bw + az * bx, aw * bz + ax * by - ay * bx + az * bw, aw * bw - ax * bx - ay * by - az * bz],
  };
};

test("a child's own pose undoes its parent's: the hinge angle is read in the parent's frame", () => {
  // a door hinged about z at 25° on a body that has itself turned 50° about (1, 1, 1) and moved
  const hinge = { kind: 'hinge', axis: [0, 0, 1], point: [0.5, 0, 0.3], min: -20, max: 70 };
  const own = { part: 3, translation: [0.5 - 0.5 * Math.cos(25 * D), -0.5 * Math.sin(25 * D), 0], rotation: quat([0, 0, 1], 25) };
  const parent = { part: 0, translation: [0.1, -0.2, 0.05], rotation: quat([1, 1, 1].map((x) => x / Math.sqrt(3)), 50) };
  const world = compose(parent, own);
  // read from the world pose the angle is wrong (the body's turn leaks in) …
  assert.ok(Math.abs(J.coordinateOfPose(hinge, world) - 25) > 1, 'world pose read as if the parent were at rest');
  // … from the own pose it is the door's 25°
  const back = J.ownPose(world, parent);
  assert.ok(Math.abs(J.coordinateOfPose(hinge, back) - 25) < 1e-9, `own angle ${J.coordinateOfPose(hinge, back)}`);
  close(back.translation, own.translation, 1e-12, 'own translation');
  close(back.rotation, own.rotation, 1e-12, 'own rotation');
  assert.equal(J.ownPose(world, null), world, 'no parent pose: the world pose is the own pose');
  // a slide on a parent turned 90° about z: the travel is read along the parent's axes
  const slide = { kind: 'slide', direction: [1, 0, 0], min: 0, max: 0.3 };
  const turnedParent = { part: 0, translation: [1, 1, 0], rotation: quat([0, 0, 1], 90) };
  const slid = compose(turnedParent, { part: 4, translation: [0.2, 0, 0], rotation: [0, 0, 0, 1] });
  assert.ok(Math.abs(J.coordinateOfPose(slide, J.ownPose(slid, turnedParent)) - 0.2) < 1e-12, 'travel in the parent frame');
});

test("a handle dragged on a turned parent's child: the drag is seen in the parent's frame", () => {
  // the body turned 90° about x: the door's hinge axis z (parent frame) points along −y in the world
  const parent = { part: 0, translation: [0, 0, 0], rotation: quat([1, 0, 0], 90) };
  const hinge = { kind: 'hinge', axis: [0, 0, 1], point: [0, 0, 0], min: -90, max: 90 };
  close(J.turned(parent.rotation, [0, 0, 1]), [0, -1, 0], 1e-12, 'the world axis of the hinge');
  // the user turns the handle 30° about the world axis −y, i.e. about the hinge
  const seen = J.dragInParent(parent, quat([0, -1, 0], 30), [0, 0.1, 0]);
  assert.ok(Math.abs(J.draggedCoordinate(hinge, 10, seen.turn, seen.shift) - 40) < 1e-9, 'turned 30° about the hinge');
  close(seen.shift, [0, 0, -0.1], 1e-12, 'the shift in the parent frame');
  // read without the parent the same drag turns the door by nothing about z
  assert.ok(Math.abs(J.draggedCoordinate(hinge, 10, quat([0, -1, 0], 30), [0, 0, 0]) - 10) < 1e-9, 'world drag misread');
  const none = J.dragInParent(null, quat([0, 0, 1], 15), [1, 2, 3]);
  assert.ok(Math.abs(J.draggedCoordinate(hinge, 0, none.turn, none.shift) - 15) < 1e-9, 'no parent: unchanged');
});
