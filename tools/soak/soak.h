// The long-run stability check, shared by tools/soak (penumbra-soak, 10,000 frames) and the
// short ctest version (tests/gl/long_run_gltest.cpp, LongRunGLTest). Needs a current GL context.
//
// What it checks, in order (docs/bad-inputs.md, "Long-run stability"):
//  1. Bad samples are dropped: the Cornell box plus a second rect light of NaN intensity, with
//     2 samples per light over `injectFrames` frames, so only the few frames that carry the NaN
//     light's samples are non-finite; the accumulated image must stay finite everywhere and
//     not black, and differ from the same run with that light at intensity 0 (evidence that
//     the NaN frames happened and were dropped rather than the light being ignored).
//  2. Memory and finiteness over `totalFrames` frames: ProgressiveSettings::frames is capped at
//     4096 (settings.h), so the run is a sequence of `runFrames`-frame accumulations, each
//     restarted with Renderer::restart(), until `totalFrames` frames have been drawn.
//     Resident memory (/proc/self/statm) is sampled every `sampleEvery` frames; the first sample
//     after `warmupFrames` is the baseline and no later sample may exceed it by more than
//     `maxGrowthMb`. The radiance is read back at every sample and must be finite.
//  3. Determinism across restarts: the image at the end of the second full run equals the one at
//     the end of the first (max abs difference <= `restartTolerance`): nothing drifts however
//     long the renderer lives.
//  4. Convergence: the `runFrames`-frame image against a `runFrames / 2`-frame one (a separate
//     accumulation): mean abs difference over RGB <= `convergenceTolerance` times the mean
//     radiance of the image.
#pragma once

#include <unistd.h>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <limits>
#include <string>

#include "penumbra/render_job.h"

