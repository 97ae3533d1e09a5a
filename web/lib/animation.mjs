// Animation playback (model-viewer's autoplay, animation-name, play(), pause(), currentTime):
// plain state, as autorotate.mjs. The viewer's loop calls advance() each animation frame and
// poses the scene on the GPU (pv_set_pose, Renderer::setPose) when the time moved. A playing
// animation is a moving view, its frames the moving preview; paused, the view converges at the
// pose like any still. Animations loop, as model-viewer's do by default.
export class AnimationPlayer {
  animations = [];  // [{name, duration}] of the loaded scene
  index = -1;       // the chosen one (-1: none: the rest pose)
  time = 0;         // seconds into it
  playing = false;
  crossfadeMs = 300;  // a newly chosen animation fades in over this while playing (model-viewer's)
  #fade = null;     // the animation fading out: {index, time, left (seconds of the fade)}
  #last = null;     // the last tick that moved the time
  #posed = '-1:0:-1:0:0';  // the pose last sent (a scene loads at rest)
  #changed;         // called when the loop should run (the viewer wakes it)

  constructor(changed = () => {}) { this.#changed = changed; }

  // A new scene: nothing chosen, nothing playing.
  reset(animations) {
    Object.assign(this, { animations: animations || [], index: -1, time: 0, playing: false });
    this.#last = null;
    this.#fade = null;
    this.#posed = '-1:0:-1:0:0';
  }

  // Back to the rest pose (no animation chosen).
  rest() {
    Object.assign(this, { index: -1, time: 0, playing: false });
    this.#last = null;
    this.#fade = null;
    this.#changed();
  }

  // The animation by name or index (null or undefined: the first, as model-viewer plays).
  // Throws a one-line error naming the ones there are.
  select(name) {
    if (!this.animations.length) {
      if (name === null || name === undefined) return -1;
      throw new Error(`no animation "${name}": the model has none`);
    }
    let i = name === null || name === undefined ? 0 : this.animations.findIndex((a) => a.name === name);
    if (i < 0 && /^\d+$/.test(String(name)) && Number(name) < this.animations.length) i = Number(name);
    if (i < 0) {
      const list = this.animations.map((a, k) => a.name || String(k)).join(', ');
      throw new Error(`no animation "${name}"; the model has ${list}`);
    }
    if (i !== this.index) {
      // While playing, the one before fades out over crossfadeMs (model-viewer's crossfade).
      this.#fade = this.playing && this.index >= 0 && this.crossfadeMs > 0
        ? { index: this.index, time: this.time, left: this.crossfadeMs / 1000 } : null;
      Object.assign(this, { index: i, time: 0 });
    }
    this.#changed();
    return i;
  }

  play(now = performance.now()) {
    if (this.index < 0) this.select(null);
    if (this.index < 0) return false;
    this.playing = true;
    this.#last = now;
    this.#changed();
    return true;
  }

  pause() {
    this.playing = false;
    this.#last = null;
    this.#changed();
  }

  get duration() { return this.index >= 0 ? this.animations[this.index].duration : 0; }

  seek(seconds) {
    if (!Number.isFinite(seconds)) throw new Error('currentTime must be a number of seconds');
    const d = this.duration;
    this.time = d > 0 ? ((seconds % d) + d) % d : 0;
    this.#changed();
  }

  // Moves the time to `now` while playing and returns the pose to show when it changed, else
  // null: [index, time, fading index, its time, its weight] (-1, 0, 0 without a crossfade; for
  // pv_set_pose). Real time, as model-viewer plays (a slow device shows fewer poses, not a
  // slower animation); a long gap (a background tab) counts at most a second.
  advance(now) {
    if (this.playing && this.#last !== null) {
      const dt = Math.min(Math.max(now - this.#last, 0), 1000) / 1000;
      this.seek(this.time + dt);
      const f = this.#fade;
      if (f) {
        const d = this.animations[f.index].duration;
        f.time = d > 0 ? (f.time + dt) % d : 0;
        f.left -= dt;
        if (f.left <= 0) this.#fade = null;
      }
    }
    if (!this.playing) this.#fade = null;  // paused: the chosen one alone
    if (this.playing) this.#last = now;
    const f = this.#fade;
    const pose = [this.index, this.time, f ? f.index : -1, f ? f.time : 0,
                  f ? f.left / (this.crossfadeMs / 1000) : 0];
    const key = pose.join(':');
    if (key === this.#posed) return null;
    this.#posed = key;
    return pose;
  }
}

// Plays or pauses, firing model-viewer's 'play' or 'pause' event on `el` when that changed.
function setPlaying(el, player, on) {
  const was = player.playing;
  if (on) player.play(); else player.pause();
  if (player.playing !== was) el.dispatchEvent(new CustomEvent(on ? 'play' : 'pause', { detail: {} }));
}

// <penumbra-viewer>'s autoplay, animation-name and animation-crossfade-duration on a loaded model (element.mjs calls this in
// each attribute pass; `applied` holds what it last applied, null after a load). Returns a
// one-line error for a name the model lacks, else null.
export function applyAnimationAttributes(el, player, applied) {
  const name = el.getAttribute('animation-name');
  const fade = el.getAttribute('animation-crossfade-duration');
  const key = JSON.stringify([name, el.hasAttribute('autoplay'), fade]);
  if (key === applied.animation) return null;
  applied.animation = key;
  const ms = fade === null ? 300 : Number(fade);
  if (!(ms >= 0)) return `animation-crossfade-duration="${fade}": must be a number of ms >= 0`;
  player.crossfadeMs = ms;
  try {
    if (name !== null || el.hasAttribute('autoplay')) player.select(name);
    if (el.hasAttribute('autoplay')) setPlaying(el, player, true);
    return null;
  } catch (e) {
    return `animation-name="${name}": ${e.message}`;
  }
}

// The element's playback API, as model-viewer's: availableAnimations, currentTime, duration,
// paused, play(), pause(), and its 'play' and 'pause' events (el.viewer.animation underneath;
// inert before a model is loaded).
export function defineAnimationApi(proto) {
  const player = (el) => el.viewer?.animation;
  Object.defineProperties(proto, {
    availableAnimations: { get() { return (player(this)?.animations || []).map((a) => a.name); } },
    currentTime: {
      get() { return player(this)?.time ?? 0; },
      set(t) { player(this)?.seek(Number(t)); },
    },
    duration: { get() { return player(this)?.duration ?? 0; } },
    paused: { get() { return !player(this)?.playing; } },
    play: { value() { if (player(this)) setPlaying(this, player(this), true); } },
    pause: { value() { if (player(this)) setPlaying(this, player(this), false); } },
  });
}
