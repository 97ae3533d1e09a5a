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

#include "penumbra/environment.h"
#include "penumbra/gl_context.h"
#include "penumbra/image.h"
#include "penumbra/renderer.h"
#include "penumbra/scene.h"
#include "penumbra/scene_file.h"
#include "penumbra/version.h"
#include "progress.h"

namespace fs = std::filesystem;
using namespace penumbra;

namespace {

int fail(const std::string& message) {
  std::fprintf(stderr, "penumbra-render: error: %s\n", message.c_str());
  return 1;
}

bool hasExtension(const std::string& path, const char* ext) {
  std::string e = fs::path(path).extension().string();
  for (auto& c : e) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return e == ext;
}

Status writeOutput(const std::string& path, Renderer& renderer) {
  if (hasExtension(path, ".exr") || hasExtension(path, ".hdr")) {
    auto radiance = renderer.readRadiance();
    if (!radiance) return radiance.error();
    return writeImage(path, *radiance);
  }
  auto display = renderer.readDisplay();
  if (!display) return display.error();
  return writeImage(path, *display);
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
      "mapping, sRGB); OUT.exr is the linear radiance before exposure."};
  app.set_version_flag("--version", std::string("penumbra-render ") + version());
  std::string scenePath, outPath, size, cameraName, envPath, toneMapper, glName = "auto",
                                                                         contactPath;
  float exposure = 0, fd = 0, occDistance = 0, envIntensity = -1, envRotation = 0;
  int frames = 0, lightSamples = -1, shadowSize = 0, saveEvery = 0;
  int64_t memoryBudgetMb = 2048;
  uint32_t seed = 0;
  bool noSsgi = false, quiet = false, noBackground = false, info = false, halfFloat = false;
  app.add_option("scene", scenePath, "scene file (.json) or model (.gltf/.glb)")->required();
  app.add_option("-o,--output", outPath, "output image (.png displayed, .exr linear)")->required();
  app.add_option("--size", size, "resolution WxH (default from the scene file, else 1280x720)");
  app.add_option("--camera", cameraName, "camera name or index");
  app.add_option("--env", envPath,
                 "environment: packed .hdr from penumbra-prefilter or a panorama");
  auto* expOpt = app.add_option("--exposure", exposure, "exposure in EV");
  app.add_option("--tonemap", toneMapper, "pbr-neutral (default), aces, reinhard or none");
  auto* intensityOpt =
      app.add_option("--env-intensity", envIntensity, "environment intensity multiplier");
  auto* rotOpt =
      app.add_option("--env-rotation", envRotation, "environment rotation about +Y, degrees");
  app.add_flag("--no-background", noBackground, "black background instead of the environment");
  app.add_option("--gl", glName, "GL backend: auto, egl, egl-device or osmesa");
  auto* framesOpt =
      app.add_option("--frames", frames, "intermediate frames m (1..4096, default 128)");
  auto* fdOpt = app.add_option("--fd", fd, "fraction of frames before direct light starts (0.3)");
  auto* occOpt =
      app.add_option("--occlusion-distance", occDistance, "occlusion distance d_occ (m)");
  auto* samplesOpt = app.add_option("--light-samples", lightSamples,
                                    "shadow-map samples per area light (0 = auto)");
  auto* shadowOpt = app.add_option("--shadow-size", shadowSize, "shadow-map size (power of two)");
  app.add_flag("--no-ssgi", noSsgi, "turn off one-bounce screen-space indirect light");
  float indirectClamp = 0;
  auto* clampOpt = app.add_option("--indirect-clamp", indirectClamp,
                                  "largest radiance of one indirect sample (0 = no limit)");
  auto* seedOpt = app.add_option("--seed", seed, "seed of the sample sequences");
  app.add_option("--save-every", saveEvery, "also write OUT_fNNNN.png every K frames");
  app.add_option("--contact-sheet", contactPath, "write frames 1, 2, 4, ... m side by side");
  app.add_flag("--half-float", halfFloat, "accumulate in RGBA16F (the weak-device path)");
  app.add_option("--memory-budget", memoryBudgetMb,
                 "memory budget in MB for the decoded scene and, separately, the estimated GPU "
                 "memory of the render targets (default 2048)");
  app.add_flag("--info", info, "print the GL context and capability report");
  app.add_flag("-q,--quiet", quiet, "no progress bar");
  CLI11_PARSE(app, argc, argv);

