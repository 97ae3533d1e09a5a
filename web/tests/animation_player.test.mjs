// Animation playback's state (web/lib/animation.mjs) without a browser: choosing an animation by
// name, index or default, one-line errors for names a model lacks, the time advancing while
// playing in real time (a long gap counts a second), looping at the end, pausing, seeking, and a
// pose handed to the renderer only when it changed; a crossfade from one animation to the next.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { AnimationPlayer } from '../lib/animation.mjs';

const clips = [{ name: 'Survey', duration: 3.4 }, { name: 'Run', duration: 0.8 }];

test('an animation is chosen by name, by index, or the first by default', () => {
  const p = new AnimationPlayer();
  p.reset(clips);
  assert.equal(p.select('Run'), 1);
  assert.equal(p.duration, 0.8);
  assert.equal(p.select('0'), 0);
  assert.equal(p.select(null), 0);
  assert.throws(() => p.select('Jump'), /no animation "Jump"; the model has Survey, Run/);
  p.reset([]);
  assert.equal(p.select(null), -1, 'a model without animations: nothing, no error');
  assert.throws(() => p.select('Run'), /no animation "Run": the model has none/);
  assert.equal(p.play(0), false);
});

test('playing advances the time by the frames\' gaps, loops, and pausing holds it', () => {
  let woken = 0;
  const p = new AnimationPlayer(() => woken++);
  p.reset(clips);
  p.select('Run');
  assert.deepEqual(p.advance(0), [1, 0, -1, 0, 0], 'the first pose is sent once');
  assert.equal(p.advance(10), null, 'not playing: nothing new to pose');
  assert.ok(p.play(1000));
  assert.ok(woken >= 2, 'choosing and playing wake the loop');
  assert.equal(p.advance(1000), null, 'no time has passed');
  const [, t1] = p.advance(1050);
  assert.ok(Math.abs(t1 - 0.05) < 1e-9, `0.05 s after 50 ms (${t1})`);
  const [, t2] = p.advance(1350);
  assert.ok(Math.abs(t2 - 0.35) < 1e-9, `a slow frame's 300 ms count in full (${t2})`);
  p.advance(1850);  // 0.85: past the end of 0.8 s
  assert.ok(Math.abs(p.time - 0.05) < 1e-6, `looped past 0.8 s to ${p.time}`);
  p.crossfadeMs = 0;   // (the crossfade has its own test)
  p.select('Survey');  // from 0 s
  p.advance(2000);     // 0.15 s
  const [, t3] = p.advance(7000);
  assert.ok(Math.abs(t3 - 1.15) < 1e-9, `a 5 s gap (a background tab) counts 1 s (${t3})`);
  p.select('Run');
  p.advance(7100);  // its first pose sent
  p.pause();
  assert.equal(p.advance(9000), null, 'paused: the time holds');
  p.seek(-0.2);
  assert.ok(Math.abs(p.time - 0.6) < 1e-9, 'seeking wraps into [0, duration)');
  assert.deepEqual(p.advance(9100), [1, p.time, -1, 0, 0], 'a seek is posed');
  assert.throws(() => p.seek(NaN), /currentTime must be a number/);
  p.rest();
  assert.deepEqual(p.advance(9200), [-1, 0, -1, 0, 0], 'back to the rest pose, sent once');
  assert.equal(p.advance(9300), null);
});

test('a new animation chosen while playing fades in over crossfadeMs, as model-viewer\'s', () => {
  const p = new AnimationPlayer();
  p.reset(clips);
  assert.equal(p.crossfadeMs, 300, "model-viewer's default");
  p.select('Survey');
  p.play(0);
  p.advance(0);
  p.advance(500);  // Survey at 0.5 s
  p.select('Run');
  const [index, time, from, fromTime, fromWeight] = p.advance(600);
  assert.deepEqual([index, from], [1, 0], 'Run over Survey');
  assert.ok(Math.abs(time - 0.1) < 1e-9 && Math.abs(fromTime - 0.6) < 1e-9, `${time} ${fromTime}`);
  assert.ok(Math.abs(fromWeight - 2 / 3) < 1e-9, `a third of the way: ${fromWeight}`);
  assert.deepEqual(p.advance(800).slice(2), [-1, 0, 0], 'faded out 300 ms after the choice');
  p.pause();
  p.play(1000);
  p.select('Survey');
  p.pause();
  assert.deepEqual(p.advance(1100).slice(2), [-1, 0, 0], 'paused: no crossfade');
});
