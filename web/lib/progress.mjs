// The refinement progress a person reads (issue #59): a percentage that never goes back and
// never jumps by more than 25 points at a frame, and a time left only once the view has
// measured itself (after frame 8). An automatic view's total is an estimate that moves as the
// view measures itself; the percentage follows it without going back.

export const MAX_STEP = 25;        // points the percentage may rise at one frame
export const ETA_FROM_FRAME = 9;   // the first frame whose time left is shown
export const FRAME_WINDOW = 8;     // frames whose mean cost prices the frames left

export class ProgressMeter {
  #percent = 0;
  #frame = 0;
  #recent = [];  // the last FRAME_WINDOW frames' milliseconds

  // state: { frame, total, converged, frameMs }. Returns { percent, secondsLeft, done }:
  // percent an integer 0..99 (100 once done), secondsLeft null while not yet believable.
  update({ frame, total, converged, frameMs }) {
    if (frame < this.#frame) {  // a new view
      this.#percent = 0;
      this.#recent = [];
    }
    if (converged) {
      this.#frame = frame;
      this.#percent = 100;
      return { percent: 100, secondsLeft: 0, done: true };
    }
    if (frame !== this.#frame) {
      this.#frame = frame;
      // The frames left cost what the last few did: the early ones (first light, the probe
      // volume filling) cost more, and converged tiles make later ones cheaper.
      if (frameMs > 0) this.#recent = [...this.#recent, frameMs].slice(-FRAME_WINDOW);
      const target = total > 0 ? Math.min(99, Math.floor((100 * frame) / total)) : 0;
      this.#percent = Math.max(this.#percent, Math.min(target, this.#percent + MAX_STEP));
    }
    const ms = this.#recent.length ? this.#recent.reduce((a, b) => a + b) / this.#recent.length : 0;
    const left = frame >= ETA_FROM_FRAME && total > frame && ms > 0 && frameMs > 0
      ? ((total - frame) * ms) / 1000 : null;
    return { percent: this.#percent, secondsLeft: left, done: false };
  }
}
