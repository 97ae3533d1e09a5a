// Loads the smoke module, runs the 32-bit and the forced half-float read-back tests and the
// exception check, and publishes { full, half, exceptions } (or { error }) on
// window.smokeResult for the browser test to read.
import createPenumbraModule from './penumbra_smoke.js';

const log = document.getElementById('log');

function publish(result) {
  window.smokeResult = result;
  log.textContent = JSON.stringify(result, (k, v) => (k === 'extensions' ? v.length : v), 2);
}

try {
  // onAbort: an abort inside wasm must still end the page with an error, not a silent hang.
  const module = await createPenumbraModule({
    onAbort: (what) => publish({ error: `wasm abort: ${what}` }),
  });
  const run = module.cwrap('penumbra_smoke_run', 'string', ['number']);
  const exceptions = module.cwrap('penumbra_smoke_exceptions', 'string', []);
  publish({ full: JSON.parse(run(0)), half: JSON.parse(run(1)), exceptions: JSON.parse(exceptions()) });
} catch (e) {
  publish({ error: `smoke page: ${e && e.stack ? e.stack : e}` });
}
