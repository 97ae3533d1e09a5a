// Benchmark (prints only; not part of tools/test-web): milliseconds per intermediate frame of
// the viewer page in headless Chromium on SwiftShader (a CPU "GPU"), the browser's side of
// issue #13's speed targets.
//
//   node web/tests/bench_frames.mjs [--frames 64] [--size 512] [--scenes cornell_box,...]
//                                   [--runs 2] [--query '&k=v'] [--label L]
// (The scenes web/dist serves: cornell_box, material_grid, glass; tools/build-web.)
//
// For each scene: a size x size window (DPR 1), the viewer with whole frames at full size
// (adaptive=0&split=1: nothing adapts, so the figures compare builds), m frames of a still
// view. Prints the first frame (its work time, as the viewer measures it), the milliseconds
// per frame from frame 2 to convergence (wall time between the presented frames: what a user
// waits), the median interval between presented frames, the longest one and the frame it
// ended (a hitch: a program linked mid-view, the probe volume's young frames), and the time from
// the view's start to convergence (the viewer's own figure). To measure another build
// of the page (e.g. the main branch's), point PENUMBRA_WEB_DIST at its web/dist and pass
// --label main.
import { closeServer, dist, serve, withPage } from './harness.mjs';

const args = process.argv.slice(2);
const arg = (name, def) => {
  const i = args.indexOf(`--${name}`);
  return i >= 0 && args[i + 1] ? args[i + 1] : def;
};
const frames = Number(arg('frames', 64));
const size = Number(arg('size', 512));
const runs = Number(arg('runs', 2));
const scenes = arg('scenes', 'cornell_box').split(',');
const label = arg('label', 'this build');
const extraQuery = arg('query', '');
const median = (xs) => {
  const s = [...xs].sort((a, b) => a - b);
  return s.length ? s[Math.floor(s.length / 2)] : NaN;
};

async function run(server, scene) {
  const options = { viewport: { width: size, height: size }, deviceScaleFactor: 1, launchMs: 30_000 };
  return withPage(options, async (page) => {
    await page.goto(`http://127.0.0.1:${server.address().port}/index.html?frames=${frames}` +
                    `&panel=0&adaptive=0&split=1&scene=assets/${scene}/${scene}.json${extraQuery}`,
                    { timeout: 30_000 });
    await page.waitForFunction(() => window.penumbraPage?.ready || window.penumbraPage?.fatal,
                               null, { timeout: 120_000 });
    // Presented frames from now on; the scene is loading or already rendering frame 1.
    await page.evaluate(() => {
      const p = window.penumbraPage;
      const log = (window.__bench = { presents: [], converged: null });
      p.viewer.on('progress', ({ frame }) => log.presents.push({ frame, t: performance.now() }));
      p.viewer.on('converged', () => { log.converged = performance.now(); });
    });
    // A load error (a scene the page does not serve) ends the run at once.
    await page.waitForFunction(() => window.__bench.converged !== null ||
                                     window.penumbraPage.fatal ||
                                     window.penumbraPage.errors.length > 0, null,
                               { timeout: 600_000, polling: 100 });
    const r = await page.evaluate(() => ({ log: window.__bench,
                                           state: window.penumbraPage.viewer.state,
                                           errors: window.penumbraPage.errors }));
    if (r.errors.length) throw new Error(r.errors.join('; '));
    // The frames of the last restart (loading may restart the view once) that were presented
    // after the listener went in (frame 1 may come before it).
    const all = r.log.presents;
    let start = all.length - 1;
    while (start > 0 && all[start - 1].frame < all[start].frame) start--;
    const shown = all.slice(start);
    const from = shown.find((p) => p.frame >= 2);
    const last = shown[shown.length - 1];
    const intervals = shown.slice(1).map((p, i) => p.t - shown[i].t);
    const longest = intervals.reduce((best, ms, i) => (ms > best.ms ? { ms, frame: shown[i + 1].frame }
                                                                    : best), { ms: -Infinity, frame: 0 });
    return {
      render: `${r.state.renderWidth}x${r.state.renderHeight}`,
      frame1Ms: r.state.frame1Ms,
      perFrameMs: from && last.frame > from.frame ? (last.t - from.t) / (last.frame - from.frame)
                                                  : NaN,
      medianMs: median(intervals),
      longest,
      totalS: (r.state.convergedMs ?? NaN) / 1000,
      frames: last.frame,
    };
  });
}

const server = await serve(dist);
try {
  console.log(`| build | scene | render size | m | first frame (ms) | per frame (ms) | ` +
              `median interval (ms) | longest interval (ms, frame) | start to converged (s) |`);
  console.log('|---|---|---|---|---|---|---|---|---|');
  for (const scene of scenes) {
    for (let i = 0; i < runs; i++) {
      const r = await run(server, scene);
      console.log(`| ${label} | ${scene} | ${r.render} | ${r.frames} | ${r.frame1Ms.toFixed(0)} | ` +
                  `${r.perFrameMs.toFixed(1)} | ${r.medianMs.toFixed(1)} | ` +
                  `${r.longest.ms.toFixed(0)} (${r.longest.frame}) | ${r.totalS.toFixed(2)} |`);
    }
  }
} finally {
  await closeServer(server);
}
