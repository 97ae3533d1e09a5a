// penumbra-soak: the long-run stability check (soak.h): 10,000 frames of the Cornell box at
// 64x64 as restarted 4096-frame accumulations, with NaN injection, resident-memory sampling,
// determinism across restarts and convergence checks. Exit 0 when every check passes.
#include <chrono>
#include <cstdio>
#include <filesystem>

#include <CLI/CLI.hpp>

#include "penumbra/gl_context.h"
#include "soak.h"

int main(int argc, char** argv) {
  using namespace penumbra;
  CLI::App app{"penumbra-soak: long-run stability check (see docs/bad-inputs.md)"};
  soak::Options o;
  std::string root = PENUMBRA_SOURCE_DIR;
  app.add_option("--source-dir", root, "repository root (for assets/cornell_box)");
  app.add_option("--frames", o.totalFrames, "frames to draw in all")->capture_default_str();
  app.add_option("--run-frames", o.runFrames, "frames per accumulation (<= 4096)")
      ->capture_default_str();
  app.add_option("--size", o.width, "image width and height")->capture_default_str();
  app.add_option("--sample-every", o.sampleEvery, "memory sample interval")->capture_default_str();
  app.add_option("--max-growth-mb", o.maxGrowthMb, "allowed resident growth after warm-up")
      ->capture_default_str();
  CLI11_PARSE(app, argc, argv);
  o.height = o.width;
  o.warmupFrames = o.sampleEvery;
  o.cornellGltf = (std::filesystem::path(root) / "assets/cornell_box/cornell_box.gltf").string();
  auto ctx = GlContext::create();
  if (!ctx) {
    std::fprintf(stderr, "penumbra-soak: error: %s\n", ctx.message().c_str());
    return 1;
  }
  o.desktopGl = (*ctx)->isDesktopGl();
  const auto t0 = std::chrono::steady_clock::now();
  auto rep = soak::run(o, [](const std::string& m) { std::fprintf(stderr, "penumbra-soak: %s\n", m.c_str()); });
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (!rep.ok()) {
    std::fprintf(stderr, "penumbra-soak: error: %s\n", rep.failure.c_str());
    return 1;
  }
  std::fprintf(stderr,
               "penumbra-soak: ok: %d frames in %.1f s; resident %.1f MB after warm-up, peak "
               "%.1f MB, final %.1f MB; restart max diff %.2g; %d vs %d frames mean abs diff "
               "%.4g (mean radiance %.4g)\n",
               rep.framesDrawn, secs, rep.baselineMb, rep.peakMb, rep.finalMb, rep.restartMaxAbs,
               o.runFrames, o.runFrames / 2, rep.convergenceMeanAbs, rep.meanRadiance);
  return 0;
}
