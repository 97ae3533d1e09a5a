// penumbra-render: renders a Penumbra scene file or a .gltf/.glb progressively to PNG (the
// displayed image) or EXR (linear radiance before exposure and tone mapping).
#include <unistd.h>

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "../common/setting_flags.h"
#include "batch.h"
#include "output.h"
#include "penumbra/batch.h"
#include "penumbra/gl_context.h"
#include "penumbra/image.h"
#include "penumbra/render_job.h"
#include "penumbra/renderer.h"
#include "penumbra/version.h"
#include "progress.h"

namespace fs = std::filesystem;
using namespace penumbra;
using penumbra::tools::writeOutput;

namespace {

int fail(const std::string& message) {
  std::fprintf(stderr, "penumbra-render: error: %s\n", message.c_str());
  return 1;
}

// Frames 1, 2, 4, ... m side by side (wrapping after 4 per row), at half size each.
Image contactSheet(const std::vector<Image>& frames) {
  const int cols = std::min<int>(4, static_cast<int>(frames.size()));
  const int rows = (static_cast<int>(frames.size()) + cols - 1) / cols;
  const int w = frames[0].width / 2, h = frames[0].height / 2;
  Image sheet(cols * w, rows * h, 4, 0.0f);
  for (size_t i = 0; i < frames.size(); ++i) {
    const int ox = static_cast<int>(i) % cols * w, oy = static_cast<int>(i) / cols * h;
    for (int y = 0; y < h; ++y) {
      for (int x = 0; x < w; ++x) {
        for (int c = 0; c < 4; ++c) {
          float sum = 0.0f;
          for (int k = 0; k < 4; ++k) sum += frames[i].pixel(2 * x + (k & 1), 2 * y + k / 2)[c];
          sheet.pixel(ox + x, oy + y)[c] = sum * 0.25f;
        }
      }
    }
  }
  return sheet;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "penumbra-render: progressive physically-based rendering of glTF scenes lit by an\n"
      "HDR environment and area lights. OUT.png is the displayed image (exposure, tone\n"
      "mapping, sRGB); OUT.exr is the linear radiance before exposure.\n"
      "With --batch JOBS.jsonl it renders one job per line in one process."};
  app.set_version_flag("--version", std::string("penumbra-render ") + version());
  std::string outPath, size, envText, glName = "auto", contactPath, shardText;
  tools::BatchOptions batch;
  int saveEvery = 0;
  int64_t memoryBudgetMb = 2048;
  bool quiet = false, info = false, halfFloat = false;
  JobRequest request;
  app.add_option("scene", request.scenePath, "scene file (.json) or model (.gltf/.glb)");
  app.add_option("-o,--output", outPath, "output image (.png displayed, .exr linear)");
  app.add_option("--size", size, "resolution WxH (default from the scene file, else 1280x720)");
  app.add_option("--camera", request.camera, "camera name or index");
  app.add_option("--animation", request.animation,
                 "glTF animation to pose the model with: name or index (default: the scene "
                 "file's, else at rest; --time alone takes the first)");
  float time = 0.0f;
  CLI::Option* timeOption =
      app.add_option("--time", time, "seconds into the animation (its ends hold before and after)");
  app.add_option("--variant", request.variant,
                 "KHR_materials_variants variant: name or index (default: the scene file's, "
                 "else the primitives' own materials)");
  app.add_option("--env", envText,
                 "environment: none (black), studio (the neutral studio shipped with "
                 "Penumbra), r,g,b (uniform radiance) or a file (packed .hdr from "
                 "penumbra-prefilter, or a panorama). Default: the scene file's, else black "
                 "for a scene with lights and studio for one without");
  tools::SettingFlags settingFlags;
  settingFlags.add(app);
  app.add_option("--gl", glName, "GL backend: auto, egl, egl-device or osmesa");
  app.add_option("--save-every", saveEvery, "also write OUT_fNNNN.png every K frames");
  app.add_option("--contact-sheet", contactPath, "write frames 1, 2, 4, ... m side by side");
  app.add_flag("--half-float", halfFloat, "accumulate in RGBA16F (the weak-device path)");
  app.add_option("--memory-budget", memoryBudgetMb,
                 "memory budget in MB for the decoded scene and, separately, the estimated GPU "
                 "memory of the render targets (default 2048)");
  app.add_flag("--info", info, "print the GL context and capability report");
  app.add_flag("-q,--quiet", quiet, "no progress bar");
  app.add_option("--batch", batch.jobsPath,
                 "render every job of a JSON-lines file, one object per line with these "
                 "options' names (\"scene\", \"output\", \"size\", \"env\", \"frames\", ...; "
                 "the command line's apply under them) with one GL context")
      ->group("Batch");
  app.add_option("--results", batch.resultsPath,
                 "batch: results file, one JSON line per job (default JOBS.results.jsonl)")
      ->group("Batch");
  app.add_option("--shard", shardText,
                 "batch: render only shard I of N (jobs k with k % N == I), e.g. "
                 "$SLURM_ARRAY_TASK_ID/$SLURM_ARRAY_TASK_COUNT")
      ->group("Batch");
  app.add_flag("--force", batch.force, "batch: render jobs whose output exists")->group("Batch");
  CLI11_PARSE(app, argc, argv);
  if (timeOption->count() > 0) request.time = time;
  const bool batchMode = !batch.jobsPath.empty();
  if (batchMode && (!request.scenePath.empty() || !outPath.empty())) {
    return fail("--batch takes its scenes and outputs from the job file: no scene or -o");
  }
  if (!batchMode && (request.scenePath.empty() || outPath.empty())) {
    return fail("give a scene and -o OUT (or --batch JOBS.jsonl); --help lists the options");
  }
  if (!batchMode && (!shardText.empty() || !batch.resultsPath.empty() || batch.force)) {
    return fail("--shard, --results and --force apply to --batch only");
  }

