// One viewer's link to its wasm module (web/src/viewer_main.cpp): the module loaded onto a
// canvas, calls whose JSON results carry errors (thrown as PenumbraError), files staged through
// the heap, and the module's death (an abort leaves it unusable). With Emitter, the viewer's
// events. Kept apart from penumbra.mjs, which owns the frame loop and the public API.
import createPenumbraViewerModule from './penumbra_viewer.js';
import { bindWasmApi, decodeInSteps, timeSteps } from './wasm_api.mjs';
import { PenumbraError, STEPPED_PANORAMA_PIXELS, fetchBytes, panoramaTooLarge, radianceSize,
  sourceName, toBytes } from './staging.mjs';

let canvasIds = 0;
let stagingIds = 0;

export class WasmSession {
  mod; pv;
  dead = null;           // why the module aborted, once it has
  onAbort = () => {};    // set by the viewer: the module aborted (after load)

  // Loads the module for `canvas` (given an id if it has none). Emscripten looks canvases up
  // with document.querySelector, which does not see into a shadow root (<penumbra-viewer>):
  // the module is given this one by its selector, returned with the session.
  static async load(canvas) {
    const session = new WasmSession();
    try {
      session.mod = await createPenumbraViewerModule({
        print: (t) => console.log(`[penumbra] ${t}`),
        printErr: (t) => console.warn(`[penumbra] ${t}`),
        onAbort: (what) => { session.dead = String(what); session.onAbort(session.dead); },
      });
    } catch (e) {
      throw new PenumbraError(`cannot load the Penumbra module: ${e && e.message ? e.message : e}`);
    }
    if (session.dead) throw new PenumbraError(`the Penumbra module aborted: ${session.dead}`);
    if (!canvas.id) canvas.id = `penumbra-canvas-${++canvasIds}`;
    const selector = `#${CSS.escape(canvas.id)}`;
    session.mod.specialHTMLTargets[selector] = canvas;
    session.pv = bindWasmApi(session.mod);
    return { session, selector };
  }

  // pv_<name>(...args), its JSON result parsed; {error} and exceptions as PenumbraError.
  call(name, ...args) {
    if (this.dead) throw new PenumbraError(`the Penumbra module aborted: ${this.dead}`);
    let text;
    try {
      text = this.pv[name](...args);
    } catch (e) {
      throw new PenumbraError(`${name}: ${e && e.message ? e.message : e}`);
    }
    const result = JSON.parse(text);
    if (result && typeof result === 'object' && typeof result.error === 'string') {
      throw new PenumbraError(result.error);
    }
    return result;
  }

  lastError() { return this.call('pv_last_error') || 'step failed'; }

  // Calls fn(ptr) with `bytes` copied into the wasm heap at ptr (freed after).
  withHeapCopy(bytes, fn, what = 'a file') {
    const ptr = this.pv.pv_alloc(bytes.length);
    if (!ptr && bytes.length) throw new PenumbraError(`out of memory staging ${what}`);
    try {
      this.mod.HEAPU8.set(bytes, ptr);
      return fn(ptr);
    } finally {
      this.pv.pv_free(ptr);
    }
  }

  // Writes files ({path, bytes}) under a fresh directory of the module's file system, returns
  // fn(root), and removes the directory whatever happens.
  staged(files, fn) {
    const root = `/stage/${++stagingIds}`;
    try {
      for (const f of files) {
        const path = `${root}/${f.path}`;
        this.withHeapCopy(f.bytes, (ptr) => this.call('pv_write_file', path, ptr, f.bytes.length),
                          path);
      }
      return fn(root);
    } finally {
      this.pv.pv_remove_tree(root);
    }
  }

