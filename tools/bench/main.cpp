// penumbra-bench: prints the progressive renderer's speed and memory figures — first-frame and
// per-frame milliseconds, time to m frames at 1280x720 and 1920x1080, peak resident memory —
// for the bundled Cornell box and the dense (>100k triangles) model. Shaders are compiled
// before timing starts (the first-frame figure excludes compilation, as the issue asks).
// --breakdown also times every pass (prepass, shadow maps, lighting, accumulation, tone map).
#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "../common/setting_flags.h"

#include "penumbra/gl_context.h"
#include "penumbra/render_job.h"
#include "penumbra/renderer.h"

using namespace penumbra;
using Clock = std::chrono::steady_clock;

namespace {

double ms(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}

long peakRssMb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_maxrss / 1024;
}

struct Row {
  std::string scene;
  int width, height, frames;
  double firstMs, perFrameMs, totalS;
  size_t triangles;
  double previewMs = 0;  // Renderer::preview and its tone map: the median of kPreviews
  // With --breakdown: milliseconds summed over frames 1..m, per pass, and frame 1's display.
  double readBackMs = 0;
  double prepassMs = 0, shadowMs = 0, lightingMs = 0, accumulateMs = 0, firstDisplayMs = 0;
  double toneMapMs = 0;  // one tone mapping, the median of nine (--breakdown)
  double occlusionMs = 0;
  double firstLightingMs = 0, firstAccumulateMs = 0;
  double probeMs = 0;
  int probeCaptures = 0;
  ProbeVolumeInfo probes;
  int64_t gpuBytes = 0;  // Renderer::gpuMemoryBytes() after the last frame
  int shadowPasses = 0;
  int lightingPasses = 0;
};

// Settings given with --set KEY=VALUE, applied to every run (A/B of one setting).
std::vector<std::pair<std::string, std::string>> gExtraSettings;
bool gLightCache = true;         // --no-light-cache turns it off
bool gQuarterOcclusion = true;   // --full-occlusion turns it off
bool gFusedAccumulation = true;  // --separate-accumulation turns it off

Result<Row> run(const std::string& sceneFile, int w, int h, const std::string& frames,
                bool breakdown, bool probeCache, bool probeVolume = true) {
  JobRequest request;
  request.scenePath = sceneFile;
  request.settings = {
      {"width", std::to_string(w)}, {"height", std::to_string(h)}, {"frames", frames}};
  if (!probeVolume) request.settings.push_back({"probeVolume", "false"});
  for (const auto& kv : gExtraSettings) request.settings.push_back(kv);
  auto job = RenderJob::load(request);
  if (!job) return job.error();
  const Scene* scene = &job->scene;
  auto r = Renderer::create({.profilePasses = breakdown,
                             .probeCache = probeCache,
                             .lightCache = gLightCache,
                             .quarterOcclusion = gQuarterOcclusion,
                             .fusedAccumulation = gFusedAccumulation});
  if (!r) return r.error();
  PN_TRY(job->applyTo(**r));
  // Warm-up: one full run compiles every program and touches every target.
  while (!(*r)->converged()) PN_TRY((*r)->step());
  (void)(*r)->readDisplay();
  (*r)->restart();
  // The preview a moving view shows, drawn again and again as while orbiting (nothing is
  // captured into the probe volume right after a restart).
  constexpr int kPreviews = 5;
  std::vector<double> previews;
  for (int i = 0; i < kPreviews; ++i) {
    const auto p0 = Clock::now();
    PN_TRY((*r)->preview());
    PN_TRY((*r)->toneMap());
    (*r)->finish();
    previews.push_back(ms(p0, Clock::now()));
  }
  std::sort(previews.begin(), previews.end());
  (*r)->restart();

  Row row{
      sceneFile.substr(sceneFile.find_last_of('/') + 1), w, h, 0, 0, 0, 0, scene->triangleCount()};
  row.previewMs = previews[kPreviews / 2];
  auto add = [&row](const FrameStats& f) {
    row.prepassMs += f.prepassMs;
    row.occlusionMs += f.occlusionMs;
    row.shadowMs += f.shadowMs;
    row.lightingMs += f.lightingMs;
    row.accumulateMs += f.accumulateMs;
    row.probeMs += f.probeMs;
    row.probeCaptures += f.probeCaptures;
    row.shadowPasses += f.shadowPasses;
    row.lightingPasses += f.lightingPasses;
  };
  // A frame is ready for display once it is accumulated and tone-mapped (what the web viewer
  // presents); reading it back into CPU memory is timed apart, as the CLI's extra cost.
  auto t0 = Clock::now();
  PN_TRY((*r)->step());
  add((*r)->lastFrame());
  row.firstLightingMs = (*r)->lastFrame().lightingMs;
  row.firstAccumulateMs = (*r)->lastFrame().accumulateMs;
  auto td = Clock::now();
  PN_TRY((*r)->toneMap());
  (*r)->finish();
  auto t1 = Clock::now();
  row.firstDisplayMs = ms(td, t1);
  while (!(*r)->converged()) {
    PN_TRY((*r)->step());
    add((*r)->lastFrame());
    PN_TRY((*r)->toneMap());
  }
  (*r)->finish();
  auto t2 = Clock::now();
  auto done = (*r)->readDisplay();
  auto t3 = Clock::now();
  if (!done) return makeError("read-back failed: " + done.message());
  if (breakdown) {
    // The tone mapping alone, the median of nine (a single pass is too short to time once).
    std::vector<double> tms;
    for (int i = 0; i < 9; ++i) {
      const auto a = Clock::now();
      PN_TRY((*r)->toneMap());
      (*r)->finish();
      tms.push_back(ms(a, Clock::now()));
    }
    std::sort(tms.begin(), tms.end());
    row.toneMapMs = tms[tms.size() / 2];
  }
  row.firstMs = ms(t0, t1);
  row.frames = (*r)->framesDone();  // m, or where an automatic view stopped
  row.perFrameMs = ms(t1, t2) / std::max(row.frames - 1, 1);
  row.totalS = ms(t0, t2) / 1000.0;
  row.readBackMs = ms(t2, t3);
  row.probes = (*r)->probeVolumeInfo();
  row.gpuBytes = Renderer::gpuMemoryBytes();
  return row;
}

