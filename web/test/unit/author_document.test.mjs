// Unit tests of the Author mode's document and undo (web/src/author_document.ts): the
// scene document written from the authored hoses, stubs and clips over the served scene,
// in the file's unit, and the edit history.

import assert from 'node:assert/strict';
import path from 'node:path';
import { test } from 'node:test';
import { fileURLToPath, pathToFileURL } from 'node:url';

const here = path.dirname(fileURLToPath(import.meta.url));
const { EditHistory, sceneDocument, toFileUnit } = await import(pathToFileURL(path.join(here, '..', '..', '..', 'target', 'web-unit', 'author_document.js')).href);

const base = () => ({
  format: 'pliant-scene', version: 1, length_unit: 'mm',
  hoses: [{ name: 'old', material: 'hose3', start: [0, 0, 0], path: [{ line: { to: [100, 0, 0] } }] }],
  parts: [{ name: 'plate', box: { size: [10, 10, 1] } }],
  timeline: [{ action: 'fix', hose: 'old', node: 0 }],
});

test('authored hoses, stubs and clips are appended to the served scene, in millimetres', () => {
  const state = {
    base: base(),
    hoses: [
      { name: 'a', material: 'hose3', section: null, points: [[0, 0, 0.1], [0.2, 0, 0.1]], fixStart: true },
      { name: 'b', material: 'hose1', section: { d_inner: 0.008, d_outer: 0.0125 }, points: [[0, 0, 0], [0.1, 0.1, 0], [0.2, 0, -0.0000001]], fixStart: false },
      { name: 'one point', material: 'hose3', section: null, points: [[0, 0, 0]], fixStart: true },
    ],
    stubs: [{ name: 's', origin: [0.3, 0, 0.1], axis: [0, 0, -2], length: 0.03, diameter: 0.03, hose: 'a', end: 'end' }],
    clips: [
      { name: 'c', origin: [0.1, 0, 0.1], opening: [0, 0, 3], orientation: [4, 0, 0], type: 'cable_tie', opening_width: 0.01, inner_diameter: 0.035, snap_force_n: 40, hose: null },
      { name: 'd', origin: [0.15, 0, 0.1], opening: [0, 0, 1], orientation: [1, 0, 0], type: 'fixed', opening_width: 0.01, inner_diameter: 0.035, snap_force_n: 40, hose: 'a' },
    ],
  };
  const before = JSON.stringify(state.base);
  const doc = sceneDocument(state, 'mine', 'mm');
  assert.equal(JSON.stringify(state.base), before, 'the base document is not changed');
  assert.equal(doc.name, 'mine');
  assert.deepEqual(doc.hoses.map((h) => h.name), ['old', 'a', 'b'], 'a hose of one point is not written');
  assert.deepEqual(doc.hoses[1], { name: 'a', material: 'hose3', start: [0, 0, 100], path: [{ line: { to: [200, 0, 100] } }] });
  assert.deepEqual(doc.hoses[2].section, { d_inner: 8, d_outer: 12.5 });
  assert.deepEqual(doc.hoses[2].path, [{ spline: { through: [[100, 100, 0]], to: [200, 0, 0] } }], 'no −0 in the file');
  assert.ok(!Object.is(doc.hoses[2].path[0].spline.to[2], -0));
  assert.deepEqual(doc.stubs, [{ name: 's', origin: [300, 0, 100], axis: [0, 0, -1], length: 30, diameter: 30, hose: 'a', end: 'end' }]);
  assert.equal('snap_force_n' in doc.clips[0], false, 'a cable tie has no snap force');
  assert.deepEqual(doc.clips[0].opening, [0, 0, 1]);
  assert.deepEqual(doc.clips[0].orientation, [1, 0, 0]);
  assert.equal(doc.clips[1].snap_force_n, 40);
  assert.equal(doc.clips[1].hose, 'a');
  // the fixes of authored hoses come first, then the served timeline
  assert.deepEqual(doc.timeline, [{ action: 'fix', hose: 'a', node: 0 }, { action: 'fix', hose: 'old', node: 0 }]);
});

test('metres stay metres, rounded to a micrometre; no timeline when there is none', () => {
  assert.equal(toFileUnit(0.1234567, 'm'), 0.123457);
  assert.equal(toFileUnit(0.1234567, 'mm'), 123.457);
  const b = base();
  delete b.timeline;
  const doc = sceneDocument({ base: b, hoses: [{ name: 'a', material: 'hose3', section: null, points: [[0, 0, 0], [1.0000004, 0, 0]], fixStart: false }], stubs: [], clips: [] }, 'n', 'm');
  assert.deepEqual(doc.hoses[1].path, [{ line: { to: [1, 0, 0] } }]);
  assert.equal('timeline' in doc, false);
  assert.equal('stubs' in doc, false);
});

test('undo and redo walk the history; a new edit drops the redo; the oldest are forgotten', () => {
  const h = new EditHistory(3);
  assert.equal(h.untouched, true);
  assert.equal(h.undo('s0'), null);
  // edits s0 → s1 → s2 → s3
  h.record('s0');
  h.record('s1');
  h.record('s2');
  assert.deepEqual([h.canUndo, h.canRedo, h.untouched], [true, false, false]);
  assert.equal(h.undo('s3'), 's2');
  assert.equal(h.undo('s2'), 's1');
  assert.equal(h.canRedo, true);
  assert.equal(h.redo('s1'), 's2');
  assert.equal(h.redo('s2'), 's3');
  assert.equal(h.redo('s3'), null);
  // undo once, then edit: the undone step cannot be redone
  assert.equal(h.undo('s3'), 's2');
  h.record('s2');
  assert.equal(h.canRedo, false);
  // limit 3: two more edits push out the oldest two
  h.record('x');
  h.record('y');
  const seen = [];
  for (let s = h.undo('now'); s !== null; s = h.undo(s)) seen.push(s);
  assert.deepEqual(seen, ['y', 'x', 's2']);
});
