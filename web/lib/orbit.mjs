// Orbit camera and its mouse/touch controls for the Penumbra viewer (web/lib/penumbra.mjs).
//
// The camera turns about a pivot near the scene's bounds centre, with world +Y up. It starts
// from the scene's own camera: the pivot is the point of that camera's view ray nearest to the
// bounds centre, so the first drag continues from the view the user sees instead of jumping.
// Mouse: left drag orbits, right drag or shift + left drag pans, the wheel zooms, a double
// click resets. Touch: one finger orbits, two fingers pinch to zoom and move to pan.

const sub = (a, b) => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
const add = (a, b) => [a[0] + b[0], a[1] + b[1], a[2] + b[2]];
const scale = (a, s) => [a[0] * s, a[1] * s, a[2] * s];
const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
                         a[0] * b[1] - a[1] * b[0]];
const length = (a) => Math.hypot(a[0], a[1], a[2]);
const normalize = (a) => scale(a, 1 / (length(a) || 1));

// Just short of straight up or down, where the look-at frame with +Y up degenerates.
const MAX_PITCH = Math.PI / 2 - 0.01;

// Viewer.setCamera()'s {eye, target, up?, yfov?} checked and completed (up +Y, yfov
// `defaultYfov`): {eye, target, up, yfov} or {error}.
export function cameraFromOptions(camera, defaultYfov) {
  const bad = (v) => !Array.isArray(v) || v.length !== 3 || !v.every(Number.isFinite);
  for (const what of ['eye', 'target']) {
    if (!camera || bad(camera[what])) return { error: `camera: '${what}' must be [x, y, z]` };
  }
  if (camera.up && bad(camera.up)) return { error: "camera: 'up' must be [x, y, z]" };
  return { eye: camera.eye, target: camera.target, up: camera.up || [0, 1, 0],
           yfov: camera.yfov ?? defaultYfov };
}

export class OrbitCamera {
  constructor() {
    this.target = [0, 0, 0];
    this.distance = 1;
    this.yaw = 0;    // radians about +Y; 0 looks from +Z toward -Z
    this.pitch = 0;  // radians above the horizon
    this.yfov = 0.8;
    this.radius = 1; // scene radius: bounds the zoom and scales the pan
  }

  // From a camera as the wasm side reports it ({eye, forward, yfov}) and the scene's bounds.
  static fromCamera(camera, bounds) {
    const o = new OrbitCamera();
    o.setFromCamera(camera, bounds);
    return o;
  }

  setFromCamera({ eye, forward, yfov }, bounds) {
    const fwd = normalize(forward);
    let centre = add(eye, fwd);
    this.radius = 1;
    if (bounds && bounds.min[0] <= bounds.max[0]) {
      centre = scale(add(bounds.min, bounds.max), 0.5);
      this.radius = Math.max(length(sub(bounds.max, bounds.min)) * 0.5, 1e-3);
    }
    // The pivot lies on the current view ray, as near the centre as the ray gets (but in front).
    const along = Math.max(dot(sub(centre, eye), fwd), this.radius * 0.1);
    this.target = add(eye, scale(fwd, along));
    this.setEye(eye);
    this.yfov = yfov;
  }

  setEye(eye) {
    const off = sub(eye, this.target);
    this.distance = Math.max(length(off), 1e-4);
    this.yaw = Math.atan2(off[0], off[2]);
    this.pitch = Math.asin(Math.max(-1, Math.min(1, off[1] / this.distance)));
    this.pitch = Math.max(-MAX_PITCH, Math.min(MAX_PITCH, this.pitch));
  }

  eye() {
    const c = Math.cos(this.pitch);
    return add(this.target, scale([c * Math.sin(this.yaw), Math.sin(this.pitch),
                                   c * Math.cos(this.yaw)], this.distance));
  }

  // Camera basis: right and up vectors of the current view (for panning).
  basis() {
    const fwd = normalize(sub(this.target, this.eye()));
    const right = normalize(cross(fwd, [0, 1, 0]));
    return { fwd, right, up: cross(right, fwd) };
  }

  // dx, dy in pixels; a drag across the whole height turns by about 180 degrees.
  orbit(dx, dy, viewHeight) {
    const k = Math.PI / Math.max(viewHeight, 1);
    this.yaw -= dx * k;
    this.pitch = Math.max(-MAX_PITCH, Math.min(MAX_PITCH, this.pitch + dy * k));
  }

