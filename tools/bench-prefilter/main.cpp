// penumbra-bench-prefilter: how long the CPU prefilter takes for the reference case, a 1024x512
// panorama to 256-pixel faces with the full mip chain at default quality, and how much memory
// it needs. The panorama is procedural (sky gradient, a small very bright sun, a striped ground
// and fine checks) so the benchmark needs no input file. A plain timed main rather than Google
// Benchmark: the figure of interest is one end-to-end wall time plus peak RSS.
//
// --process times what an asset pipeline waits for instead: the whole penumbra-prefilter
// process (start-up, reading an EXR of the same panorama, the prefilter, writing the packed
// file, exit), with the child's peak RSS from wait4().
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "penumbra/ibl.h"
#include "penumbra/image.h"

extern char** environ;

namespace {

namespace ibl = penumbra::ibl;

penumbra::Image makePanorama(int width) {
  const int height = width / 2;
  penumbra::Image image(width, height, 3);
  const glm::vec3 sun = glm::normalize(glm::vec3(0.3f, 0.6f, -0.5f));
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const float u = (static_cast<float>(x) + 0.5f) / width;
      const float v = (static_cast<float>(y) + 0.5f) / height;
      const glm::vec3 d = ibl::panoramaDirection(u, v);
      glm::vec3 c;
      if (d.y > 0.0f) {
        c = glm::mix(glm::vec3(0.9f, 0.95f, 1.0f), glm::vec3(0.2f, 0.4f, 0.9f), d.y);
      } else {
        const bool stripe = (static_cast<int>(u * 64.0f) & 1) != 0;
        c = stripe ? glm::vec3(0.3f, 0.25f, 0.2f) : glm::vec3(0.1f, 0.1f, 0.08f);
      }
      if (((x / 4) ^ (y / 4)) & 1) c *= 0.8f;  // fine detail for the minified levels
      if (glm::dot(d, sun) > std::cos(0.02f)) c = glm::vec3(20000.0f, 18000.0f, 15000.0f);
      float* p = image.pixel(x, y);
      p[0] = c.x;
      p[1] = c.y;
      p[2] = c.z;
    }
  }
  return image;
}

double peakRssMiB() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0;  // ru_maxrss is in KiB on Linux
}

struct ProcessRun {
  double seconds = 0.0;
  double peakMiB = 0.0;
  int status = -1;
};

ProcessRun runProcess(const std::vector<std::string>& args) {
  std::vector<char*> argv;
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  ProcessRun run;
  const auto start = std::chrono::steady_clock::now();
  pid_t pid = 0;
  if (posix_spawn(&pid, argv[0], nullptr, nullptr, argv.data(), environ) != 0) return run;
  int status = 0;
  rusage usage{};
  if (wait4(pid, &status, 0, &usage) != pid) return run;
  run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  run.peakMiB = static_cast<double>(usage.ru_maxrss) / 1024.0;
  run.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return run;
}

