// Unit tests of the VR body's `worker_pose` message (web/src/xr_body.ts): the gaze from
// the eyes to a point ahead, hands by handedness, nothing non-finite sent, the rate.

import assert from 'node:assert/strict';
import path from 'node:path';
import { test } from 'node:test';
import { fileURLToPath, pathToFileURL } from 'node:url';

const here = path.dirname(fileURLToPath(import.meta.url));
const B = await import(pathToFileURL(path.join(here, '..', '..', '..', 'target', 'web-unit', 'xr_body.js')).href);

test('head and hands by handedness', () => {
  const m = B.bodyPoseMessage([0, 0, 1.6], [1, 0, 1.1], [
    { handedness: 'left', position: [0.3, 0.2, 1] },
    { handedness: 'right', position: [0.3, -0.2, 1] },
  ]);
  assert.deepEqual(m, { type: 'worker_pose', head: { position: [0, 0, 1.6], gaze: [1, 0, 1.1 - 1.6] }, hands: [[0.3, -0.2, 1], [0.3, 0.2, 1]] });
});

test('untracked or non-finite parts are left out; nothing at all sends nothing', () => {
  const m = B.bodyPoseMessage([0, NaN, 1.6], [1, 0, 1], [{ handedness: 'right', position: [0.3, -0.2, 1] }, { handedness: 'none', position: [1, 1, 1] }]);
  assert.deepEqual(m, { type: 'worker_pose', hands: [[0.3, -0.2, 1], null] });
  assert.equal(B.bodyPoseMessage([0, 0, 1.6], [0, 0, 1.6], []), null, 'a zero gaze is no head');
  assert.equal(B.bodyPoseMessage(null, null, [{ handedness: 'left', position: null }]), null);
});

test('at most BODY_POSE_HZ a second', () => {
  const gap = 1000 / B.BODY_POSE_HZ;
  assert.equal(B.bodyPoseDue(1000 + gap, 1000), true);
  assert.equal(B.bodyPoseDue(1000 + gap - 1, 1000), false);
  assert.equal(B.bodyPoseDue(0, -Infinity), true);
});
