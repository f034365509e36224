// Unit tests of how a junction body's shape is drawn (web/src/junction_geometry.ts,
// web/src/part_joints.ts): a body with a shape is drawn as its part, not as a hub, and the
// part's rest mesh carried by the snapshot's pose — the body's rigid motion, R = R_b R₀ᵀ,
// T = c − R c₀ (pliant_core::junction_shape) — puts its outlets where the body moved them.

import assert from 'node:assert/strict';
import path from 'node:path';
import { test } from 'node:test';
import { fileURLToPath, pathToFileURL } from 'node:url';

const here = path.dirname(fileURLToPath(import.meta.url));
const unit = (name) => pathToFileURL(path.join(here, '..', '..', '..', 'target', 'web-unit', name)).href;
const G = await import(unit('junction_geometry.js'));
const J = await import(unit('part_joints.js'));

/** q1 q2 for quaternions [x, y, z, w]. */
const mul = (a, b) => [
  a[3] * b[0] + a[0] * b[3] + a[1] * b[2] - a[2] * b[1],
  a[3] * b[1] - a[0] * b[2] + a[1] * b[3] + a[2] * b[0],
  a[3] * b[2] + a[0] * b[1] - a[1] * b[0] + a[2] * b[3],
  a[3] * b[3] - a[0] * b[0] - a[1] * b[1] - a[2] * b[2],
];
const conj = (q) => [-q[0], -q[1], -q[2], q[3]];
const quat = (a, deg) => {
  const h = (deg * Math.PI) / 360;
  return [a[0] * Math.sin(h), a[1] * Math.sin(h), a[2] * Math.sin(h), Math.cos(h)];
};
const turn = (q, v) => J.carry({ part: 0, translation: [0, 0, 0], rotation: q }, v);
const close = (a, b, tol, what) => a.forEach((x, i) => assert.ok(Math.abs(x - b[i]) <= tol, `${what}: ${a} vs ${b}`));

test('a body with a shape is drawn as its part, one without as a hub', () => {
  assert.equal(G.drawnAsHub({ outlets: [] }), true);
  assert.equal(G.drawnAsHub({ outlets: [], shape: null }), true);
  assert.equal(G.drawnAsHub({ outlets: [], shape: 0 }), false);
  assert.equal(G.drawnAsHub({ outlets: [], shape: 3 }), false);
});

test("the shape's rest mesh at the body's pose puts its outlets where the body moved them", () => {
  // a T piece: centre of mass c0, principal frame R0 at rest, three outlets
  const c0 = [0.32, 0.01, -0.02];
  const r0 = quat([0.6, 0, 0.8], 25);
  const outlets = [[0.3, 0, 0], [0.34, 0, 0], [0.32, 0.03, 0]];
  // the body moved: centre c, frame R_b = Q R0 (turned by Q about its centre)
  const q = mul(quat([0, 0, 1], 90), quat([1, 0, 0], 30));
  const c = [0.5, -0.2, 0.1];
  const rb = mul(q, r0);
  // the pose the server sends: R = R_b R0ᵀ, T = c − R c0
  const rotation = mul(rb, conj(r0));
  const rc0 = turn(rotation, c0);
  const pose = { part: 0, rotation, translation: [c[0] - rc0[0], c[1] - rc0[1], c[2] - rc0[2]] };
  for (const o of outlets) {
    // where the body carries the outlet: c + Q (o − c0)
    const arm = turn(q, [o[0] - c0[0], o[1] - c0[1], o[2] - c0[2]]);
    close(J.carry(pose, o), [c[0] + arm[0], c[1] + arm[1], c[2] + arm[2]], 1e-12, `outlet ${o}`);
  }
  // the centre of mass itself goes to c
  close(J.carry(pose, c0), c, 1e-12, 'centre');
});
