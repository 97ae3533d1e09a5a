// Orbit camera and controls (web/lib/orbit.mjs) without a browser: the camera math, and the
// pointer handling fed with synthetic events on a plain EventTarget standing in for the canvas
// (mouse drag, right drag, shift drag, wheel, one-finger orbit, two-finger pinch and pan).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { OrbitCamera, attachOrbitControls, cameraFromOptions } from '../lib/orbit.mjs';

const close = (a, b, eps = 1e-5) => a.every((v, i) => Math.abs(v - b[i]) <= eps);
const bounds = { min: [-1, 0, -1], max: [1, 2, 1] };

function makeElement() {
  const el = new EventTarget();
  el.style = { touchAction: '' };
  el.clientHeight = 200;
  return el;
}
function pointer(el, type, { id = 1, x = 0, y = 0, button = 0, kind = 'mouse', shift = false } = {}) {
  el.dispatchEvent(Object.assign(new Event(type, { cancelable: true }),
                                 { pointerId: id, clientX: x, clientY: y, button,
                                   pointerType: kind, shiftKey: shift }));
}

test('fromCamera keeps the view: same eye, pivot on the view ray', () => {
  const eye = [0, 1, 4];
  const o = OrbitCamera.fromCamera({ eye, forward: [0, 0, -1], yfov: 0.7 }, bounds);
  assert.ok(close(o.eye(), eye), `eye ${o.eye()}`);
  assert.ok(close(o.target, [0, 1, 0]), `target ${o.target}`);  // nearest point to the centre
  assert.equal(o.yfov, 0.7);
  const c = o.toCamera();
  assert.deepEqual(c.up, [0, 1, 0]);
});

test('orbit turns about the pivot at constant distance; pitch stays below the pole', () => {
  const o = OrbitCamera.fromCamera({ eye: [0, 1, 4], forward: [0, 0, -1], yfov: 0.7 }, bounds);
  const d = o.distance;
  o.orbit(100, 0, 200);  // half the height: a quarter turn... times two = 90 degrees
  assert.ok(Math.abs(Math.hypot(...o.eye().map((v, i) => v - o.target[i])) - d) < 1e-5);
  assert.ok(Math.abs(o.yaw + Math.PI / 2) < 1e-6, `yaw ${o.yaw}`);
  o.orbit(0, 10_000, 200);
  assert.ok(o.pitch < Math.PI / 2 && o.pitch > 1.5);
});

test('pan moves the pivot in the view plane; zoom is bounded by the scene size', () => {
  const o = OrbitCamera.fromCamera({ eye: [0, 1, 4], forward: [0, 0, -1], yfov: 0.7 }, bounds);
  o.pan(10, 0, 200);  // drag right: the scene follows, the pivot moves left (-X)
  assert.ok(o.target[0] < 0 && Math.abs(o.target[2]) < 1e-6);
  o.zoom(1e-9);
  assert.ok(o.distance >= o.radius * 0.02 - 1e-9);
  o.zoom(1e9);
  assert.ok(o.distance <= o.radius * 50 + 1e-9);
});

test('mouse: left drag orbits, right or shift drag pans, wheel zooms, double click resets', () => {
  const el = makeElement();
  const o = OrbitCamera.fromCamera({ eye: [0, 1, 4], forward: [0, 0, -1], yfov: 0.7 }, bounds);
  let changes = 0, resets = 0;
  const ctl = attachOrbitControls(el, o, { onChange: () => changes++, onReset: () => resets++ });
  assert.equal(el.style.touchAction, 'none');
  pointer(el, 'pointerdown', { x: 10, y: 10 });
  assert.equal(ctl.active, true);
  pointer(el, 'pointermove', { x: 30, y: 10 });
  pointer(el, 'pointerup', { x: 30, y: 10 });
  assert.equal(ctl.active, false);
  assert.ok(o.yaw < 0 && changes === 1);
  const t0 = [...o.target];
  pointer(el, 'pointerdown', { id: 2, button: 2, x: 0, y: 0 });
  pointer(el, 'pointermove', { id: 2, button: 2, x: 0, y: 20 });
  pointer(el, 'pointerup', { id: 2 });
  assert.ok(o.target[1] > t0[1], 'right drag down moves the pivot up');
  const t1 = [...o.target];
  pointer(el, 'pointerdown', { id: 3, x: 0, y: 0, shift: true });
  pointer(el, 'pointermove', { id: 3, x: 20, y: 0, shift: true });
  pointer(el, 'pointerup', { id: 3 });
  assert.ok(!close(o.target, t1), 'shift drag pans');
  const d = o.distance;
  el.dispatchEvent(Object.assign(new Event('wheel', { cancelable: true }), { deltaY: -100, deltaMode: 0 }));
  assert.ok(o.distance < d, 'wheel up zooms in');
  el.dispatchEvent(new Event('dblclick'));
  assert.equal(resets, 1);
  ctl.detach();
  assert.equal(el.style.touchAction, '');
});

