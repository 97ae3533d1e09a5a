// penumbra-prefilter: turns an equirectangular HDR panorama into everything the renderer needs
// for image-based lighting (GGX-prefiltered specular cube mips, SH irradiance, DFG LUT), as the
// packed single-file environment and/or per-face images. See docs/ibl.md.
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "penumbra/environment_format.h"
#include "penumbra/gl_context.h"
#include "penumbra/ibl.h"
#include "penumbra/image.h"
#include "penumbra/prefilter_gpu.h"
#include "penumbra/version.h"

namespace {

using penumbra::Image;
using penumbra::Status;
namespace ibl = penumbra::ibl;

constexpr const char* kFooter = R"(Outputs in OUTDIR:
  environment.hdr, environment.json   --format packed/all: all faces x mips in one Radiance
                                      RGBE image (width 6*size, faces +X -X +Y -Y +Z -Z left to
                                      right, mips stacked downward) with the manifest embedded
                                      as the header line PENUMBRA_ENV={...} and beside it
  faces/mip<m>_<px|nx|py|ny|pz|nz>.exr|.hdr|.png   --format faces-*/all (PNG: 8-bit sRGB,
                                      clamped at 1, for viewing only)
  preview/mip<m>.png                  --extras or --format all: equirectangular view of each
                                      mip (sRGB, clamped)
  brdf_lut.exr, brdf_lut.png          --extras/all: DFG LUT: x = n.v, y = perceptual roughness (row 0 first),
                                      both at texel centres;
                                      R = A, G = B (specular = prefiltered * (F0 A + B)),
                                      B = A + B (E_ss); PNG linear 8-bit
  sh.json                             --extras/all: 9 radiance SH coefficients;
                                      E(n) = sum A_l L_lm Y_lm(n)
Conventions: glTF frame (+Y up); GL cube-map face orientation; panorama centre column = +X,
u toward +Z, top row = +Y (Blender/three.js); mip m of M has perceptual roughness m/(M-1),
GGX alpha = roughness^2; mip 0 is the unfiltered mirror level; faces halve down to 4 pixels.)";

bool isPowerOfTwo(int v) {
  return v > 0 && (v & (v - 1)) == 0;
}

void fail(const std::string& message) {
  std::fprintf(stderr, "penumbra-prefilter: error: %s\n", message.c_str());
}

// Progress bar on stderr, only drawn when stderr is a terminal.
struct ProgressBar {
  bool enabled = false;
  int drawn = -1;
  void operator()(float fraction) {
    if (!enabled) return;
    const int percent = static_cast<int>(fraction * 100.0f + 0.5f);
    if (percent == drawn) return;
    drawn = percent;
    const int filled = percent * 30 / 100;
    std::fprintf(stderr, "\rprefiltering [%s%s] %3d%%", std::string(filled, '#').c_str(),
                 std::string(30 - filled, '.').c_str(), percent);
    if (percent >= 100) std::fprintf(stderr, "\n");
    std::fflush(stderr);
  }
};

Status checkOutputFolder(const std::string& folder) {
  std::error_code ec;
  std::filesystem::create_directories(folder, ec);
  if (ec)
    return penumbra::makeError("cannot write to output folder '" + folder + "': " + ec.message());
  if (!std::filesystem::is_directory(folder, ec)) {
    return penumbra::makeError("cannot write to output folder '" + folder + "': not a folder");
  }
  const std::string probe = folder + "/.penumbra-write-test-" + std::to_string(getpid());
  std::FILE* f = std::fopen(probe.c_str(), "wb");
  if (!f) {
    return penumbra::makeError("cannot write to output folder '" + folder +
                               "': " + std::strerror(errno));
  }
  std::fclose(f);
  std::filesystem::remove(probe, ec);
  return {};
}

