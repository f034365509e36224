// Unit tests of where the scene goes in VR and AR (web/src/xr_placement.ts).

import assert from 'node:assert/strict';
import path from 'node:path';
import { test } from 'node:test';
import { fileURLToPath, pathToFileURL } from 'node:url';

const here = path.dirname(fileURLToPath(import.meta.url));
const X = await import(pathToFileURL(path.join(here, '..', '..', '..', 'target', 'web-unit', 'xr_placement.js')).href);

const add = (a, b) => a.map((x, i) => x + b[i]);

test('VR: the centre at working height in front of the user', () => {
  const c = [0.3, 0.5, -0.2];
  assert.deepEqual(add(c, X.xrOffset('immersive-vr', c, 0.1)), [0, X.VR_HEIGHT, -X.VR_DISTANCE]);
});

test('AR: the lowest point on the real floor, the centre in front of the user', () => {
  const c = [0.3, 0.5, -0.2];
  const o = X.xrOffset('immersive-ar', c, 0.1);
  assert.equal(0.1 + o[1], 0, 'lowest point on the floor');
  const centre = add(c, o);
  assert.deepEqual([centre[0], centre[2]], [0, -X.AR_DISTANCE]);
  assert.ok(Math.abs(centre[1] - 0.4) < 1e-15, 'the centre keeps its height above the lowest point');
});

test('AR hit: the lowest point on the surface hit, the centre straight above it', () => {
  const c = [0.3, 0.5, -0.2];
  const hit = [0.4, 0.72, -0.9];
  const o = X.hitOffset(c, 0.1, hit);
  assert.ok(Math.abs(0.1 + o[1] - 0.72) < 1e-15, 'lowest point on the table');
  const centre = add(c, o);
  assert.ok(Math.abs(centre[0] - 0.4) < 1e-15 && Math.abs(centre[2] + 0.9) < 1e-15, String(centre));
  assert.ok(Math.abs(centre[1] - (0.72 + 0.4)) < 1e-15, 'the centre keeps its height above the lowest point');
});

test('AR hit: the pose\'s y axis is the normal; only surfaces facing up count', () => {
  const about = (axis, angle) => [...axis.map((a) => a * Math.sin(angle / 2)), Math.cos(angle / 2)];
  assert.deepEqual(X.hitNormal([0, 0, 0, 1]), [0, 1, 0]);
  // 90° about x turns y into z
  const n = X.hitNormal(about([1, 0, 0], Math.PI / 2));
  assert.ok(Math.abs(n[0]) < 1e-15 && Math.abs(n[1]) < 1e-15 && Math.abs(n[2] - 1) < 1e-15, String(n));
  assert.ok(X.facesUp([0, 0, 0, 1]), 'a level table');
  assert.ok(X.facesUp(about([0, 1, 0], 2)), 'a turn about the vertical keeps it level');
  assert.ok(X.facesUp(about([1, 0, 0], X.MAX_SURFACE_TILT - 1e-9)));
  assert.ok(!X.facesUp(about([1, 0, 0], X.MAX_SURFACE_TILT + 1e-9)), 'just over the tilt');
  assert.ok(!X.facesUp(about([0, 0, 1], Math.PI / 2)), 'a wall');
  assert.ok(!X.facesUp(about([1, 0, 0], Math.PI)), 'a ceiling');
});