namespace penumbra::soak {

struct Options {
  std::string cornellGltf;  // assets/cornell_box/cornell_box.gltf
  int width = 64, height = 64;
  int runFrames = 4096;     // frames of one accumulation (1..4096)
  int totalFrames = 10000;  // frames drawn in all, over restarted runs
  int sampleEvery = 500;    // RSS and finiteness sample interval
  int warmupFrames = 500;   // the baseline is the first sample at or after this frame
  double maxGrowthMb = 4.0;
  int injectFrames = 256;
  int shadowMapSize = 256;
  double restartTolerance = 1e-6;
  double convergenceTolerance = 0.02;
  bool desktopGl = false;
};

struct Report {
  double baselineMb = 0, peakMb = 0, finalMb = 0;
  int framesDrawn = 0;
  double restartMaxAbs = 0, convergenceMeanAbs = 0, meanRadiance = 0;
  std::string failure;  // empty when every check passed
  bool ok() const { return failure.empty(); }
};

inline double residentMb() {
  std::ifstream f("/proc/self/statm");
  long pages = 0, resident = 0;
  f >> pages >> resident;
  return static_cast<double>(resident) * static_cast<double>(sysconf(_SC_PAGESIZE)) / (1 << 20);
}

// Index of the first non-finite value, or -1.
inline long firstNonFinite(const Image& img) {
  for (size_t i = 0; i < img.pixels.size(); ++i)
    if (!std::isfinite(img.pixels[i])) return static_cast<long>(i);
  return -1;
}

inline double meanRgb(const Image& img) {
  double s = 0;
  for (size_t i = 0; i < img.pixels.size(); ++i)
    if (i % 4 != 3) s += img.pixels[i];
  return s / (static_cast<double>(img.pixels.size()) * 0.75);
}

inline Report run(const Options& o, const std::function<void(const std::string&)>& log) {
  Report rep;
  auto fail = [&](const std::string& m) {
    rep.failure = m;
    return rep;
  };
  JobRequest request;
  request.scenePath = o.cornellGltf;
  request.camera = "cornell";
  request.environment =
      EnvironmentSpec{.kind = EnvironmentSpec::Kind::Uniform, .radiance = glm::vec3(0.05f)};
  request.settings = {{"width", std::to_string(o.width)},
                      {"height", std::to_string(o.height)},
                      {"shadowMapSize", std::to_string(o.shadowMapSize)},
                      {"occlusionDistance", "0.3"}};
  auto job = RenderJob::load(request);
  if (!job) return fail(job.message());
  const Scene* scene = &job->scene;
  auto created = Renderer::create({.desktopGl = o.desktopGl});
  if (!created) return fail(created.message());
  Renderer& r = **created;
  RenderSettings s = job->settings;
  if (auto st = job->applyTo(r); !st) return fail(st.message());
  auto accumulate = [&](int frames) -> Status {
    while (frames-- > 0 && !r.converged()) {
      auto f = r.step();
      if (!f) return f.error();
      ++rep.framesDrawn;
    }
    return {};
  };

  // 1. NaN injection.
  {
    Scene bad = *scene;
    Light nanLight;
    nanLight.name = "nan";
    nanLight.intensity = std::numeric_limits<float>::quiet_NaN();
    nanLight.position = scene->bounds.center();
    nanLight.direction = {0, -1, 0};
    nanLight.right = {1, 0, 0};
    nanLight.up = {0, 0, 1};
    nanLight.width = nanLight.height = 0.2f;
    bad.lights.push_back(nanLight);
    RenderSettings si = s;
    si.progressive.frames = o.injectFrames;
    si.progressive.lightSamples = 2;
    if (auto st = r.setSettings(si); !st) return fail(st.message());
    if (auto st = r.setScene(bad); !st) return fail(st.message());
    if (auto st = accumulate(o.injectFrames); !st) return fail(st.message());
    auto img = r.readRadiance();
    if (!img) return fail(img.message());
    if (long i = firstNonFinite(*img); i >= 0)
      return fail("NaN injection: non-finite radiance at value " + std::to_string(i));
    if (!(meanRgb(*img) > 0)) return fail("NaN injection: the image is black");
    // The same run with the light at intensity 0 instead of NaN: were the NaN frames really
    // produced (and dropped), the two images differ; were the light ignored, they would not.
    bad.lights.back().intensity = 0.0f;
    if (auto st = r.setScene(bad); !st) return fail(st.message());
    if (auto st = accumulate(o.injectFrames); !st) return fail(st.message());
    auto zero = r.readRadiance();
    if (!zero) return fail(zero.message());
    auto dz = compareImages(*img, *zero);
    if (!dz) return fail(dz.message());
    if (!(dz->maxAbs > 0)) {
      return fail("NaN injection: no frame was dropped (the NaN light had no effect)");
    }
    log("NaN-intensity light over " + std::to_string(o.injectFrames) +
        " frames: image finite, mean radiance " + std::to_string(meanRgb(*img)) +
        "; differs from the zero-intensity run by up to " + std::to_string(dz->maxAbs) +
        " (the dropped frames)");
  }

  // 2 and 3. Restarted runs, memory and finiteness samples, determinism across restarts.
  s.progressive.frames = o.runFrames;
  if (auto st = r.setSettings(s); !st) return fail(st.message());
  if (auto st = r.setScene(*scene); !st) return fail(st.message());
  r.restart();
  Image firstRun, secondRun;
  int runIndex = 0, drawn = 0;
  bool haveBaseline = false;
  while (drawn < o.totalFrames) {
    auto f = r.step();
    if (!f) return fail(f.message());
    ++drawn;
    ++rep.framesDrawn;
    if (drawn % o.sampleEvery == 0) {
      const double mb = residentMb();
      auto img = r.readRadiance();
      if (!img) return fail(img.message());
      if (long i = firstNonFinite(*img); i >= 0)
        return fail("frame " + std::to_string(drawn) + ": non-finite radiance at value " +
                    std::to_string(i));
      if (!haveBaseline && drawn >= o.warmupFrames) {
        haveBaseline = true;
        rep.baselineMb = rep.peakMb = mb;
      } else if (haveBaseline) {
        rep.peakMb = std::max(rep.peakMb, mb);
        if (mb - rep.baselineMb > o.maxGrowthMb) {
          char m[160];
          std::snprintf(m, sizeof m,
                        "frame %d: resident memory %.1f MB grew %.1f MB over the "
                        "baseline %.1f MB (limit %.1f MB)",
                        drawn, mb, mb - rep.baselineMb, rep.baselineMb, o.maxGrowthMb);
          return fail(m);
        }
      }
      rep.finalMb = mb;
      char m[120];
      std::snprintf(m, sizeof m, "frame %5d (run %d, frame %4d): resident %.1f MB", drawn,
                    runIndex + 1, r.framesDone(), mb);
      log(m);
    }
    if (r.converged()) {
      auto img = r.readRadiance();
      if (!img) return fail(img.message());
      if (runIndex == 0) firstRun = std::move(*img);
      if (runIndex == 1) secondRun = std::move(*img);
      ++runIndex;
      r.restart();
    }
  }
  if (secondRun.empty()) return fail("fewer than two complete runs: raise totalFrames");
  auto d = compareImages(firstRun, secondRun);
  if (!d) return fail(d.message());
  rep.restartMaxAbs = d->maxAbs;
  if (d->maxAbs > o.restartTolerance) {
    return fail("the second " + std::to_string(o.runFrames) + "-frame run differs from the " +
                "first by " + std::to_string(d->maxAbs));
  }

  // 4. Convergence: half the frames against all of them.
  RenderSettings sh = s;
  sh.progressive.frames = o.runFrames / 2;
  if (auto st = r.setSettings(sh); !st) return fail(st.message());
  if (auto st = accumulate(sh.progressive.frames); !st) return fail(st.message());
  auto half = r.readRadiance();
  if (!half) return fail(half.message());
  auto c = compareImages(firstRun, *half);
  if (!c) return fail(c.message());
  rep.convergenceMeanAbs = c->meanAbs;
  rep.meanRadiance = meanRgb(firstRun);
  if (c->meanAbs > o.convergenceTolerance * rep.meanRadiance) {
    return fail("not converged: " + std::to_string(o.runFrames) + " vs " +
                std::to_string(sh.progressive.frames) + " frames differ by " +
                std::to_string(c->meanAbs) + " (mean abs), over " +
                std::to_string(o.convergenceTolerance) + " x mean radiance " +
                std::to_string(rep.meanRadiance));
  }
  return rep;
}

}  // namespace penumbra::soak
