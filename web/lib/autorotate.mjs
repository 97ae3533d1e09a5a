// Auto-rotate (model-viewer's auto-rotate, rotation-per-second, auto-rotate-delay): once the
// view has been left alone for `delayMs`, the orbit camera turns about the target's vertical
// axis at `speed` radians a second; any interaction restarts the delay. Penumbra turns the camera
// (model-viewer turns the model: the same picture under an environment that turns with the
// view). A turning view is a moving view: its frames are the moving preview, and it converges
// when auto-rotate stops. Plain state; the viewer's loop calls advance() each animation frame.
export const AUTO_ROTATE_DEFAULTS = Object.freeze({
  speed: Math.PI / 32,  // radians a second, model-viewer's default
  delayMs: 3000,        // model-viewer's default
});

export class AutoRotate {
  enabled = false;
  speed = AUTO_ROTATE_DEFAULTS.speed;
  delayMs = AUTO_ROTATE_DEFAULTS.delayMs;
  #idleSince = 0;   // performance.now() of the last interaction, or of configure()
  #last = null;     // the last tick that turned the camera

  configure({ enabled = this.enabled, speed = this.speed, delayMs = this.delayMs } = {}, now = 0) {
    if (!Number.isFinite(speed)) throw new RangeError('auto-rotate: speed must be a number');
    if (!(delayMs >= 0)) throw new RangeError('auto-rotate: the delay must be >= 0 ms');
    const starting = enabled && !this.enabled;
    Object.assign(this, { enabled: Boolean(enabled), speed, delayMs });
    if (starting) this.interacted(now);
  }

  // A drag, a wheel or a key: the turning stops until the view has been left alone again.
  interacted(now) {
    this.#idleSince = now;
    this.#last = null;
  }

  // Whether the view is turning at `now` (after the delay).
  turning(now) {
    return this.enabled && now - this.#idleSince >= this.delayMs;
  }

  // Turns `orbit` (orbit.mjs) for the time since the last tick; true when it turned. A long gap
  // (a background tab) turns at most a tenth of a second's worth, as a paused animation would.
  advance(orbit, now) {
    if (!orbit || !this.turning(now)) {
      this.#last = null;
      return false;
    }
    const dt = this.#last === null ? 0 : Math.min(now - this.#last, 100) / 1000;
    this.#last = now;
    if (dt <= 0) return false;
    orbit.yaw += this.speed * dt;
    return true;
  }
}
