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
