// penumbra-prefilter: turns an equirectangular HDR panorama into everything the renderer needs
// for image-based lighting (GGX-prefiltered specular cube mips, SH irradiance, DFG LUT), as the
// packed single-file environment and/or per-face images. See docs/ibl.md.
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
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

constexpr const char* kFooter = R"(Outputs in OUTDIR (in OUTDIR/<name>/ for each of several inputs):
  environment.hdr, environment.json   --format packed/all: all faces x mips in one Radiance
                                      RGBE image (width 6*size, faces +X -X +Y -Y +Z -Z left to
                                      right, mips stacked downward) with the manifest embedded
                                      as the header line PENUMBRA_ENV={...} and beside it
  environment.ktx2                    --format ktx2/all: the same cube map for other engines
                                      (three.js KTX2Loader, glTF Sample Viewer): RGBA16F, every
                                      mip, the manifest under the key "penumbra.environment";
                                      alone, the sun stays in the cube map
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
  std::string label;
  int drawn = -1;
  void operator()(float fraction) {
    if (!enabled) return;
    const int percent = static_cast<int>(fraction * 100.0f + 0.5f);
    if (percent == drawn) return;
    drawn = percent;
    const int filled = percent * 30 / 100;
    std::fprintf(stderr, "\rprefiltering %s [%s%s] %3d%%", label.c_str(),
                 std::string(filled, '#').c_str(), std::string(30 - filled, '.').c_str(), percent);
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

// Which files to write (--format, a comma-separated list).
struct Formats {
  bool packed = false, ktx2 = false, facesExr = false, facesHdr = false, facesPng = false;
  bool extras = false;  // previews, the DFG table, the SH
};

Formats parseFormats(const std::vector<std::string>& names) {
  Formats f;
  for (const std::string& n : names) {
    const bool all = n == "all";
    f.packed |= all || n == "packed";
    f.ktx2 |= all || n == "ktx2";
    f.facesExr |= all || n == "faces-exr";
    f.facesHdr |= all || n == "faces-hdr";
    f.facesPng |= all || n == "faces-png";
    f.extras |= all;
  }
  return f;
}

struct Options {
  int size = ibl::kDefaultFaceSize;
  int samples = ibl::kDefaultSamples;
  int lutSize = 128;
  int threads = 0;
  float sunThreshold = -1.0f;
  Formats formats;
  bool quiet = false;
};

double secondsBetween(std::chrono::steady_clock::time_point from,
                      std::chrono::steady_clock::time_point to) {
  return std::chrono::duration<double>(to - from).count();
}

// Writes what --format asks for into out.outDir.
bool writeOutputs(Writer& out, const penumbra::PackedEnvironment& env, const Options& o) {
  const Formats& f = o.formats;
  if (f.packed) {
    const std::string path = out.outDir + "/environment.hdr";
    if (!out.report(penumbra::writePackedEnvironment(path, env), path)) return false;
    if (!o.quiet) std::printf("wrote %s/environment.json\n", out.outDir.c_str());
  }
  if (f.ktx2) {
    const std::string path = out.outDir + "/environment.ktx2";
    if (!out.report(penumbra::writeKtx2Environment(path, env), path)) return false;
  }
  std::vector<std::string> faceExtensions;
  if (f.facesExr) faceExtensions.push_back(".exr");
  if (f.facesHdr) faceExtensions.push_back(".hdr");
  if (f.facesPng) faceExtensions.push_back(".png");
  if (!faceExtensions.empty()) {
    std::error_code ec;
    std::filesystem::create_directories(out.outDir + "/faces", ec);
  }
  const ibl::Cubemap& cube = env.specular;
  for (const std::string& ext : faceExtensions) {
    for (int m = 0; m < cube.mipCount(); ++m) {
      for (int face = 0; face < ibl::kFaceCount; ++face) {
        const std::string name = "faces/mip" + std::to_string(m) + "_" + ibl::faceTag(face) + ext;
        if (!out.write(name, cube.face(m, face), ext == ".png")) return false;
      }
    }
  }
  // Previews, the DFG table and the SH are for people and other renderers; an asset pipeline
  // that needs only the packed file does not pay for them.
  if (f.extras) {
    std::error_code ec;
    std::filesystem::create_directories(out.outDir + "/preview", ec);
    for (int m = 0; m < cube.mipCount(); ++m) {
      const Image preview = ibl::cubemapToPanorama(cube, m, 4 * cube.faceSize(m), o.threads);
      if (!out.write("preview/mip" + std::to_string(m) + ".png", preview, true)) return false;
    }
    const Image lut =
        ibl::computeBrdfLut({.size = o.lutSize, .samples = 512, .threads = o.threads});
    if (!out.write("brdf_lut.exr", lut) || !out.write("brdf_lut.png", lut)) return false;
    const std::string shPath = out.outDir + "/sh.json";
    if (!out.report(ibl::writeShJson(shPath, env.sh), shPath)) return false;
  }
  return true;
}

// Prefilters one panorama into outDir. `label` names it in the progress bar ("a.hdr (2 of 3)").
bool prefilterOne(const std::string& input, const std::string& outDir, const std::string& label,
                  const Options& o, bool onGpu) {
  if (Status s = checkOutputFolder(outDir); !s.ok()) {
    fail(s.message());
    return false;
  }
  const auto start = std::chrono::steady_clock::now();
  auto panorama = penumbra::readImage(input);
  if (!panorama) {
    fail(panorama.message());
    return false;
  }
  if (panorama->width != 2 * panorama->height) {
    fail(input + ": expected a 2:1 equirectangular panorama, got " +
         std::to_string(panorama->width) + "x" + std::to_string(panorama->height));
    return false;
  }
  if (auto verdict = ibl::radianceVerdict(ibl::sanitizeRadiance(*panorama), input); !verdict) {
    fail(verdict.message());
    return false;
  } else if (!verdict->empty()) {
    std::fprintf(stderr, "penumbra-prefilter: warning: %s\n", verdict->c_str());
  }

  const auto read = std::chrono::steady_clock::now();
  ProgressBar bar;
  bar.enabled = !o.quiet && isatty(STDERR_FILENO);
  bar.label = label;
  ibl::PrefilterOptions options;
  options.faceSize = o.size;
  options.samples = o.samples;
  options.threads = o.threads;
  // Face and KTX2 files have no place for a sun that other engines would read: without the
  // packed file, nothing is taken out.
  options.sunThreshold = o.formats.packed ? o.sunThreshold : 0.0f;
  options.progress = [&bar](float f) { bar(f); };
  auto env =
      onGpu ? penumbra::prefilterGpu(*panorama, options) : ibl::prefilterCpu(*panorama, options);
  if (!o.quiet) std::fprintf(stderr, "penumbra-prefilter: %s path\n", onGpu ? "GPU" : "CPU");
  if (!env) {
    fail(env.message());
    return false;
  }
  env->generator = std::string("penumbra-prefilter ") + penumbra::version();
  if (!o.quiet && env->sun) {
    const ibl::Sun& sun = *env->sun;
    std::printf(
        "sun: direction (%.4f, %.4f, %.4f), angular radius %.3f degrees, irradiance "
        "(%.4g, %.4g, %.4g), threshold %.4g\n",
        sun.direction.x, sun.direction.y, sun.direction.z, sun.angularRadius * 57.29578f,
        sun.irradiance.x, sun.irradiance.y, sun.irradiance.z, sun.threshold);
  }
  if (env->sun && o.formats.ktx2) {
    std::fprintf(stderr,
                 "penumbra-prefilter: warning: %s: the sun left the cube map for the packed "
                 "file, so environment.ktx2 lacks it (--sun-threshold off keeps it in)\n",
                 input.c_str());
  }
  const auto prefiltered = std::chrono::steady_clock::now();
  Writer out{outDir, o.quiet};
  if (!writeOutputs(out, *env, o)) return false;
  if (!o.quiet) {
    std::printf(
        "prefiltered %s %dx%d to %d-pixel faces, %d mips, %d samples: read %.2f s, prefilter "
        "%.2f s, writing %.2f s\n",
        input.c_str(), panorama->width, panorama->height, o.size, env->specular.mipCount(),
        o.samples, secondsBetween(start, read), secondsBetween(read, prefiltered),
        secondsBetween(prefiltered, std::chrono::steady_clock::now()));
  }
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "Prefilters equirectangular HDR panoramas for Penumbra's image-based lighting "
      "and for other engines (KTX2).",
      "penumbra-prefilter"};
  app.footer(kFooter);
  std::vector<std::string> inputs;
  std::string outDir;
  Options o;
  std::vector<std::string> formatNames = {"packed"};
  bool useCpu = false;
  bool useGpu = false;
  bool extras = false;
  app.add_option("INPUT", inputs,
                 "2:1 equirectangular panoramas (.hdr, .exr, .png, ...); with several, each "
                 "goes to OUTDIR/<its name without extension>/")
      ->required();
  app.add_option("-o,--output", outDir, "output folder (created if missing)")->required();
  app.add_option("--size", o.size, "face size of mip 0, a power of two in [4, 4096]")
      ->capture_default_str();
  app.add_option("--samples", o.samples,
                 "GGX samples per texel of importance-sampled mip 1, doubled per further mip "
                 "(small rough mips are convolved exactly instead)")
      ->capture_default_str();
  app.add_option("--format", formatNames,
                 "packed | ktx2 | faces-exr | faces-hdr | faces-png | all, or several "
                 "separated by commas (packed,ktx2)")
      ->delimiter(',')
      ->check(CLI::IsMember({"packed", "ktx2", "faces-exr", "faces-hdr", "faces-png", "all"}))
      ->capture_default_str();
  app.add_option("--lut-size", o.lutSize, "DFG LUT width and height")->capture_default_str();
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
  app.add_option("--threads", o.threads, "worker threads, 0 = all cores")->capture_default_str();
  app.add_flag("--extras", extras,
               "also write the previews, the DFG table and the SH (as --format all does)");
  app.add_flag("-q,--quiet", o.quiet, "print errors and warnings only");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help exits 0 through CLI11; every other parse error is one line, like ours.
    if (e.get_exit_code() == static_cast<int>(CLI::ExitCodes::Success)) return app.exit(e);
    fail(std::string(e.what()) + " (see --help)");
    return 2;
  }
  o.formats = parseFormats(formatNames);
  o.formats.extras |= extras;

  if (!isPowerOfTwo(o.size) || o.size < 4 || o.size > 4096) {
    fail("--size must be a power of two between 4 and 4096, got " + std::to_string(o.size));
    return 1;
  }
  if (o.samples < 1 || o.samples > 65536) {
    fail("--samples must be between 1 and 65536, got " + std::to_string(o.samples));
    return 1;
  }
  if (o.lutSize < 1 || o.lutSize > 4096) {
    fail("--lut-size must be between 1 and 4096, got " + std::to_string(o.lutSize));
    return 1;
  }
  if (sunText == "off") {
    o.sunThreshold = 0.0f;
  } else if (sunText != "auto") {
    char* end = nullptr;
    o.sunThreshold = std::strtof(sunText.c_str(), &end);
    if (end == sunText.c_str() || *end != '\0' || !(o.sunThreshold > 0.0f) ||
        !std::isfinite(o.sunThreshold)) {
      fail("--sun-threshold must be auto, off or a positive luminance, got '" + sunText + "'");
      return 1;
    }
  }
  if (o.threads < 0) {
    fail("--threads must be 0 (all cores) or positive, got " + std::to_string(o.threads));
    return 1;
  }
  // With several inputs each gets a folder of its own, named after it.
  std::vector<std::string> outDirs;
  for (const std::string& input : inputs) {
    const std::string dir =
        inputs.size() == 1 ? outDir : outDir + "/" + std::filesystem::path(input).stem().string();
    if (std::find(outDirs.begin(), outDirs.end(), dir) != outDirs.end()) {
      fail("two inputs would share the output folder '" + dir + "': rename one");
      return 1;
    }
    outDirs.push_back(dir);
  }
  if (Status s = checkOutputFolder(outDir); !s.ok()) {
    fail(s.message());
    return 1;
  }

  // The GPU path when asked for, or by default where it is faster (a hardware GPU). Without a
  // GPU device every context is software, where the CPU path is faster: then a context (slow
  // to create, about 12 MB) is made only for an explicit --gpu. One context for every input.
  std::unique_ptr<penumbra::GlContext> context;
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
  // One panorama after another: each prefilter already spreads over every core.
  int failed = 0;
  const int n = static_cast<int>(inputs.size());
  for (int i = 0; i < n; ++i) {
    std::string label = std::filesystem::path(inputs[i]).filename().string();
    if (n > 1) label += " (" + std::to_string(i + 1) + " of " + std::to_string(n) + ")";
    if (!prefilterOne(inputs[i], outDirs[i], label, o, context != nullptr)) ++failed;
  }
  if (failed > 0 && n > 1) {
    fail(std::to_string(failed) + " of " + std::to_string(n) + " panoramas failed");
  }
  return failed > 0 ? 1 : 0;
}
