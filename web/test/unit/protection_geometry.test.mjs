// Unit tests of drawing protections and junction bodies (web/src/protection_geometry.ts,
// web/src/junction_geometry.ts): pure functions over the tube's ring arrays.

import assert from 'node:assert/strict';
import path from 'node:path';
import { test } from 'node:test';
import { fileURLToPath, pathToFileURL } from 'node:url';

const here = path.dirname(fileURLToPath(import.meta.url));
const built = (f) => pathToFileURL(path.join(here, '..', '..', '..', 'target', 'web-unit', f)).href;
const { fillProtection, protectionStyle, ringRange, ringScale, ringShade, tubeIndices } = await import(
  built('protection_geometry.js')
);
const { hubRadius, junctionPose } = await import(built('junction_geometry.js'));

test('a stretch covers the rings at its arc lengths, at least two', () => {
  // 41 rings over 1 m: ring k at k/40 m
  assert.deepEqual(ringRange(0, 1, 1, 41), [0, 40]);
  assert.deepEqual(ringRange(0.25, 0.5, 1, 41), [10, 20]);
  assert.deepEqual(ringRange(0.0386, 0.9349, 0.2587 / 0.2587, 41), [2, 37]);
  // shorter than a ring spacing: still drawn over two rings
  assert.deepEqual(ringRange(0.5, 0.501, 1, 41), [20, 21]);
  assert.deepEqual(ringRange(0.999, 1, 1, 41), [39, 40]);
  // past the end: clamped
  assert.deepEqual(ringRange(0.5, 2, 1, 41), [20, 40]);
  // empty stretches and hoses draw nothing
  assert.equal(ringRange(0.5, 0.5, 1, 41), null);
  assert.equal(ringRange(0, 1, 0, 41), null);
  assert.equal(ringRange(0, 1, 1, 1), null);
});

test('kinds look different: the corrugated tube is ribbed and the largest, tape banded', () => {
  const tube = protectionStyle('corrugated_tube');
  const tape = protectionStyle('tape');
  const sleeve = protectionStyle('sleeve');
  assert.ok(ringScale(tube, 0) !== ringScale(tube, 1), 'ribs: every other ring larger');
  assert.ok(Math.min(ringScale(tube, 0), ringScale(tube, 1)) > ringScale(sleeve, 0));
  assert.ok(ringScale(sleeve, 0) > ringScale(tape, 0) && ringScale(tape, 0) > 1);
  assert.equal(ringScale(tape, 0), ringScale(tape, 1), 'tape is smooth');
  assert.ok(ringShade(tape, 1) < ringShade(tape, 0), 'tape shows bands');
  assert.equal(ringShade(sleeve, 1), ringShade(sleeve, 0), 'a sleeve is plain');
  assert.ok(ringShade(tube, 0) < ringShade(sleeve, 0) && ringShade(sleeve, 0) < ringShade(tape, 0), 'the tube darkest');
  assert.ok(sleeve.roughness > tape.roughness, 'a sleeve is matte');
  assert.deepEqual(protectionStyle('no_such_kind'), protectionStyle('other'));
});

test('a protection lies over its rings, pushed out from the centres by its factor', () => {
  // a straight tube along x: 5 rings, 4 segments around (5 vertices per ring), radius 2
  const radial = 4;
  const rings = 5;
  const centre = new Float32Array(rings * 3);
  const pos = new Float32Array(rings * (radial + 1) * 3);
  for (let k = 0; k < rings; k++) {
    centre[3 * k] = k;
    for (let j = 0; j <= radial; j++) {
      const a = (j / radial) * 2 * Math.PI;
      const v = 3 * (k * (radial + 1) + j);
      pos[v] = k;
      pos[v + 1] = 2 * Math.cos(a);
      pos[v + 2] = 2 * Math.sin(a);
    }
  }
  // the hose coloured by ring: red, green, blue, …
  const rgb = new Float32Array(pos.length);
  for (let v = 0; v < rgb.length / 3; v++) rgb[3 * v + (Math.floor(v / (radial + 1)) % 3)] = 1;
  const style = protectionStyle('corrugated_tube');
  const out = new Float32Array(3 * (radial + 1) * 3);
  const outRgb = new Float32Array(out.length);
  fillProtection(pos, rgb, centre, radial, 1, 3, style, out, outRgb);
  for (let k = 1; k <= 3; k++) {
    for (let j = 0; j <= radial; j++) {
      const o = 3 * ((k - 1) * (radial + 1) + j);
      assert.ok(Math.abs(out[o] - k) < 1e-6, 'on its ring');
      const r = Math.hypot(out[o + 1], out[o + 2]);
      assert.ok(Math.abs(r - 2 * ringScale(style, k)) < 1e-5, `ring ${k}: radius ${r}`);
      // the hose's colour there, shaded: the colour mode shows through
      for (let d = 0; d < 3; d++) {
        const want = d === k % 3 ? ringShade(style, k) : 0;
        assert.ok(Math.abs(outRgb[o + d] - want) < 1e-6, `ring ${k} colour ${d}`);
      }
    }
  }
  // two triangles per quad: (rings − 1) · radial · 6 indices, all within the vertices
  const idx = tubeIndices(3, radial);
  assert.equal(idx.length, 2 * radial * 6);
  assert.ok(Math.max(...idx) === 3 * (radial + 1) - 1 && Math.min(...idx) === 0);
  // every triangle faces outwards (front faces are drawn): its normal along the radius
  // (the rings run n → b = t × n; here t = x, n = y, b = z as in the sweep)
  for (let f = 0; f < idx.length; f += 3) {
    const v = [0, 1, 2].map((c) => [0, 1, 2].map((d) => out[3 * idx[f + c] + d]));
    const e1 = v[1].map((x, d) => x - v[0][d]);
    const e2 = v[2].map((x, d) => x - v[0][d]);
    const n = [e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]];
    const mid = [0, 1, 2].map((d) => (v[0][d] + v[1][d] + v[2][d]) / 3);
    assert.ok(n[1] * mid[1] + n[2] * mid[2] > 0, `triangle ${f / 3} faces inwards`);
  }
});

test('a junction body sits at the mean of its outlets, an arm reaching each', () => {
  const pose = junctionPose([
    [0.1, 0, 0],
    [-0.1, 0, 0],
    [0, 0.3, 0],
  ]);
  assert.deepEqual(pose.centre.map((x) => Math.round(x * 1e12) / 1e12), [0, 0.1, 0]);
  assert.equal(pose.arms.length, 3);
  const a = pose.arms[2];
  assert.ok(Math.abs(a.length - 0.2) < 1e-12);
  assert.deepEqual(a.direction.map((x) => Math.round(x * 1e12) / 1e12), [0, 1, 0]);
  const b = pose.arms[0];
  assert.ok(Math.abs(b.length - Math.hypot(0.1, 0.1)) < 1e-12);
  // outlets at one point: arms of zero length, a unit direction all the same
  const p = junctionPose([
    [1, 2, 3],
    [1, 2, 3],
  ]);
  assert.deepEqual(p.centre, [1, 2, 3]);
  assert.equal(p.arms[0].length, 0);
  assert.equal(Math.hypot(...p.arms[0].direction), 1);
  // the hub is thicker than its thickest outlet
  assert.ok(hubRadius([0.004, 0.006]) > 0.006);
  assert.equal(hubRadius([]), 0.002);
});