// "WxH", or a message and false.
bool parseSize(const std::string& size, int& w, int& h) {
  if (std::sscanf(size.c_str(), "%dx%d", &w, &h) == 2) return true;
  std::fprintf(stderr, "penumbra-bench: error: bad size '%s'\n", size.c_str());
  return false;
}

// The probe volume's per-frame cost: runs with and without it, alternating (so a machine's
// drifting load hits both alike), and the medians of their per-frame times.
int giCost(const std::vector<std::string>& scenes, const std::vector<std::string>& sizes,
           const std::string& frames, int rounds, bool probeCache) {
  std::printf("| scene | size | m | rounds | per frame without (ms) | with (ms) | added |\n");
  std::printf("|---|---|---|---|---|---|---|\n");
  const auto median = [](std::vector<double> v) {
    std::sort(v.begin(), v.end());
    const size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
  };
  for (const auto& scene : scenes) {
    for (const auto& size : sizes) {
      int w = 0, h = 0;
      if (!parseSize(size, w, h)) return 1;
      std::vector<double> without, with;
      for (int i = 0; i < rounds; ++i) {
        for (const bool gi : {false, true}) {
          auto row = run(scene, w, h, frames, false, probeCache, gi);
          if (!row) {
            std::fprintf(stderr, "penumbra-bench: error: %s\n", row.message().c_str());
            return 1;
          }
          (gi ? with : without).push_back(row->perFrameMs);
        }
      }
      const double a = median(without), b = median(with);
      std::printf("| %s | %dx%d | %s | %d | %.1f | %.1f | %+.1f %% |\n",
                  scene.substr(scene.find_last_of('/') + 1).c_str(), w, h, frames.c_str(), rounds,
                  a, b, 100.0 * (b - a) / a);
      std::fflush(stdout);
    }
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"penumbra-bench: speed and memory of the progressive renderer"};
  std::vector<std::string> scenes = {"assets/cornell_box/cornell_box.json",
                                     "assets/dense/dense.json"};
  std::vector<std::string> sizes = {"1280x720", "1920x1080"};
  std::string frames = "128";
  app.add_option("--scene", scenes, "scene files (repeatable)");
  app.add_option("--size", sizes, "resolutions WxH (repeatable)");
  app.add_option("--frames", frames,
                 "intermediate frames m, or auto: until the image is measured converged (the "
                 "table then times the converged picture)");
  bool breakdown = false;
  app.add_flag("--breakdown", breakdown,
               "also time every pass (waits for the GPU after each, so totals grow a little)");
  bool noProbeCache = false;
  app.add_flag("--no-probe-cache", noProbeCache,
               "look the probe volume up every frame (A/B against its per-view cache)");
  int giRounds = 0;
  app.add_option("--gi-cost", giRounds,
                 "instead of the table: what the probe volume adds per frame, from this many "
                 "interleaved runs with and without it (medians)");
  bool noLightCache = false;
  app.add_flag("--no-light-cache", noLightCache,
               "evaluate the area lights every frame (A/B against their per-view cache)");
  bool fullOcclusion = false;
  app.add_flag("--full-occlusion", fullOcclusion,
               "trace a diffuse occlusion ray per pixel (A/B against a ray per 2x2 block)");
  bool separateAccumulation = false;
  app.add_flag("--separate-accumulation", separateAccumulation,
               "accumulate every frame in a pass of its own (A/B against the lighting pass "
               "adding its sample to the mean)");
  std::vector<std::string> extra;
  app.add_option("--set", extra, "KEY=VALUE: a setting for every run, as in the scene file");
  CLI11_PARSE(app, argc, argv);
  gLightCache = !noLightCache;
  gQuarterOcclusion = !fullOcclusion;
  gFusedAccumulation = !separateAccumulation;
  if (std::string bad; !tools::parseSetOptions(extra, gExtraSettings, bad)) {
    std::fprintf(stderr, "penumbra-bench: error: --set expects KEY=VALUE, got '%s'\n", bad.c_str());
    return 1;
  }

  auto ctx = GlContext::create();
  if (!ctx) {
    std::fprintf(stderr, "penumbra-bench: error: %s\n", ctx.message().c_str());
    return 1;
  }
  std::printf("# %s\n", (*ctx)->description().c_str());
  if (giRounds > 0) return giCost(scenes, sizes, frames, giRounds, !noProbeCache);
  std::printf(
      "| scene | triangles | size | frames | preview (ms) | first frame (ms) | per frame (ms) | "
      "time to last frame (s) | read-back (ms) |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|\n");
  for (const auto& scene : scenes) {
    for (const auto& size : sizes) {
      int w = 0, h = 0;
      if (!parseSize(size, w, h)) return 1;
      auto row = run(scene, w, h, frames, breakdown, !noProbeCache);
      if (!row) {
        std::fprintf(stderr, "penumbra-bench: error: %s\n", row.message().c_str());
        return 1;
      }
      std::printf("| %s | %zu | %dx%d | %d | %.1f | %.1f | %.1f | %.2f | %.1f |\n",
                  row->scene.c_str(), row->triangles, w, h, row->frames, row->previewMs,
                  row->firstMs, row->perFrameMs, row->totalS, row->readBackMs);
      if (breakdown) {
        const double n = row->frames;
        std::printf(
            "|   per frame (ms): prepass %.1f, occlusion rays %.1f, shadow maps %.1f (%d passes), "
            "lighting %.1f (%d "
            "passes), accumulate %.1f, probe volume %.1f (%d captures); frame 1: lighting %.1f, "
            "accumulate %.1f, tone map %.1f; tone map alone (median of 9) %.1f | | | | | | | | |\n",
            row->prepassMs / n, row->occlusionMs / n, row->shadowMs / n, row->shadowPasses,
            row->lightingMs / n, row->lightingPasses, row->accumulateMs / n, row->probeMs / n,
            row->probeCaptures, row->firstLightingMs, row->firstAccumulateMs, row->firstDisplayMs,
            row->toneMapMs);
      }
      std::printf(
          "|   GPU memory: %.1f MB (textures, renderbuffers and buffers) | | | | | | | | |\n",
          static_cast<double>(row->gpuBytes) / 1048576.0);
      if (row->probes.probes > 0) {
        std::printf(
            "|   probe volume: %d probes (%dx%dx%d, %d moved off the grid), %.2f MB GPU memory, "
            "%.1f captures per probe after both runs | | | | | | | | |\n",
            row->probes.probes, row->probes.counts[0], row->probes.counts[1], row->probes.counts[2],
            row->probes.moved, static_cast<double>(row->probes.bytes) / 1048576.0,
            row->probes.meanCaptures);
      }
      std::fflush(stdout);
    }
  }
  std::printf("\npeak resident memory: %ld MB\n", peakRssMb());
  return 0;
}
