// Unit tests of the viewer's mode (web/src/app_mode.ts): live, replay and author, and
// what each event does in each mode.

import assert from 'node:assert/strict';
import path from 'node:path';
import { test } from 'node:test';
import { fileURLToPath, pathToFileURL } from 'node:url';

const here = path.dirname(fileURLToPath(import.meta.url));
const { nextMode, drawsLive, handsAct } = await import(pathToFileURL(path.join(here, '..', '..', '..', 'target', 'web-unit', 'app_mode.js')).href);

test('every event in every mode', () => {
  const table = {
    live: { replay: 'replay', live: 'live', toggle_author: 'author' },
    replay: { replay: 'replay', live: 'live', toggle_author: 'author' },
    author: { replay: 'replay', live: 'author', toggle_author: 'live' },
  };
  for (const [mode, events] of Object.entries(table)) {
    for (const [event, want] of Object.entries(events)) assert.equal(nextMode(mode, event), want, `${mode} + ${event}`);
  }
});

test('only live lets hands act; only a replay draws a recording', () => {
  assert.deepEqual(['live', 'replay', 'author'].map(handsAct), [true, false, false]);
  assert.deepEqual(['live', 'replay', 'author'].map(drawsLive), [true, false, true]);
});
