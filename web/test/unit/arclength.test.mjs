// Unit tests of placing violation markers along a hose by arc length
// (web/src/arclength.ts).

import assert from 'node:assert/strict';
import path from 'node:path';
import { test } from 'node:test';
import { fileURLToPath, pathToFileURL } from 'node:url';

const here = path.dirname(fileURLToPath(import.meta.url));
const { pointAtArcLength } = await import(
  pathToFileURL(path.join(here, '..', '..', '..', 'target', 'web-unit', 'arclength.js')).href
);

const near = (p, q) => assert.ok(Math.hypot(p[0] - q[0], p[1] - q[1], p[2] - q[2]) < 1e-12, `${p} ≠ ${q}`);

test('a point at an arc length lies on the polyline at that distance from the first node', () => {
  // an L: 0.3 m along x, then 0.4 m along z
  const xyz = new Float64Array([0, 0, 0, 0.3, 0, 0, 0.3, 0, 0.4]);
  near(pointAtArcLength(xyz, 0), [0, 0, 0]);
  near(pointAtArcLength(xyz, 0.15), [0.15, 0, 0]);
  near(pointAtArcLength(xyz, 0.3), [0.3, 0, 0]);
  near(pointAtArcLength(xyz, 0.5), [0.3, 0, 0.2]);
  near(pointAtArcLength(xyz, 0.7), [0.3, 0, 0.4]);
});

test('arc lengths past the ends are clamped; coincident nodes and no nodes are handled', () => {
  const xyz = [1, 2, 3, 1, 2, 3, 2, 2, 3];
  near(pointAtArcLength(xyz, -1), [1, 2, 3]);
  near(pointAtArcLength(xyz, 5), [2, 2, 3]);
  near(pointAtArcLength(xyz, 0.5), [1.5, 2, 3]);
  assert.equal(pointAtArcLength([], 0.1), null);
  near(pointAtArcLength(xyz, Number.NaN), [1, 2, 3]);
});
