// The viewer's requestAnimationFrame loop (penumbra.mjs runs its frames through it). It ticks
// while there is work and sleeps when step() says there is none (a converged view), so a still
// page costs nothing until wake(); pause() stops it (a view off-screen) until resume(); a tick
// that throws is reported once and the loop rests a second before trying again, so one fault is
// not reported sixty times a second.
const BACKOFF_MS = 1000;

export class FrameLoop {
  #raf = 0; #paused = false; #stopped = false; #resting = 0;
  #step; #onError;

  // step(): draws what this animation frame allows; returns true while there is more to do.
  constructor(step, onError) {
    this.#step = step;
    this.#onError = onError;
  }

  get scheduled() { return this.#raf !== 0; }
  get paused() { return this.#paused; }

  // Schedules a tick unless one is pending (an arrow: it is also a ResizeObserver callback).
  wake = () => {
    if (!this.#raf && !this.#paused && !this.#stopped && !this.#resting) {
      this.#raf = requestAnimationFrame(this.#tick);
    }
  };

  pause() {
    this.#paused = true;
    cancelAnimationFrame(this.#raf);
    this.#raf = 0;
  }

  resume() {
    this.#paused = false;
    this.wake();
  }

  stop() {
    this.#stopped = true;
    this.pause();
    clearTimeout(this.#resting);
  }

  #tick = () => {
    this.#raf = 0;
    if (this.#paused || this.#stopped) return;
    let more;
    try {
      more = this.#step();
    } catch (e) {
      this.#resting = setTimeout(() => { this.#resting = 0; this.wake(); }, BACKOFF_MS);
      this.#onError(e);
      return;
    }
    if (more) this.wake();
  };
}

// Draws parts of frames (pv_step_part) until the next part, if it costs what the last one did,
// would overrun `budgetMs`, or the view converges. beforePart() runs before each part;
// onPart(ms, began) after each (began: the part began a frame); onFrame() after a part that
// completed a frame, true to stop there. Returns {parts, frames}; a failed part throws error().
export function drawParts(pv, budgetMs, { beforePart, onPart, onFrame, error }) {
  let parts = 0, frames = 0;
  const start = performance.now();
  let prev = start;
  for (;;) {
    beforePart();
    const r = pv.pv_step_part();
    if (r < 0) throw error();
    if (r === 0) break;
    pv.pv_sync();
    const t = performance.now(), dt = t - prev;
    prev = t;
    parts++;
    onPart(dt, pv.pv_last_part() === 1);
    if (r === 1 && (++frames, onFrame())) break;
    if (pv.pv_converged() || (t - start) + dt > budgetMs) break;
  }
  return { parts, frames };
}
