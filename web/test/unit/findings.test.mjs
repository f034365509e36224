// Unit tests of the verdict's findings as the panel lists them (web/src/findings.ts):
// whom each names, the value against its limit, the time, and the hose and part a click
// highlights; and the seek of a replay to a finding's time (web/src/record.ts).

import assert from 'node:assert/strict';
import path from 'node:path';
import { test } from 'node:test';
import { fileURLToPath, pathToFileURL } from 'node:url';

const here = path.dirname(fileURLToPath(import.meta.url));
const out = path.join(here, '..', '..', '..', 'target', 'web-unit');
const { findingRows, violationText } = await import(pathToFileURL(path.join(out, 'findings.js')).href);
const { frameAtSimulated } = await import(pathToFileURL(path.join(out, 'record.js')).href);

const hoses = ['coolant', 'harness'];
const parts = ['body', 'fan', 'door'];
const violation = {
  check: 'bend_radius', hose: 1, hose_name: 'harness', arc_length: 0.25, time: 1.5,
  value: 0.031, limit: 0.045, first_time: 1.2, last_time: 1.7, instants: 40, at: null,
};

test('rows name the hose and part, the value against the limit and the time', () => {
  const rows = findingRows({
    reasons: [
      { kind: 'check_violated', violation },
      { kind: 'hand_load_over_limit', hand: 4, load: 'pull', value: 212.34, limit: 180, ratio: 1.1797, time: 2.25, working: { fastener: 'clip', name: 'c1' } },
      { kind: 'clearance_violated', hose: 'coolant', part: 'fan', gap: 0.004, minimum: 0.01, time: 3, coordinate: 35, position: 'at door angle 35°' },
    ],
    pending: [{ kind: 'fastener_pending', fastener: 'stub', name: 's1', state: 'free' }],
    warnings: [{ kind: 'moment_above_guide', hand: 4, load: 'twist', value: 1.5, time: 2, guide_hi: 1, limit: 2, moments_decide: false }],
    zones: [],
    worker: [{ kind: 'worker', finding: { kind: 'collision', who: 'the 50th-percentile man', segment: 'forearm', part: 'door', depth: 0.012, time: 4, first_time: 3.9, last_time: 4.1 } }],
  }, hoses, parts);
  assert.deepEqual(rows.map((r) => [r.list, r.kind, r.hose, r.part, r.time]), [
    ['reasons', 'check_violated', 1, null, 1.5],
    ['reasons', 'hand_load_over_limit', null, null, 2.25],
    ['reasons', 'clearance_violated', 0, 1, 3],
    ['pending', 'fastener_pending', null, null, null],
    ['warnings', 'moment_above_guide', null, null, 2],
    ['worker', 'worker', null, 2, 4],
  ]);
  assert.equal(rows[0].subject, "hose 'harness'");
  assert.equal(rows[0].measure, 'bend radius 31 mm < 45 mm at s = 250 mm');
  assert.equal(rows[1].subject, "hand 4 at clip 'c1'");
  assert.equal(rows[1].measure, 'pull 212.3 N > 180.0 N (×1.18)');
  assert.equal(rows[2].measure, 'gap 4 mm < 10 mm at door angle 35°');
  assert.equal(rows[3].subject, "stub 's1'");
  assert.equal(rows[4].measure, 'twist 1.50 N·m > guide 1.00 N·m (limit 2.00 N·m)');
  assert.equal(rows[5].subject, "the 50th-percentile man: segment 'forearm' in part 'door'");
  assert.equal(rows[5].measure, '12 mm deep');
});

test('names and indices outside the session name nothing', () => {
  const rows = findingRows({
    reasons: [
      { kind: 'check_violated', violation: { ...violation, hose: 7 } },
      { kind: 'contact', part: 'roof', first_time: 0.5, last_time: 0.75 },
      { kind: 'instability', note: 'snapped_through', hose: 'coolant', time: 0.3, node: 12 },
    ],
    pending: [], warnings: [], zones: [],
  }, hoses, parts);
  assert.deepEqual(rows.map((r) => [r.hose, r.part, r.time]), [[null, null, 1.5], [null, null, 0.5], [0, null, 0.3]]);
  assert.equal(rows[2].measure, 'snapped through');
});

test('a range of motion names the hose nearest its allowed bend radius and the moving part', () => {
  const [r] = findingRows({
    reasons: [{
      kind: 'motion_extremes', coordinate: { part: 2, part_name: 'door', kind: 'hinge' }, from: 0, to: 70,
      bend_radii: [{ hose: 'coolant', radius: 0.08, allowed: 0.05, coordinate: 10 }, { hose: 'harness', radius: 0.031, allowed: 0.045, coordinate: 68 }],
    }],
    pending: [], warnings: [], zones: [],
  }, hoses, parts);
  assert.deepEqual([r.hose, r.part], [1, 2]);
  assert.equal(r.measure, "hose 'harness' bend radius 31 mm (allowed 45 mm) at 68.0");
});

test('verdicts that pass list what they checked, without a subject', () => {
  const rows = findingRows({
    reasons: [{ kind: 'within_limits_so_far', worst: { hand: 0, load: 'push', value: 50, limit: 100, ratio: 0.5, time: 1 } }, { kind: 'no_hand_acted', stage: 'running' }],
    pending: [], warnings: [], zones: [],
  }, hoses, parts);
  assert.equal(rows[0].measure, 'worst push 50.0 N of 100.0 N (×0.50)');
  assert.deepEqual([rows[1].subject, rows[1].measure, rows[1].time], ['', 'running', null]);
});

test('the violation texts of the markers and the panel', () => {
  assert.equal(violationText({ check: 'twist', value: Math.PI / 9, limit: Math.PI / 18 }), 'twist 20.0 °/m > 10.0 °/m');
  assert.equal(violationText({ check: 'tension_at_rest', value: 12.345, limit: 10 }), 'tension_at_rest 12.3 (limit 10.0)');
});

test('a replay seeks to the first frame at or after a finding’s simulated time', () => {
  const frames = [0, 0.1, 0.2, 0.3].map((time, i) => ({ t: i * 0.5, snapshot: { time } }));
  assert.equal(frameAtSimulated(frames, 0.15), 2);
  assert.equal(frameAtSimulated(frames, 0), 0);
  assert.equal(frameAtSimulated(frames, 0.3), 3);
  assert.equal(frameAtSimulated(frames, 9), 3, 'after the end: the last frame');
  assert.equal(frameAtSimulated([], 1), 0);
});