test('touch: one finger orbits, two fingers pinch to zoom and move together to pan', () => {
  const el = makeElement();
  const o = OrbitCamera.fromCamera({ eye: [0, 1, 4], forward: [0, 0, -1], yfov: 0.7 }, bounds);
  attachOrbitControls(el, o);
  pointer(el, 'pointerdown', { id: 7, kind: 'touch', x: 50, y: 50 });
  pointer(el, 'pointermove', { id: 7, kind: 'touch', x: 80, y: 50 });
  assert.ok(o.yaw < 0, 'one finger orbits');
  const yaw = o.yaw, d = o.distance;
  // Second finger: spread apart (pinch out) = zoom in, no further orbit.
  pointer(el, 'pointerdown', { id: 8, kind: 'touch', x: 120, y: 50 });
  pointer(el, 'pointermove', { id: 8, kind: 'touch', x: 160, y: 50 });
  assert.ok(o.distance < d, `pinch out zooms in (${o.distance} vs ${d})`);
  assert.equal(o.yaw, yaw);
  // Both fingers move down together: pan.
  const t = [...o.target];
  pointer(el, 'pointermove', { id: 7, kind: 'touch', x: 80, y: 90 });
  pointer(el, 'pointermove', { id: 8, kind: 'touch', x: 160, y: 90 });
  assert.ok(o.target[1] > t[1], 'two-finger drag pans');
  pointer(el, 'pointerup', { id: 7, kind: 'touch' });
  pointer(el, 'pointerup', { id: 8, kind: 'touch' });
});

test('controls given a getter act on whichever camera it returns, and idle without one', () => {
  const el = makeElement();
  let current = null;
  const ctl = attachOrbitControls(el, () => current);
  pointer(el, 'pointerdown', { x: 10, y: 10 });
  pointer(el, 'pointermove', { x: 30, y: 10 });  // no camera yet: nothing to move, no throw
  pointer(el, 'pointerup', { x: 30, y: 10 });
  current = OrbitCamera.fromCamera({ eye: [0, 1, 4], forward: [0, 0, -1], yfov: 0.7 }, bounds);
  pointer(el, 'pointerdown', { x: 10, y: 10 });
  pointer(el, 'pointermove', { x: 30, y: 10 });
  pointer(el, 'pointerup', { x: 30, y: 10 });
  assert.ok(current.yaw < 0, 'the camera set later orbits');
  ctl.detach();
});

test('setCamera options: eye and target required, up and yfov defaulted, bad vectors named', () => {
  assert.deepEqual(cameraFromOptions({ eye: [0, 0, 5], target: [0, 0, 0] }, 0.8),
                   { eye: [0, 0, 5], target: [0, 0, 0], up: [0, 1, 0], yfov: 0.8 });
  assert.equal(cameraFromOptions({ eye: [1, 2, 3], target: [0, 0, 0], yfov: 0.5 }, 0.8).yfov, 0.5);
  assert.equal(cameraFromOptions(null, 0.8).error, "camera: 'eye' must be [x, y, z]");
  assert.equal(cameraFromOptions({ eye: [0, 0, 5], target: [0, NaN, 0] }, 0.8).error,
               "camera: 'target' must be [x, y, z]");
  assert.equal(cameraFromOptions({ eye: [0, 0, 5], target: [0, 0, 0], up: [0, 1] }, 0.8).error,
               "camera: 'up' must be [x, y, z]");
});
