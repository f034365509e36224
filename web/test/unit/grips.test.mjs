// Unit tests of the grip choice (web/src/grips.ts): cycling per VR controller and the
// keys that override the panel's choice for a mouse grab.

import assert from 'node:assert/strict';
import path from 'node:path';
import { test } from 'node:test';
import { fileURLToPath, pathToFileURL } from 'node:url';

const here = path.dirname(fileURLToPath(import.meta.url));
const { GRIPS, gripFor, gripOfKey, isGrip, nextGrip } = await import(
  pathToFileURL(path.join(here, '..', '..', '..', 'target', 'web-unit', 'grips.js')).href
);

test('cycling goes firm → axial → ball → firm', () => {
  assert.deepEqual(GRIPS, ['firm', 'axial', 'ball']);
  assert.equal(nextGrip('firm'), 'axial');
  assert.equal(nextGrip('axial'), 'ball');
  assert.equal(nextGrip('ball'), 'firm');
  let g = 'firm';
  for (let i = 0; i < 3; i++) g = nextGrip(g);
  assert.equal(g, 'firm');
});

test('a grip key held at the grab overrides the panel, the newest one wins', () => {
  assert.equal(gripFor('axial', []), 'axial');
  assert.equal(gripFor('firm', ['KeyB']), 'ball');
  assert.equal(gripFor('ball', ['KeyF']), 'firm');
  assert.equal(gripFor('firm', ['KeyA', 'ShiftLeft', 'KeyB']), 'ball');
  assert.equal(gripFor('firm', new Set(['KeyB', 'KeyA'])), 'axial');
  assert.equal(gripOfKey('KeyX'), null);
  assert.ok(isGrip('ball') && !isGrip('loose') && !isGrip(undefined));
});