struct Writer {
  std::string outDir;
  bool quiet = false;
  bool extras = false;
  int written = 0;
  bool write(const std::string& relative, const Image& image, bool srgb = false) {
    const std::string path = outDir + "/" + relative;
    Status s = penumbra::writeImage(path, image, penumbra::WriteOptions{.srgbEncode = srgb});
    return report(s, path);
  }
  bool report(const Status& s, const std::string& path) {
    if (!s.ok()) {
      fail(s.message());
      return false;
    }
    ++written;
    if (!quiet) std::printf("wrote %s\n", path.c_str());
    return true;
  }
};

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Prefilters an equirectangular HDR panorama for Penumbra's image-based lighting.",
               "penumbra-prefilter"};
  app.footer(kFooter);
  std::string input;
  std::string outDir;
  int size = ibl::kDefaultFaceSize;
  int samples = ibl::kDefaultSamples;
  int lutSize = 128;
  int threads = 0;
  std::string format = "packed";
  bool useCpu = false;
  bool useGpu = false;
  bool quiet = false;
  bool extras = false;
  app.add_option("INPUT", input, "2:1 equirectangular panorama (.hdr, .exr, .png, ...)")
      ->required();
  app.add_option("-o,--output", outDir, "output folder (created if missing)")->required();
  app.add_option("--size", size, "face size of mip 0, a power of two in [4, 4096]")
      ->capture_default_str();
  app.add_option("--samples", samples,
                 "GGX samples per texel of importance-sampled mip 1, doubled per further mip "
                 "(small rough mips are convolved exactly instead)")
      ->capture_default_str();
  app.add_option("--format", format, "packed | faces-exr | faces-hdr | faces-png | all")
      ->check(CLI::IsMember({"packed", "faces-exr", "faces-hdr", "faces-png", "all"}))
      ->capture_default_str();
  app.add_option("--lut-size", lutSize, "DFG LUT width and height")->capture_default_str();
  auto* cpuFlag = app.add_flag("--cpu", useCpu,
                               "prefilter on the CPU (the reference; by default the GPU is used "
                               "only where it is faster, i.e. on a hardware GPU)");
  app.add_flag("--gpu", useGpu,
               "prefilter on the GPU through OpenGL ES 3.0 (falls back to the CPU "
               "with a warning when no context can be made)")
      ->excludes(cpuFlag);
  std::string sunText = "auto";
  app.add_option("--sun-threshold", sunText,
                 "auto | off | LUMINANCE: the panorama's brightest compact region above it becomes "
                 "a sun (a shadow-casting light in the packed file's manifest) and leaves the "
                 "cube map; only the packed format can carry it")
      ->capture_default_str();
  app.add_option("--threads", threads, "worker threads, 0 = all cores")->capture_default_str();
  app.add_flag("--extras", extras,
               "also write the previews, the DFG table and the SH (as --format all does)");
  app.add_flag("-q,--quiet", quiet, "print errors and warnings only");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help exits 0 through CLI11; every other parse error is one line, like ours.
    if (e.get_exit_code() == static_cast<int>(CLI::ExitCodes::Success)) return app.exit(e);
    fail(std::string(e.what()) + " (see --help)");
    return 2;
  }

  if (!isPowerOfTwo(size) || size < 4 || size > 4096) {
    fail("--size must be a power of two between 4 and 4096, got " + std::to_string(size));
    return 1;
  }
  if (samples < 1 || samples > 65536) {
    fail("--samples must be between 1 and 65536, got " + std::to_string(samples));
    return 1;
  }
  if (lutSize < 1 || lutSize > 4096) {
    fail("--lut-size must be between 1 and 4096, got " + std::to_string(lutSize));
    return 1;
  }
  float sunThreshold = -1.0f;
  if (sunText == "off") {
    sunThreshold = 0.0f;
  } else if (sunText != "auto") {
    char* end = nullptr;
    sunThreshold = std::strtof(sunText.c_str(), &end);
    if (end == sunText.c_str() || *end != '\0' || !(sunThreshold > 0.0f) ||
        !std::isfinite(sunThreshold)) {
      fail("--sun-threshold must be auto, off or a positive luminance, got '" + sunText + "'");
      return 1;
    }
  }
  // Face files have no place for a sun: without the packed file, nothing is taken out.
  if (format != "packed" && format != "all") sunThreshold = 0.0f;
  if (threads < 0) {
    fail("--threads must be 0 (all cores) or positive, got " + std::to_string(threads));
    return 1;
  }
  if (Status s = checkOutputFolder(outDir); !s.ok()) {
    fail(s.message());
    return 1;
  }

  const auto start = std::chrono::steady_clock::now();
  auto panorama = penumbra::readImage(input);
  if (!panorama) {
    fail(panorama.message());
    return 1;
  }
  if (panorama->width != 2 * panorama->height) {
    fail("expected a 2:1 equirectangular panorama, got " + std::to_string(panorama->width) + "x" +
         std::to_string(panorama->height));
    return 1;
  }
  if (auto verdict = ibl::radianceVerdict(ibl::sanitizeRadiance(*panorama), input); !verdict) {
    fail(verdict.message());
    return 1;
  } else if (!verdict->empty()) {
    std::fprintf(stderr, "penumbra-prefilter: warning: %s\n", verdict->c_str());
  }

  const auto read = std::chrono::steady_clock::now();
  ProgressBar bar;
  bar.enabled = !quiet && isatty(STDERR_FILENO);
  ibl::PrefilterOptions options;
  options.faceSize = size;
  options.samples = samples;
  options.threads = threads;
  options.sunThreshold = sunThreshold;
  options.progress = [&bar](float f) { bar(f); };
  // The GPU path when asked for, or by default where it is faster (a hardware GPU).
  std::unique_ptr<penumbra::GlContext> context;
  // Without a GPU device every context is software, where the CPU path is faster: then a
  // context (slow to create, about 12 MB) is made only for an explicit --gpu.
  if (!useCpu && (useGpu || penumbra::GlContext::hardwareGpuPresent())) {
    auto ctx = penumbra::GlContext::create();
    if (ctx) {
      if (useGpu || penumbra::gpuPrefilterIsFaster()) context = std::move(*ctx);
    } else if (useGpu) {
      std::fprintf(stderr,
                   "penumbra-prefilter: warning: no GL context for --gpu (%s); using the CPU\n",
                   ctx.message().c_str());
    }
  }
  auto env =
      context ? penumbra::prefilterGpu(*panorama, options) : ibl::prefilterCpu(*panorama, options);
  if (!quiet) {
    std::fprintf(stderr, "penumbra-prefilter: %s path\n", context ? "GPU" : "CPU");
  }
  if (!env) {
    fail(env.message());
    return 1;
  }
  env->generator = std::string("penumbra-prefilter ") + penumbra::version();
  if (!quiet && env->sun) {
    const ibl::Sun& sun = *env->sun;
    std::printf("sun: direction (%.4f, %.4f, %.4f), angular radius %.3f degrees, irradiance "
                "(%.4g, %.4g, %.4g), threshold %.4g\n",
                sun.direction.x, sun.direction.y, sun.direction.z,
                sun.angularRadius * 57.29578f, sun.irradiance.x, sun.irradiance.y,
                sun.irradiance.z, sun.threshold);
  }
  const auto prefiltered = std::chrono::steady_clock::now();
  const auto seconds = [](auto from, auto to) {
    return std::chrono::duration<double>(to - from).count();
  };

  Writer out{outDir, quiet};
  const bool all = format == "all";
  if (format == "packed" || all) {
    const std::string path = outDir + "/environment.hdr";
    if (!out.report(penumbra::writePackedEnvironment(path, *env), path)) return 1;
    if (!quiet) std::printf("wrote %s/environment.json\n", outDir.c_str());
  }
  std::vector<std::string> faceExtensions;
  if (format == "faces-exr" || all) faceExtensions.push_back(".exr");
  if (format == "faces-hdr" || all) faceExtensions.push_back(".hdr");
  if (format == "faces-png" || all) faceExtensions.push_back(".png");
  if (!faceExtensions.empty()) {
    std::error_code ec;
    std::filesystem::create_directories(outDir + "/faces", ec);
  }
  const ibl::Cubemap& cube = env->specular;
  for (const std::string& ext : faceExtensions) {
    for (int m = 0; m < cube.mipCount(); ++m) {
      for (int f = 0; f < ibl::kFaceCount; ++f) {
        const std::string name = "faces/mip" + std::to_string(m) + "_" + ibl::faceTag(f) + ext;
        if (!out.write(name, cube.face(m, f), ext == ".png")) return 1;
      }
    }
  }
  // Previews, the DFG table and the SH are for people and other renderers; an asset pipeline
  // that needs only the packed file does not pay for them.
  if (extras || all) {
    std::error_code ec;
    std::filesystem::create_directories(outDir + "/preview", ec);
    for (int m = 0; m < cube.mipCount(); ++m) {
      const Image preview = ibl::cubemapToPanorama(cube, m, 4 * cube.faceSize(m), threads);
      if (!out.write("preview/mip" + std::to_string(m) + ".png", preview, true)) return 1;
    }
    const Image lut = ibl::computeBrdfLut({.size = lutSize, .samples = 512, .threads = threads});
    if (!out.write("brdf_lut.exr", lut) || !out.write("brdf_lut.png", lut)) return 1;
    const std::string shPath = outDir + "/sh.json";
    if (!out.report(ibl::writeShJson(shPath, env->sh), shPath)) return 1;
  }
  if (!quiet) {
    std::printf(
        "prefiltered %dx%d to %d-pixel faces, %d mips, %d samples: read %.2f s, prefilter "
        "%.2f s, writing %.2f s\n",
        panorama->width, panorama->height, size, cube.mipCount(), samples, seconds(start, read),
        seconds(read, prefiltered), seconds(prefiltered, std::chrono::steady_clock::now()));
  }
  return 0;
}