// The whole-process benchmark: the panorama as an EXR in a scratch folder, then `repeat` runs
// of `prefilter pano.exr -o out --size N --samples N --quiet`.
int benchProcess(const std::string& prefilter, const penumbra::Image& panorama, int size,
                 int samples, int repeat) {
  namespace fs = std::filesystem;
  if (access(prefilter.c_str(), X_OK) != 0) {
    std::fprintf(stderr, "penumbra-bench-prefilter: error: %s is not an executable (--prefilter)\n",
                 prefilter.c_str());
    return 1;
  }
  const fs::path dir = fs::temp_directory_path() / ("penumbra-bench-" + std::to_string(getpid()));
  fs::create_directories(dir);
  const std::string input = (dir / "pano.exr").string();
  if (auto written = penumbra::writeImage(input, panorama); !written) {
    std::fprintf(stderr, "penumbra-bench-prefilter: error: %s\n", written.message().c_str());
    return 1;
  }
  double best = 1e30, total = 0.0, peak = 0.0;
  std::vector<double> times;
  for (int r = 0; r < repeat; ++r) {
    const ProcessRun run =
        runProcess({prefilter, input, "-o", (dir / "out").string(), "--size", std::to_string(size),
                    "--samples", std::to_string(samples), "--quiet"});
    if (run.status != 0) {
      std::fprintf(stderr, "penumbra-bench-prefilter: error: %s exited with status %d\n",
                   prefilter.c_str(), run.status);
      fs::remove_all(dir);
      return 1;
    }
    best = std::min(best, run.seconds);
    total += run.seconds;
    times.push_back(run.seconds);
    peak = std::max(peak, run.peakMiB);
  }
  fs::remove_all(dir);
  std::printf("whole process: %s %dx%d EXR -o DIR --size %d --samples %d\n", prefilter.c_str(),
              panorama.width, panorama.height, size, samples);
  // The median too: on a shared machine a few slow runs move the mean a lot.
  std::sort(times.begin(), times.end());
  const double median = times.size() % 2
                            ? times[times.size() / 2]
                            : 0.5 * (times[times.size() / 2 - 1] + times[times.size() / 2]);
  std::printf("  seconds: best %.3f, median %.3f, mean %.3f over %d runs (start-up to exit)\n",
              best, median, total / repeat, repeat);
  std::printf("  peak RSS: %.1f MiB (largest of the runs)\n", peak);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  int threads = 0;
  int repeat = 3;
  int samples = ibl::kDefaultSamples;
  int size = ibl::kDefaultFaceSize;
  int width = 1024;
  bool process = false;
  // Default: the CLI built next to this benchmark (build/tools/prefilter/).
  std::string prefilter =
      (std::filesystem::path(argv[0]).parent_path() / ".." / "prefilter" / "penumbra-prefilter")
          .lexically_normal()
          .string();
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const auto next = [&]() { return i + 1 < argc ? std::atoi(argv[++i]) : 0; };
    if (arg == "--threads") {
      threads = next();
    } else if (arg == "--repeat") {
      repeat = std::max(1, next());
    } else if (arg == "--samples") {
      samples = next();
    } else if (arg == "--size") {
      size = next();
    } else if (arg == "--width") {
      width = next();
    } else if (arg == "--process") {
      process = true;
    } else if (arg == "--prefilter" && i + 1 < argc) {
      prefilter = argv[++i];
      process = true;
    } else {
      std::printf(
          "usage: penumbra-bench-prefilter [--threads N] [--repeat N] [--samples N] [--size N] "
          "[--width N] [--process [--prefilter PATH]]\n");
      return arg == "--help" || arg == "-h" ? 0 : 2;
    }
  }
  const penumbra::Image panorama = makePanorama(width);
  if (process) return benchProcess(prefilter, panorama, size, samples, repeat);
  ibl::PrefilterOptions options;
  options.faceSize = size;
  options.samples = samples;
  options.threads = threads;

  double best = 1e30;
  double total = 0.0;
  int mips = 0;
  for (int r = 0; r < repeat; ++r) {
    const auto start = std::chrono::steady_clock::now();
    auto env = ibl::prefilterCpu(panorama, options);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (!env) {
      std::fprintf(stderr, "penumbra-bench-prefilter: error: %s\n", env.message().c_str());
      return 1;
    }
    mips = env->specular.mipCount();
    best = std::min(best, seconds);
    total += seconds;
  }
  const auto lutStart = std::chrono::steady_clock::now();
  const penumbra::Image lut =
      ibl::computeBrdfLut({.size = 128, .samples = 512, .threads = threads});
  const double lutSeconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - lutStart).count();

  std::printf("prefilter %dx%d -> %d px faces, %d mips, %d samples, %d threads\n", width, width / 2,
              size, mips, samples, ibl::resolveThreads(threads));
  std::printf("  seconds: best %.3f, mean %.3f over %d runs (panorama->cube, GGX mips, SH)\n", best,
              total / repeat, repeat);
  std::printf("  DFG LUT 128x128, 512 samples: %.3f s (%dx%d)\n", lutSeconds, lut.width,
              lut.height);
  std::printf("  peak RSS: %.1f MiB\n", peakRssMiB());
  return 0;
}