  // Moves the pivot so the point under the cursor follows it (at the pivot's depth).
  pan(dx, dy, viewHeight) {
    const perPixel = (2 * this.distance * Math.tan(this.yfov / 2)) / Math.max(viewHeight, 1);
    const { right, up } = this.basis();
    this.target = add(this.target, add(scale(right, -dx * perPixel), scale(up, dy * perPixel)));
  }

  // factor < 1 moves closer. Bounded so a runaway wheel cannot lose the scene.
  zoom(factor) {
    this.distance = Math.max(this.radius * 0.02, Math.min(this.radius * 50, this.distance * factor));
  }

  toCamera() {
    return { eye: this.eye(), target: [...this.target], up: [0, 1, 0], yfov: this.yfov };
  }
}

// Attaches pointer and wheel listeners to `element`. `onChange()` runs after every camera
// change; `onReset()` on a double click. Returns { detach(), active } where `active` is true
// while a drag or pinch is in progress.
export function attachOrbitControls(element, orbit, { onChange, onReset } = {}) {
  if (typeof orbit === 'function') {  // a getter of the current camera (none: controls idle)
    const current = orbit;
    orbit = { orbit: (...a) => current()?.orbit(...a), pan: (...a) => current()?.pan(...a),
              zoom: (...a) => current()?.zoom(...a) };
  }
  const pointers = new Map();  // pointerId -> {x, y, button, shift}
  let pinch = null;            // {dist, mid} of the previous two-finger event
  const height = () => element.clientHeight || element.height || 1;

  const changed = () => { if (onChange) onChange(); };
  const two = () => {
    const [a, b] = [...pointers.values()];
    return { dist: Math.hypot(a.x - b.x, a.y - b.y), mid: [(a.x + b.x) / 2, (a.y + b.y) / 2] };
  };

  const down = (e) => {
    if (e.pointerType === 'mouse' && e.button !== 0 && e.button !== 2) return;
    // Capture keeps the drag alive outside the element; synthetic events cannot be captured.
    try { element.setPointerCapture?.(e.pointerId); } catch { /* not an active pointer */ }
    pointers.set(e.pointerId, { x: e.clientX, y: e.clientY, button: e.button, shift: e.shiftKey });
    pinch = pointers.size === 2 ? two() : null;
    e.preventDefault();
  };
  const move = (e) => {
    const p = pointers.get(e.pointerId);
    if (!p) return;
    const dx = e.clientX - p.x, dy = e.clientY - p.y;
    p.x = e.clientX;
    p.y = e.clientY;
    if (pointers.size >= 2) {
      const now = two();
      if (pinch && now.dist > 0 && pinch.dist > 0) {
        orbit.zoom(pinch.dist / now.dist);
        orbit.pan(now.mid[0] - pinch.mid[0], now.mid[1] - pinch.mid[1], height());
      }
      pinch = now;
    } else if (p.button === 2 || p.shift || e.shiftKey) {
      orbit.pan(dx, dy, height());
    } else {
      orbit.orbit(dx, dy, height());
    }
    if (dx !== 0 || dy !== 0) changed();
    e.preventDefault();
  };
  const up = (e) => {
    if (!pointers.delete(e.pointerId)) return;
    try { element.releasePointerCapture?.(e.pointerId); } catch { /* already released */ }
    pinch = pointers.size === 2 ? two() : null;
  };
  const wheel = (e) => {
    // deltaMode 1 = lines, 2 = pages; normalise to pixels before the exponential zoom.
    const px = e.deltaY * (e.deltaMode === 1 ? 16 : e.deltaMode === 2 ? 400 : 1);
    orbit.zoom(Math.exp(Math.max(-200, Math.min(200, px)) * 0.002));
    changed();
    e.preventDefault();
  };
  const menu = (e) => e.preventDefault();  // right drag pans instead of opening a menu
  const dbl = (e) => { if (onReset) onReset(); e.preventDefault(); };

  const listeners = [['pointerdown', down], ['pointermove', move], ['pointerup', up],
                     ['pointercancel', up], ['wheel', wheel], ['contextmenu', menu],
                     ['dblclick', dbl]];
  const previousTouchAction = element.style.touchAction;
  element.style.touchAction = 'none';  // the browser must not scroll or zoom the page instead
  for (const [type, fn] of listeners) element.addEventListener(type, fn, { passive: false });
  return {
    get active() { return pointers.size > 0; },
    detach() {
      for (const [type, fn] of listeners) element.removeEventListener(type, fn);
      element.style.touchAction = previousTouchAction;
      pointers.clear();
    },
  };
}
