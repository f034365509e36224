// Unit tests of the colour modes and their legends (web/src/colour_modes.ts), compiled by
// `npm run test:unit` into target/web-unit first.

import assert from 'node:assert/strict';
import path from 'node:path';
import { test } from 'node:test';
import { fileURLToPath, pathToFileURL } from 'node:url';

const here = path.dirname(fileURLToPath(import.meta.url));
const { beamValues, colourValueOf, growAxialScale, legendRange, niceCeil, nodeColourValues } = await import(
  pathToFileURL(path.join(here, '..', '..', '..', 'target', 'web-unit', 'colour_modes.js')).href
);

const close = (a, b, eps = 1e-6) => assert.ok(Math.abs(a - b) <= eps, `${a} ≠ ${b}`);

test('bend radius: the ratio to the minimum is the colour value, red at and past the minimum', () => {
  const r = legendRange('bend_radius', null, 0);
  assert.equal(r.signed, false);
  close(colourValueOf(r, 0), 0); // straight: blue
  close(colourValueOf(r, 0.5), 0.5); // twice the minimum radius: green
  close(colourValueOf(r, 1), 1); // at the minimum: red
  close(colourValueOf(r, 3.3), 1);
  assert.match(r.ticks[2], /minimum/);
});

test('twist: judged by magnitude against the limit from the welcome, shown in °/m', () => {
  const limit = (20 * Math.PI) / 180;
  const r = legendRange('twist', limit, 0);
  close(r.scale, limit);
  close(colourValueOf(r, -limit / 2), 0.5);
  close(colourValueOf(r, limit), 1);
  assert.equal(r.unit, '°/m');
  assert.equal(r.ticks[2], '≥ 20 °/m (limit)');
  // no limit sent (check off): the checks' default 10 °/m
  close(legendRange('twist', null, 0).scale, (10 * Math.PI) / 180);
});

test('axial force: signed, zero in the middle, compression blue, tension red', () => {
  const r = legendRange('axial_force', null, 50);
  assert.equal(r.signed, true);
  close(colourValueOf(r, 0), 0.5);
  close(colourValueOf(r, -50), 0);
  close(colourValueOf(r, 25), 0.75);
  close(colourValueOf(r, 500), 1);
  assert.deepEqual(r.ticks, ['−50 N (compression)', '0', '+50 N (tension)']);
  assert.equal(colourValueOf(r, Number.NaN), 1, 'never NaN: non-finite is red');
});

test('the axial scale grows to a round value and does not shrink', () => {
  assert.equal(niceCeil(3.2), 5);
  assert.equal(niceCeil(0.7), 1);
  assert.equal(niceCeil(120), 200);
  assert.equal(niceCeil(1000), 1000);
  let s = growAxialScale(0, [{ colour: 0, axial_force: [0.1, -0.2] }]);
  assert.equal(s, 1, 'at least 1 N');
  s = growAxialScale(s, [{ colour: 0, axial_force: [12, -31] }]);
  assert.equal(s, 50);
  assert.equal(growAxialScale(s, [{ colour: 0, axial_force: [3] }]), 50);
});

test('per-node values take the worse of the two beams; hand load has none', () => {
  const r = legendRange('bend_radius', null, 0);
  const out = nodeColourValues(r, [0.2, 1.5, 0.1], new Float32Array(4));
  assert.deepEqual(Array.from(out).map((x) => +x.toFixed(3)), [0.2, 1, 1, 0.1]);
  const a = legendRange('axial_force', null, 10);
  const signed = nodeColourValues(a, [-10, 2], new Float32Array(3));
  assert.deepEqual(Array.from(signed).map((x) => +x.toFixed(3)), [0, 0, 0.6]);
  assert.equal(beamValues('hand_load', { colour: 0.3, twist: [1] }), null);
  assert.deepEqual(beamValues('twist', { colour: 0, twist: [1, 2] }), [1, 2]);
  assert.equal(beamValues('bend_radius', { colour: 0 }), null, 'no minimum: one colour');
});
