// The hand-off page's path tracer in a dedicated worker, drawing into the page's canvas through
// an OffscreenCanvas (docs/web/handoff.md, "The path-tracer hand-off"). Why a worker: WebGL's shader
// compile is synchronous where KHR_parallel_shader_compile is missing (SwiftShader), and
// three-gpu-pathtracer's shader takes 45-60 s there; in a worker that wait blocks the worker, not
// the page's input. tools/build-web bundles this file with three.js and the path tracer
// (esbuild) into pathtracer-worker.js.
//
// Messages from the page:
//   {type: 'init', canvas, options}  create the path tracer on the transferred canvas; answers
//        {type: 'created', parallelCompile, lights, lampFaces}: parallelCompile says whether the browser
//        compiles shaders in the background (KHR_parallel_shader_compile); without it the
//        compile holds up every WebGL call of the page, in any thread, until it is done
//   {type: 'compile', camera, width, height}  compile the shader now (one sample of this view);
//        answers {type: 'ready', compileMs}
//   {type: 'start', generation, camera, settings, width, height, budgetMs, maxSamples}
//        trace this view (up to maxSamples)
//   {type: 'stop'}                                  stop tracing (the camera moved)
//   {type: 'read', id}                              answers {type: 'image', id, image}
// Messages to the page, tagged with the generation of their 'start':
//   {type: 'sample', generation, samples, tracingMs}            after every whole sample
//   {type: 'snapshot', generation, samples, tracingMs, image}   at 1, 2, 4, ... samples
//   {type: 'error', message}
import { PathTracerView } from './pathtracer.mjs';

let view = null;
let generation = -1;
let running = false;
let budgetMs, maxSamples;  // set by 'start'
let nextSnapshot = 1;
let pending = 0;

const post = (m, transfer = []) => self.postMessage(m, transfer);
const fail = (e) => post({ type: 'error', message: e && e.message ? e.message : String(e) });
// A worker's rAF follows the display of its transferred canvas; a timeout where there is none.
const later = (f) => (self.requestAnimationFrame ? self.requestAnimationFrame(f) : setTimeout(f, 0));

function loop() {
  pending = 0;
  if (!running) return;
  const g = generation;
  try {
    view.step(budgetMs, (samples) => {
      if (g !== generation || !running) return false;
      post({ type: 'sample', generation: g, samples, tracingMs: view.tracingMs });
      if (samples === nextSnapshot) {
        nextSnapshot *= 2;
        const image = view.readDisplay();
        post({ type: 'snapshot', generation: g, samples, tracingMs: view.tracingMs, image },
             [image.data.buffer]);
      }
      if (samples >= maxSamples) running = false;
      return running;
    });
  } catch (e) {
    running = false;
    fail(e);
    return;
  }
  if (running && !pending) pending = later(loop);
}

// One message at a time, in order: a 'start' waits for the compile of 'init'.
let queue = Promise.resolve();
self.onmessage = ({ data: m }) => { queue = queue.then(() => handle(m)); };

async function handle(m) {
  try {
    if (m.type === 'init') {
      view = await PathTracerView.create(m.canvas, m.options);
      post({ type: 'created', parallelCompile: view.parallelCompile, lights: view.lights,
             lampFaces: view.lampFaces });
    } else if (m.type === 'compile') {
      view.setCamera(m.camera, m.width, m.height);
      await view.compile();
      post({ type: 'ready', compileMs: view.compileMs });
    } else if (m.type === 'start') {
      view.applySettings(m.settings);
      view.setCamera(m.camera, m.width, m.height);
      generation = m.generation;
      budgetMs = m.budgetMs;
      maxSamples = m.maxSamples;
      nextSnapshot = 1;
      running = true;
      if (!pending) pending = later(loop);
    } else if (m.type === 'stop') {
      running = false;
    } else if (m.type === 'read') {
      const image = view.readDisplay();
      post({ type: 'image', id: m.id, image }, [image.data.buffer]);
    }
  } catch (e) {
    running = false;
    fail(e);
  }
}
