// Benchmark (prints only; not part of tools/test-web): how responsive the viewer page is in
// headless Chromium on SwiftShader (a CPU "GPU": slower than any phone, so the worst case).
//
//   node web/tests/bench_responsive.mjs [--frames 16] [--steps 20] [--only desktop|phone]
//                                       [--mode before|after|both] [--query '&k=v'] [--label L]
//
// For a 1280x720 desktop window and a 390x844 phone (deviceScaleFactor 3, touch, isMobile),
// each with frame splitting and the adaptive still resolution off ("before":
// adaptive=0&split=1, whole frames at full size) and on ("after": the defaults), it loads the
// Cornell box (m frames), waits for frame 2 (a full frame under way: the user starts to drag
// while the image converges), drags `steps` steps of 8 CSS pixels 33 ms apart (mouse, or one
// finger through CDP touch events), and prints:
// - first image: navigation start to the first presented frame;
// - input -> frame: from each pointermove's timeStamp (when the browser got the input, so
//   time the page was busy counts) to the next presented frame after its handler ran
//   (median, 95th percentile, max);
// - drag fps: frames presented per second between the first move and the release;
// - converge: release to the 'converged' event, and the still render size.
// To measure another build of the page (e.g. the main branch's), point PENUMBRA_WEB_DIST at
// its web/dist and pass --mode after --label main (unknown URL parameters are ignored there).
import { closeServer, dist, serve, withPage } from './harness.mjs';

const args = process.argv.slice(2);
const arg = (name, def) => {
  const i = args.indexOf(`--${name}`);
  return i >= 0 && args[i + 1] ? args[i + 1] : def;
};
const frames = Number(arg('frames', 16));
const steps = Number(arg('steps', 20));
const only = arg('only', 'both');
const modes = arg('mode', 'both') === 'both' ? ['before', 'after'] : [arg('mode')];
const CONFIGS = [
  { name: 'desktop 1280x720, DPR 1', key: 'desktop', touch: false,
    context: { viewport: { width: 1280, height: 720 }, deviceScaleFactor: 1 } },
  { name: 'phone 390x844, DPR 3, touch', key: 'phone', touch: true,
    context: { viewport: { width: 390, height: 844 }, deviceScaleFactor: 3, isMobile: true,
               hasTouch: true } },
].filter((c) => only === 'both' || c.key === only);
const MODE_QUERY = { before: '&adaptive=0&split=1', after: '' };
const label = arg('label', '');  // names the build in the table (e.g. "main" for PENUMBRA_WEB_DIST)
const extraQuery = arg('query', '');  // more viewer URL parameters, for experiments
const sleep = (ms) => new Promise((r) => setTimeout(r, ms));
const pct = (xs, p) => {
  const s = [...xs].sort((a, b) => a - b);
  return s.length ? s[Math.min(s.length - 1, Math.floor(p * s.length))] : NaN;
};

