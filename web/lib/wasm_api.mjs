// The wasm module's C entry points (web/src/viewer_main.cpp) as JS functions, and the timing loop
// Viewer.benchmark() runs on them. Kept apart from penumbra.mjs, which owns the frame loop.

// pv_* by name: cwrap'd with their return and argument types (s: a string, JSON or a one-line
// error; n: a number).
export function bindWasmApi(mod) {
  const s = 'string', n = 'number';
  const w = (name, ret, args) => mod.cwrap(name, ret, args);
  return {
    pv_create: w('pv_create', s, [s, n]), pv_destroy: w('pv_destroy', null, []),
    pv_alloc: w('pv_alloc', n, [n]), pv_free: w('pv_free', null, [n]),
    pv_write_file: w('pv_write_file', s, [s, n, n]), pv_remove_tree: w('pv_remove_tree', null, [s]),
    pv_load_scene: w('pv_load_scene', s, [s, s]),
    pv_set_environment: w('pv_set_environment', s, [s, s]),
    pv_set_uniform_environment: w('pv_set_uniform_environment', s, [n, n, n]),
    pv_env_begin: w('pv_env_begin', s, [n, n, s]), pv_env_step: w('pv_env_step', s, [n]),
    pv_env_finish: w('pv_env_finish', s, []),
    pv_set_builtin_environment: w('pv_set_builtin_environment', s, [s]),
    pv_set_skybox: w('pv_set_skybox', s, [s, s]),
    pv_set_settings: w('pv_set_settings', s, [s]), pv_get_state: w('pv_get_state', s, []),
    pv_settings_schema: w('pv_settings_schema', s, []),
    pv_set_camera: w('pv_set_camera', s, [n, n, n, n, n, n, n, n, n, n]),
    pv_reset_camera: w('pv_reset_camera', s, []),
    pv_set_variant: w('pv_set_variant', s, [s]), pv_set_pose: w('pv_set_pose', s, [n, n, n, n, n]),
    pv_step: w('pv_step', n, []), pv_last_error: w('pv_last_error', s, []),
    pv_step_part: w('pv_step_part', n, []), pv_set_tiles: w('pv_set_tiles', n, [n]),
    pv_last_part: w('pv_last_part', n, []), pv_last_parts: w('pv_last_parts', n, []),
    pv_sync: w('pv_sync', null, []), pv_present: w('pv_present', s, [n, n]),
    pv_read: w('pv_read', s, [n]), pv_frames_done: w('pv_frames_done', n, []), pv_total_frames: w('pv_total_frames', n, []),
    pv_converged: w('pv_converged', n, []), pv_gpu_memory: w('pv_gpu_memory', n, []), pv_restart: w('pv_restart', null, []),
    pv_preview: w('pv_preview', s, []),
    pv_context_lost: w('pv_context_lost', null, []),
    pv_context_restored: w('pv_context_restored', s, []),
  };
}

// Restarts the view and times up to `frames` steps back to back: with one read-back at the end
// (throughput), or after every step (`syncEach`: latency, what the time budget sees). Returns
// {frames, ms}; frames 0 when the first step failed (pv_last_error says why).
export function timeSteps(pv, frames, syncEach) {
  pv.pv_restart();
  pv.pv_sync();
  const t0 = performance.now();
  let n = 0;
  for (let f = pv.pv_step(); f > 0; f = pv.pv_step()) {
    if (syncEach) pv.pv_sync();
    if (++n >= frames) break;
  }
  pv.pv_sync();
  return { frames: n, ms: performance.now() - t0 };
}

// Decodes a panorama begun with pv_env_begin in steps of about 50 ms, yielding to the page
// between them: `step(rows)` decodes and returns true when done; `stale()` true stops early
// (another environment was set). Returns true when it completed.
export async function decodeInSteps(step, stale) {
  let rows = 32;
  for (let done = false; !done;) {
    await new Promise((resolve) => setTimeout(resolve, 0));
    if (stale()) return false;
    const t = performance.now();
    done = step(rows);
    const ms = performance.now() - t;
    rows = Math.max(1, Math.min(4096, Math.round(rows * (ms > 0 ? 50 / ms : 2))));
  }
  return true;
}
