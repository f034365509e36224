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