  request.settings = settingFlags.overrides();
  if (!size.empty()) {
    auto wh = parseSize(size);
    if (!wh) return fail("--" + wh.message());
    request.settings.emplace_back("width", std::to_string(wh->first));
    request.settings.emplace_back("height", std::to_string(wh->second));
  }
  if (!envText.empty()) {
    auto spec = parseEnvironmentSpec(envText);
    if (!spec) return fail(spec.message());
    request.environment = *spec;
  }
  if (memoryBudgetMb < 1 || memoryBudgetMb > (int64_t{1} << 30)) {
    return fail("--memory-budget must be a positive number of MB, got " +
                std::to_string(memoryBudgetMb));
  }
  request.memoryBudgetBytes = memoryBudgetMb << 20;
  if (batchMode) {
    if (!shardText.empty()) {
      auto shard = parseShard(shardText);
      if (!shard) return fail(shard.message());
      batch.shard = *shard;
    }
    auto backend = parseBackend(glName);
    if (!backend) return fail(backend.message());
    batch.backend = *backend;
    batch.defaults = request;
    batch.quiet = quiet;
    batch.info = info;
    batch.halfFloat = halfFloat;
    if (saveEvery > 0 || !contactPath.empty()) {
      return fail("--save-every and --contact-sheet apply to a single render, not --batch");
    }
    return tools::runBatch(batch);
  }
  // Refuse an output we cannot write before spending time on the render.
  const fs::path outDir = fs::path(outPath).parent_path();
  if (!outDir.empty() && !fs::is_directory(outDir)) {
    return fail("output folder '" + outDir.string() + "' does not exist");
  }
  if (!isImageOutputPath(outPath)) {
    return fail("output must end in .png, .exr or .hdr: " + outPath);
  }

  auto backend = parseBackend(glName);
  if (!backend) return fail(backend.message());
  auto context = GlContext::create({.backend = *backend});
  if (!context) return fail(context.message());

  auto job = RenderJob::load(request);
  if (!job) return fail(job.message());
  if (!quiet) {
    for (const auto& w : job->warnings)
      std::fprintf(stderr, "penumbra-render: warning: %s\n", w.c_str());
  }
  const RenderSettings& s = job->settings;

  auto renderer =
      Renderer::create({.desktopGl = (*context)->isDesktopGl(), .forceHalfFloat = halfFloat});
  if (!renderer) return fail(renderer.message());
  Renderer& r = **renderer;
  if (info) {
    std::fprintf(stderr, "%s\n%s", (*context)->description().c_str(), r.capabilityReport().c_str());
    std::fprintf(stderr, "environment: %s\n", job->environmentName.c_str());
  }
  if (auto st = job->applyTo(r); !st) return fail(st.message());

  tools::ProgressBar bar("rendering", r.convergence().expectedFrames,
                         !quiet && isatty(STDERR_FILENO));
  std::vector<Image> sheet;
  int nextSheetFrame = 1;
  const auto start = std::chrono::steady_clock::now();
  while (!r.converged()) {
    auto frame = r.step();
    if (!frame) return fail(frame.message());
    bar.update(*frame, r.convergence().expectedFrames);
    if (saveEvery > 0 && (*frame % saveEvery == 0)) {
      char suffix[32];
      std::snprintf(suffix, sizeof suffix, "_f%04d.png", *frame);
      const std::string p =
          (fs::path(outPath).parent_path() / fs::path(outPath).stem()).string() + suffix;
      if (auto st = writeOutput(p, r); !st) return fail(st.message());
    }
    if (!contactPath.empty() && (*frame == nextSheetFrame || r.converged())) {
      auto d = r.readDisplay();
      if (!d) return fail(d.message());
      sheet.push_back(std::move(*d));
      while (nextSheetFrame <= *frame) nextSheetFrame *= 2;
    }
  }
  bar.finish();
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (auto st = writeOutput(outPath, r); !st) return fail(st.message());
  if (!contactPath.empty() && !sheet.empty()) {
    if (auto st = writeImage(contactPath, contactSheet(sheet)); !st) return fail(st.message());
  }
  if (!quiet) {
    const ConvergenceInfo c = r.convergence();
    std::string how;
    if (c.automatic) {
      char buf[200];
      std::snprintf(buf, sizeof buf,
                    " (auto: %s; estimated error %.2f 8-bit steps RMS, 99 %% of tiles within "
                    "%.2f; %.0f %% of tiles skipped)",
                    c.converged ? "converged" : "stopped at maxFrames", c.error, c.tileError,
                    100.0 * c.skippedTiles);
      how = buf;
    }
    std::fprintf(stderr, "penumbra-render: %d frames at %dx%d in %.2f s -> %s%s\n", r.framesDone(),
                 s.width, s.height, seconds, outPath.c_str(), how.c_str());
  }
  return 0;
}