  // An environment from `source` (Viewer.setEnvironment: null, 'studio', [r, g, b], a URL,
  // bytes or a File) into the renderer; `name` names bytes. check() throws where the viewer
  // went away while fetching. A large panorama is decoded in steps, the page running between
  // them (stale() true stops it: null). Returns the renderer's state.
  async setEnvironment(source, name, { check, stale }) {
    if (source === null || source === 'studio') {
      return this.call('pv_set_builtin_environment', source === null ? 'default' : 'studio');
    }
    if (Array.isArray(source)) {
      if (source.length !== 3 || !source.every(Number.isFinite)) {
        throw new PenumbraError('a uniform environment is [r, g, b]');
      }
      return this.call('pv_set_uniform_environment', ...source);
    }
    const { bytes, file } = await this.#environmentFile(source, name, 'environment.hdr', check);
    const size = radianceSize(bytes);
    if (size && !size.packed && size.width * size.height > STEPPED_PANORAMA_PIXELS) {
      this.withHeapCopy(bytes, (ptr) => this.call('pv_env_begin', ptr, bytes.length, file));
      if (!await decodeInSteps((rows) => this.call('pv_env_step', rows).done, stale)) return null;
      return this.call('pv_env_finish');
    }
    return this.staged([{ path: file, bytes }],
                       (root) => this.call('pv_set_environment', root, file));
  }

  // The background apart from the lighting (Viewer.setSkybox: a URL, bytes or a File of a
  // packed environment or a panorama; null: the environment again). Returns the state.
  async setSkybox(source, name, check) {
    if (source === null) return this.call('pv_set_skybox', '', '');
    const { bytes, file } = await this.#environmentFile(source, name, 'skybox.hdr', check);
    return this.staged([{ path: file, bytes }], (root) => this.call('pv_set_skybox', root, file));
  }

  // An environment file's bytes and a safe name for them, refused when too large to decode.
  async #environmentFile(source, name, fallback, check) {
    const bytes = typeof source === 'string' || source instanceof URL
      ? await fetchBytes(new URL(String(source), location.href).href) : await toBytes(source);
    check();
    const shown = name || sourceName(source, fallback);
    const tooLarge = panoramaTooLarge(bytes, shown);
    if (tooLarge) throw new PenumbraError(tooLarge);
    return { bytes, file: shown.replace(/[^\w.+-]/g, '_') };
  }

  // The last complete frame (pv_read): {width, height, frames, data} (RGBA floats, a copy).
  read(display) {
    const r = this.call('pv_read', display ? 1 : 0);
    const data = new Float32Array(this.mod.HEAPU8.buffer, r.ptr, r.width * r.height * 4).slice();
    return { width: r.width, height: r.height, frames: r.frames, data };
  }

  // Viewer.benchmark()'s figures over `frames` steps: one warm-up run (shaders compile on first
  // use), then back to back with one read-back (throughput) and with one after every step
  // (latency).
  benchmark(frames) {
    const run = (syncEach) => {
      const r = timeSteps(this.pv, frames, syncEach);
      if (r.frames === 0) throw new PenumbraError(this.lastError());
      return r;
    };
    run(false);
    const a = run(false);
    const b = run(true);
    return { frames: a.frames, msPerFrame: a.ms / a.frames, msPerFrameSynced: b.ms / b.frames,
             totalMs: a.ms };
  }
}

// Event handlers by name. A handler that throws does not stop the others (nor the frame loop);
// an error with no 'error' handler goes to the console.
export class Emitter {
  #listeners = new Map();

  on(event, handler) {
    if (!this.#listeners.has(event)) this.#listeners.set(event, new Set());
    this.#listeners.get(event).add(handler);
    return () => this.off(event, handler);
  }
  off(event, handler) { this.#listeners.get(event)?.delete(handler); }
  clear() { this.#listeners.clear(); }

  emit(event, detail) {
    for (const fn of this.#listeners.get(event) || []) {
      try { fn(detail); } catch (e) { console.error(e); }
    }
  }
  emitError(e) {
    const err = e instanceof Error ? e : new PenumbraError(String(e));
    if (!this.#listeners.get('error')?.size) console.error(err);
    this.emit('error', err);
  }
}