async function run(server, config, mode) {
  return withPage({ ...config.context, launchMs: 30_000 }, async (page, b) => {
    // The time of the first progress entry (a presented frame), from navigation start; set up
    // before the page runs so it works with any build of the page (PENUMBRA_WEB_DIST).
    await page.addInitScript(() => {
      let p;
      Object.defineProperty(window, 'penumbraPage', { configurable: true, get: () => p, set: (v) => {
        p = v;
        const push = v.progressLog.push.bind(v.progressLog);
        v.progressLog.push = (...a) => {
          if (v.firstImageMs === undefined) v.firstImageMs = performance.now();
          return push(...a);
        };
      } });
    });
    await page.goto(`http://127.0.0.1:${server.address().port}/index.html?frames=${frames}` +
                    `&panel=0${MODE_QUERY[mode]}${extraQuery}`, { timeout: 30_000 });
    await page.waitForFunction(() => window.penumbraPage?.ready || window.penumbraPage?.fatal,
                               null, { timeout: 120_000 });
    // Record presented frames, converged events and every pointermove (capture: before the
    // viewer's own handler runs, so handledAt is when the page got to it).
    await page.evaluate(() => {
      const p = window.penumbraPage;
      const log = (window.__bench = { presents: [], converged: [], moves: [], up: null });
      p.viewer.on('progress', () => log.presents.push(performance.now()));
      p.viewer.on('converged', () => log.converged.push(performance.now()));
      const c = document.getElementById('canvas');
      c.addEventListener('pointermove', (e) => log.moves.push({ t: e.timeStamp, handled: performance.now() }),
                         { capture: true });
      c.addEventListener('pointerup', () => { log.up = performance.now(); }, { capture: true });
    });
    await page.waitForFunction(() => window.penumbraPage.viewer.state.frame >= 2, null,
                               { timeout: 300_000, polling: 20 });
    const firstImageMs = await page.evaluate(() => window.penumbraPage.firstImageMs);
    const vp = config.context.viewport;
    const x0 = vp.width / 2, y0 = vp.height / 2;
    const cdp = config.touch ? await b.context.newCDPSession(page) : null;
    const touch = (type, x, y) => cdp.send('Input.dispatchTouchEvent', {
      type, touchPoints: type === 'touchEnd' ? [] : [{ x, y, id: 1 }] });
    if (config.touch) await touch('touchStart', x0, y0);
    else { await page.mouse.move(x0, y0); await page.mouse.down(); }
    for (let i = 1; i <= steps; i++) {
      const x = x0 + 8 * i, y = y0 + 2 * i;
      if (config.touch) await touch('touchMove', x, y);
      else await page.mouse.move(x, y);
      await sleep(33);
    }
    const during = await page.evaluate(() => window.penumbraPage.viewer.state);
    if (config.touch) await touch('touchEnd');
    else await page.mouse.up();
    await page.waitForFunction(() => window.__bench.up !== null &&
                                     window.__bench.converged.some((t) => t > window.__bench.up),
                               null, { timeout: 600_000, polling: 100 });
    const r = await page.evaluate(() => ({ log: window.__bench,
                                           state: window.penumbraPage.viewer.state,
                                           errors: window.penumbraPage.errors }));
    if (r.errors.length) throw new Error(r.errors.join('; '));
    const { moves, presents, converged, up } = r.log;
    const latency = moves.map((m) => {
      const shown = presents.find((t) => t >= m.handled);
      return shown === undefined ? NaN : shown - m.t;
    }).filter(Number.isFinite);
    if (args.includes('--verbose')) {
      console.log(`  ${config.key} ${mode}: latencies ${latency.map(Math.round).join(' ')}; ` +
                  `moves at ${moves.map((m) => Math.round(m.t)).join(' ')}; handled ` +
                  `${moves.map((m) => Math.round(m.handled - m.t)).join(' ')}; presents ` +
                  `${presents.filter((t) => t >= moves[0]?.t - 500 && t <= up).map(Math.round).join(' ')}`);
      console.log(`  during the drag: ${JSON.stringify(during)}`);
    }
    const first = moves.length ? moves[0].handled : up;
    const dragPresents = presents.filter((t) => t >= first && t <= up).length;
    return {
      firstImageMs, latency, moves: moves.length,
      fps: (1000 * dragPresents) / Math.max(1, up - first),
      convergeMs: converged.find((t) => t > up) - up,
      during: `${during.renderWidth}x${during.renderHeight}`,
      still: `${r.state.renderWidth}x${r.state.renderHeight} of ${r.state.canvasWidth}x${r.state.canvasHeight}`,
      split: r.state.split, parts: r.state.parts, frameMs: r.state.frameMs,
    };
  });
}

const server = await serve(dist);
try {
  console.log(`Cornell box, m = ${frames}, a ${steps}-step drag started at frame 2; ` +
              'headless Chromium, WebGL2 on SwiftShader');
  console.log('| viewport | mode | first image | input -> frame median / p95 / max | drag fps | ' +
              'converge after release | still image | last frame |');
  console.log('| --- | --- | --- | --- | --- | --- | --- | --- |');
  for (const config of CONFIGS) {
    for (const mode of modes) {
      const r = await run(server, config, mode);
      const ms = (x) => `${Math.round(x)}`;
      console.log(`| ${config.name} | ${label || mode} | ${(r.firstImageMs / 1000).toFixed(2)} s | ` +
                  `${ms(pct(r.latency, 0.5))} / ${ms(pct(r.latency, 0.95))} / ` +
                  `${ms(Math.max(...r.latency))} ms (${r.latency.length} of ${r.moves} moves) | ` +
                  `${r.fps.toFixed(1)} | ${(r.convergeMs / 1000).toFixed(1)} s | ${r.still} | ` +
                  `${ms(r.frameMs)} ms in ${r.parts ?? 1} part${r.parts > 1 ? 's' : ''} |`);
    }
  }
} finally {
  closeServer(server);
}
