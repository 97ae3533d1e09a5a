// The progress line's rules (web/lib/progress.mjs) in node alone: monotone, at most 25 points
// a frame, a time left only after frame 8, Done at the stop, a new view from 0.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { ETA_FROM_FRAME, MAX_STEP, ProgressMeter } from '../lib/progress.mjs';

test('the percentage never goes back and never jumps by more than 25 points', () => {
  const m = new ProgressMeter();
  // An automatic view: its total starts at the cap, then the estimate moves both ways.
  const totals = [1024, 1024, 1024, 326, 652, 230, 136, 162, 136, 136];
  let last = 0;
  const seen = [];
  for (let i = 0; i < totals.length; i++) {
    const frame = [1, 2, 4, 6, 8, 10, 12, 14, 17, 20][i];
    const { percent, done } = m.update({ frame, total: totals[i], converged: false, frameMs: 50 });
    assert.equal(done, false);
    assert.ok(percent >= last, `frame ${frame}: ${percent} after ${last}`);
    assert.ok(percent - last <= MAX_STEP, `frame ${frame}: jumped from ${last} to ${percent}`);
    assert.ok(percent <= 99);
    seen.push(percent);
    last = percent;
  }
  assert.ok(seen.at(-1) > 0, 'it moves');
  // Redrawn without a new frame: the same figure.
  assert.equal(m.update({ frame: 20, total: 40, converged: false, frameMs: 50 }).percent, last);
  assert.deepEqual(m.update({ frame: 22, total: 22, converged: true, frameMs: 50 }),
                   { percent: 100, secondsLeft: 0, done: true });
  // A new view starts again from 0.
  assert.equal(m.update({ frame: 1, total: 1024, converged: false, frameMs: 50 }).percent, 0);
});

test('the time left is shown only once the view has measured itself', () => {
  const m = new ProgressMeter();
  assert.equal(m.update({ frame: ETA_FROM_FRAME - 1, total: 1024, converged: false, frameMs: 100 })
    .secondsLeft, null);
  const { secondsLeft } = m.update({ frame: 10, total: 110, converged: false, frameMs: 100 });
  assert.equal(secondsLeft, 10);
  assert.equal(m.update({ frame: 11, total: 110, converged: false, frameMs: 0 }).secondsLeft, null,
               'no frame time yet');
});

test('the time left prices the frames left at the last few frames\' mean cost', () => {
  const m = new ProgressMeter();
  // Early frames dear (first light, the volume filling), later ones cheap (tiles skipped).
  let left = null;
  for (let frame = 1; frame <= 20; frame++) {
    left = m.update({ frame, total: 120, converged: false, frameMs: frame <= 10 ? 400 : 100 })
      .secondsLeft;
  }
  assert.equal(left, (100 * 100) / 1000, 'the last 8 frames cost 100 ms each');
  // One dear frame among them moves the price by its share of the window only.
  left = m.update({ frame: 21, total: 120, converged: false, frameMs: 900 }).secondsLeft;
  assert.equal(left, (99 * (7 * 100 + 900)) / 8 / 1000);
});
