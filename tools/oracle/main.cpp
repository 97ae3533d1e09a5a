// penumbra-oracle: when does a view look done, and when does the automatic view stop? For each
// scene it renders the automatic plan to --frames (1024) without stopping and finds the oracle
// frame: the first frame from which the displayed 8-bit image stays within 1/255 RMS of the
// last one, with 99 % of its 8x8 tiles within 3/255. Then it renders the automatic view as a
// user gets it and prints its stop beside the oracle, the time to each, how honest its
// estimated time left was after frame 8, and the grain of its frames against frame 1's.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "../common/setting_flags.h"

#include "oracle_metrics.h"
#include "penumbra/gl_context.h"
#include "penumbra/image.h"
#include "penumbra/render_job.h"
#include "penumbra/renderer.h"

using namespace penumbra;
using Clock = std::chrono::steady_clock;

namespace {

constexpr int kReferenceCap = 4096;  // the reference run's maxFrames (never reached)

struct Options {
  int width = 640, height = 360, frames = 1024;
  std::string environment;
  bool trace = false;
  std::string images;  // a folder for each scene's reference and stop images
  // A TSV file: each checkpoint of the reference run (no stop, no tile skipped), the rule's
  // estimate beside the truth, for trying stopping rules offline; with referenceOnly the
  // automatic view is not rendered.
  std::string checkpoints;
  bool referenceOnly = false;
  std::vector<std::pair<std::string, std::string>> settings;
};

Result<std::unique_ptr<Renderer>> open(const std::string& scene, const Options& o,
                                       std::vector<std::pair<std::string, std::string>> extra) {
  JobRequest request;
  request.scenePath = scene;
  request.settings = {{"width", std::to_string(o.width)},
                      {"height", std::to_string(o.height)},
                      {"frames", "auto"},
                      {"maxFrames", std::to_string(o.frames)}};
  for (const auto& kv : o.settings) request.settings.push_back(kv);
  for (auto& kv : extra) request.settings.push_back(std::move(kv));
  if (!o.environment.empty()) {
    auto env = parseEnvironmentSpec(o.environment);
    if (!env) return env.error();
    request.environment = *env;
  }
  auto job = RenderJob::load(request);
  if (!job) return job.error();
  auto r = Renderer::create();
  if (!r) return r.error();
  PN_TRY(job->applyTo(**r));
  return std::move(*r);
}

Result<oracle::Frame8> display(Renderer& r) {
  auto img = r.readDisplay();
  if (!img) return img.error();
  oracle::Frame8 f{img->width, img->height, {}};
  f.rgb.reserve(static_cast<size_t>(img->width) * img->height * 3);
  for (size_t i = 0; i < img->pixels.size(); i += 4) {
    for (size_t c = 0; c < 3; ++c) {
      f.rgb.push_back(
          static_cast<uint8_t>(std::lround(std::clamp(img->pixels[i + c], 0.0f, 1.0f) * 255.0f)));
    }
  }
  return f;
}

// One step, timed to the GPU's end.
Result<double> timedStep(Renderer& r) {
  const auto t0 = Clock::now();
  PN_TRY(r.step());
  r.finish();
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

struct Row {
  int oracle = 0, stop = 0;
  double oracleS = 0, stopS = 0;
  oracle::Difference atStop;
  double etaWorst = 0;    // largest factor between estimated and real time left, frame > 8
  double etaMedian = 0;   // and its median over those frames
  double grainFirst = 0;  // frame 1's excess grain over the converged image
  double grainWorst = 0;  // the largest of frames 2..stop
  int grainWorstFrame = 0;
};

Status save(const oracle::Frame8& f, const std::string& path) {
  Image img(f.width, f.height, 3);
  for (size_t i = 0; i < f.rgb.size(); ++i) img.pixels[i] = f.rgb[i] / 255.0f;
  return writeImage(path, img);
}

// One line a checkpoint: scene, its oracle frame, the reference run's cap, the checkpoint, the
// rule's estimate (RMS, tiles' p99: as displayed, margin and rounding included), the measured
// decay, and the truth (the displayed image against the reference's last frame).
Status writeCheckpoints(const Options& o, const std::string& scene, int oracleFrame,
                        const std::vector<ConvergenceInfo>& measured,
                        const std::vector<oracle::Difference>& diffs) {
  std::FILE* f = std::fopen(o.checkpoints.c_str(), "a");
  if (!f) return makeError("cannot write " + o.checkpoints);
  const std::string name = scene.substr(scene.find_last_of('/') + 1);
  for (const ConvergenceInfo& c : measured) {
    const auto& d = diffs[static_cast<size_t>(c.frame - 1)];
    std::fprintf(f, "%s\t%d\t%d\t%d\t%.4f\t%.4f\t%.4f\t%.4f\t%.4f\n", name.c_str(),
                 oracleFrame, kReferenceCap, c.frame, c.error, c.tileError, c.decay, d.rms,
                 d.tileP99);
  }
  return std::fclose(f) == 0 ? Status{} : makeError("cannot write " + o.checkpoints);
}

Result<Row> measure(const std::string& scene, const Options& o) {
  Row row;
  // The automatic plan run to the cap: never measured converged (the smallest threshold; a view
  // that meets even that has stopped changing), no tile skipped.
  std::vector<oracle::Frame8> frames;
  std::vector<double> elapsed;
  std::vector<ConvergenceInfo> measured;  // the reference run's checkpoints
  {
    // (A larger cap: the same plan up to --frames, and no "little left to change before the
    // cap" that would end it sooner.)
    auto r = open(scene, o,
                  {{"convergenceThreshold", "0.125"},
                   {"skipConvergedTiles", "false"},
                   {"maxFrames", std::to_string(std::max(kReferenceCap, o.frames))}});
    if (!r) return r.error();
    double t = 0;
    while (!(*r)->converged() && (*r)->framesDone() < o.frames) {
      auto s = timedStep(**r);
      if (!s) return s.error();
      t += *s;
      elapsed.push_back(t);
      const ConvergenceInfo c = (*r)->convergence();
      if (c.measured && c.frame == (*r)->framesDone()) measured.push_back(c);
      auto f = display(**r);
      if (!f) return f.error();
      frames.push_back(std::move(*f));
    }
  }
  const oracle::Frame8 last = frames.back();
  const std::string stem = o.images + "/" + scene.substr(scene.find_last_of('/') + 1) + "_";
  if (!o.images.empty()) PN_TRY(save(last, stem + "reference.png"));
  std::vector<oracle::Difference> diffs;
  for (const auto& f : frames) diffs.push_back(oracle::difference(f, last));
  row.oracle = oracle::oracleFrame(diffs);
  if (o.trace && row.oracle > 1) {
    const auto& d = diffs[static_cast<size_t>(row.oracle - 2)];
    std::printf("#   the reference's frame %d, the last not acceptable: %.2f / %.2f\n",
                row.oracle - 1, d.rms, d.tileP99);
  }
  row.oracleS = row.oracle > 0 ? elapsed[static_cast<size_t>(row.oracle - 1)] : 0.0;
  if (!o.checkpoints.empty()) PN_TRY(writeCheckpoints(o, scene, row.oracle, measured, diffs));
  if (o.referenceOnly) return row;
  frames.resize(1);  // frame 1, for the grain
  // The automatic view as a user gets it.
  auto r = open(scene, o, {});
  if (!r) return r.error();
  std::vector<double> t;
  std::vector<int> expected;
  double total = 0;
  while (!(*r)->converged()) {
    auto s = timedStep(**r);
    if (!s) return s.error();
    total += *s;
    t.push_back(total);
    expected.push_back((*r)->convergence().expectedFrames);
    auto f = display(**r);
    if (!f) return f.error();
    const double grain = oracle::excessGrain(*f, last);
    if (t.size() == 1) row.grainFirst = grain;
    if (t.size() > 1 && grain > row.grainWorst) {
      row.grainWorst = grain;
      row.grainWorstFrame = static_cast<int>(t.size());
    }
    if ((*r)->converged()) {
      row.atStop = oracle::difference(*f, last);
      if (!o.images.empty()) PN_TRY(save(*f, stem + "stop.png"));
    }
    const ConvergenceInfo c = (*r)->convergence();
    if (o.trace && c.measured && c.frame == static_cast<int>(t.size())) {
      // The estimate against the truth: this frame against the reference's last.
      const auto truth = oracle::difference(*f, last);
      std::printf(
          "#   frame %d: estimate %.2f / tiles %.2f (decay %.2f, expected %d), against "
          "the reference %.2f / %.2f\n",
          c.frame, c.error, c.tileError, c.decay, c.expectedFrames, truth.rms, truth.tileP99);
    }
  }
  row.stop = (*r)->framesDone();
  row.stopS = total;
  // As the viewer says it (web/lib/progress.mjs): the frames left at the mean time of the last
  // eight frames.
  std::vector<double> factors;
  for (int k = 9; k < row.stop; ++k) {
    const double done = t[static_cast<size_t>(k - 1)];
    const double recent = (done - t[static_cast<size_t>(k - 9)]) / 8.0;
    const double predicted = (expected[static_cast<size_t>(k - 1)] - k) * recent;
    const double real = total - done;
    if (predicted <= 0 || real <= 0) continue;
    factors.push_back(std::max(predicted / real, real / predicted));
  }
  if (!factors.empty()) {
    std::sort(factors.begin(), factors.end());
    row.etaWorst = factors.back();
    row.etaMedian = factors[factors.size() / 2];
  }
  return row;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "penumbra-oracle: the frame a view looks done against where the automatic view stops"};
  std::vector<std::string> scenes = {"assets/cornell_box/cornell_box.json"};
  std::string size = "640x360";
  Options o;
  app.add_option("--scene", scenes, "scene files or glTF models (repeatable)");
  app.add_option("--size", size, "resolution WxH");
  app.add_option("--frames", o.frames, "the reference frame and the automatic view's cap")
      ->check(CLI::Range(16, 4096));
  app.add_option("--environment", o.environment,
                 "environment for every scene: none, studio, r,g,b or an HDR or packed file");
  app.add_option("--images", o.images, "write each scene's reference and stop images here");
  app.add_flag("--trace", o.trace, "print each checkpoint's estimate beside the true error");
  app.add_option("--checkpoints", o.checkpoints,
                 "append the reference run's checkpoints to this TSV file: scene, oracle frame, "
                 "cap, frame, estimate RMS and tile p99, decay, true RMS and tile p99");
  app.add_flag("--reference-only", o.referenceOnly,
               "render only the reference run (the oracle frame; no automatic view)");
  std::vector<std::string> extra;
  app.add_option("--set", extra, "KEY=VALUE: a setting for every run, as in the scene file");
  CLI11_PARSE(app, argc, argv);
  if (std::sscanf(size.c_str(), "%dx%d", &o.width, &o.height) != 2 || o.width < 8 || o.height < 8) {
    std::fprintf(stderr, "penumbra-oracle: error: bad size '%s'\n", size.c_str());
    return 1;
  }
  if (std::string bad; !tools::parseSetOptions(extra, o.settings, bad)) {
    std::fprintf(stderr, "penumbra-oracle: error: --set expects KEY=VALUE, got '%s'\n",
                 bad.c_str());
    return 1;
  }
  auto ctx = GlContext::create();
  if (!ctx) {
    std::fprintf(stderr, "penumbra-oracle: error: %s\n", ctx.message().c_str());
    return 1;
  }
  std::printf("# %s, %dx%d, reference frame %d\n", (*ctx)->description().c_str(), o.width, o.height,
              o.frames);
  std::printf(
      "| scene | oracle frame | stop | stop / oracle | time to oracle (s) | time to stop (s) | "
      "stop vs reference: RMS / tile p99 (steps) | estimated time left after frame 8: median / "
      "worst factor | grain: frame 1 / worst later (frame) |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|\n");
  int failures = 0;
  for (const auto& scene : scenes) {
    auto row = measure(scene, o);
    const std::string name = scene.substr(scene.find_last_of('/') + 1);
    if (!row) {
      std::fprintf(stderr, "penumbra-oracle: error: %s: %s\n", name.c_str(), row.message().c_str());
      ++failures;
      continue;
    }
    std::printf(
        "| %s | %d | %d | %.2f | %.2f | %.2f | %.2f / %.2f | %.2f / %.2f | %.2f / %.2f (%d) |\n",
        name.c_str(), row->oracle, row->stop,
        row->oracle > 0 ? static_cast<double>(row->stop) / row->oracle : 0.0, row->oracleS,
        row->stopS, row->atStop.rms, row->atStop.tileP99, row->etaMedian, row->etaWorst,
        row->grainFirst, row->grainWorst, row->grainWorstFrame);
    std::fflush(stdout);
  }
  return failures ? 1 : 0;
}