  auto sceneFile = loadSceneFile(scenePath);
  if (!sceneFile) return fail(sceneFile.message());
  SceneFile sf = std::move(*sceneFile);
  RenderSettings& s = sf.settings;
  if (!size.empty()) {
    int w = 0, h = 0;
    char x = 0;
    if (std::sscanf(size.c_str(), "%d%c%d", &w, &x, &h) != 3 || (x != 'x' && x != 'X')) {
      return fail("--size must be WxH, e.g. 1280x720 (got '" + size + "')");
    }
    s.width = w;
    s.height = h;
  }
  if (*expOpt) s.exposure = exposure;
  if (!toneMapper.empty()) {
    auto t = parseToneMapper(toneMapper);
    if (!t) return fail(t.message());
    s.toneMapper = *t;
  }
  if (*intensityOpt) s.environmentIntensity = envIntensity;
  if (*rotOpt) s.environmentRotation = envRotation;
  if (noBackground) s.showBackground = false;
  if (*framesOpt) s.progressive.frames = frames;
  if (*fdOpt) s.progressive.directDelay = fd;
  if (*occOpt) s.progressive.occlusionDistance = occDistance;
  if (*samplesOpt) s.progressive.lightSamples = lightSamples;
  if (*shadowOpt) s.progressive.shadowMapSize = shadowSize;
  if (noSsgi) s.progressive.screenSpaceIndirect = false;
  if (*clampOpt) s.progressive.indirectClamp = indirectClamp;
  if (*seedOpt) s.progressive.seed = seed;
  if (!envPath.empty()) sf.environmentPath = envPath;
  if (!cameraName.empty()) sf.camera = cameraName;
  if (auto st = validate(s); !st) return fail(st.message());
  if (memoryBudgetMb < 1 || memoryBudgetMb > (int64_t{1} << 30)) {
    return fail("--memory-budget must be a positive number of MB, got " +
                std::to_string(memoryBudgetMb));
  }
  const int64_t budgetBytes = memoryBudgetMb << 20;
  {
    // Render targets: about 5 RGBA32F colour targets and 2 32-bit depth buffers per pixel,
    // plus up to 4 shadow maps of 32-bit depth. Checked before any GL allocation.
    const int64_t pixels = int64_t{s.width} * s.height;
    const int64_t shadow = int64_t{s.progressive.shadowMapSize} * s.progressive.shadowMapSize;
    const int64_t need = pixels * (5 * 16 + 2 * 4) + 4 * shadow * 4;
    if (need > budgetBytes) {
      return fail("render targets for " + std::to_string(s.width) + "x" +
                  std::to_string(s.height) + " need about " + std::to_string(need >> 20) +
                  " MB of GPU memory, over the memory budget of " +
                  std::to_string(memoryBudgetMb) + " MB (--memory-budget)");
    }
  }
  if (!quiet) {
    for (const auto& w : sf.warnings)
      std::fprintf(stderr, "penumbra-render: warning: %s\n", w.c_str());
  }
  // Refuse an output we cannot write before spending time on the render.
  const fs::path outDir = fs::path(outPath).parent_path();
  if (!outDir.empty() && !fs::is_directory(outDir)) {
    return fail("output folder '" + outDir.string() + "' does not exist");
  }
  if (!hasExtension(outPath, ".png") && !hasExtension(outPath, ".exr") &&
      !hasExtension(outPath, ".hdr")) {
    return fail("output must end in .png, .exr or .hdr: " + outPath);
  }

  auto backend = parseBackend(glName);
  if (!backend) return fail(backend.message());
  auto context = GlContext::create({.backend = *backend});
  if (!context) return fail(context.message());

  LoadOptions loadOptions;
  loadOptions.memoryBudgetBytes = budgetBytes;
  auto scene = loadGltf(sf.gltfPath, loadOptions);
  if (!scene) return fail(scene.message());
  if (!quiet) {
    for (const auto& w : scene->warnings)
      std::fprintf(stderr, "penumbra-render: warning: %s\n", w.c_str());
  }
  PackedEnvironment env;
  if (!sf.environmentPath.empty()) {
    auto e = loadEnvironment(sf.environmentPath);
    if (!e) return fail(e.message());
    env = std::move(*e);
  } else {
    env = uniformEnvironment(sf.uniformEnvironment);
  }

  auto renderer =
      Renderer::create({.desktopGl = (*context)->isDesktopGl(), .forceHalfFloat = halfFloat});
  if (!renderer) return fail(renderer.message());
  Renderer& r = **renderer;
  if (info) {
    std::fprintf(stderr, "%s\n%s", (*context)->description().c_str(), r.capabilityReport().c_str());
  }
  if (auto st = r.setSettings(s); !st) return fail(st.message());
  if (auto st = r.setScene(*scene); !st) return fail(st.message());
  if (auto st = r.setEnvironment(env); !st) return fail(st.message());
  if (!sf.camera.empty()) {
    auto idx = findCamera(*scene, sf.camera);
    if (!idx) return fail(idx.message());
    r.setCamera(scene->cameras[static_cast<size_t>(*idx)]);
  } else if (!scene->cameras.empty()) {
    r.setCamera(scene->cameras[0]);
  } else {
    r.setCamera(defaultCamera(*scene));
  }

  tools::ProgressBar bar("rendering", s.progressive.frames, !quiet && isatty(STDERR_FILENO));
  std::vector<Image> sheet;
  int nextSheetFrame = 1;
  const auto start = std::chrono::steady_clock::now();
  while (!r.converged()) {
    auto frame = r.step();
    if (!frame) return fail(frame.message());
    bar.update(*frame);
    if (saveEvery > 0 && (*frame % saveEvery == 0)) {
      char suffix[32];
      std::snprintf(suffix, sizeof suffix, "_f%04d.png", *frame);
      const std::string p =
          (fs::path(outPath).parent_path() / fs::path(outPath).stem()).string() + suffix;
      if (auto st = writeOutput(p, r); !st) return fail(st.message());
    }
    if (!contactPath.empty() && (*frame == nextSheetFrame || *frame == s.progressive.frames)) {
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
    std::fprintf(stderr, "penumbra-render: %d frames at %dx%d in %.2f s -> %s\n",
                 s.progressive.frames, s.width, s.height, seconds, outPath.c_str());
  }
  return 0;
}
