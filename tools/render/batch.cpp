#include "batch.h"

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "output.h"
#include "penumbra/renderer.h"
#include "progress.h"

namespace fs = std::filesystem;

namespace penumbra::tools {
namespace {

using Clock = std::chrono::steady_clock;

int fail(const std::string& message) {
  std::fprintf(stderr, "penumbra-render: error: %s\n", message.c_str());
  return 1;
}

double secondsSince(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

struct JobLine {
  int number = 0;
  std::string text;
  std::string error;  // a sequence that cannot be expanded: the job fails with this
};

// The shard's lines of the job file (blank lines are not jobs).
Result<std::vector<JobLine>> readJobs(const std::string& path, const BatchShard& shard) {
  std::ifstream in(path);
  if (!in) return makeError("cannot read job file " + path);
  std::vector<JobLine> lines;
  std::string text;
  int number = 0, job = 0;
  while (std::getline(in, text)) {
    ++number;
    if (text.find_first_not_of(" \t\r") == std::string::npos) continue;
    // A sequence line is one job per time (expandSequence); its error reaches the results as
    // the line's own job.
    auto expanded = expandSequence(text, number);
    if (!expanded) {
      if (shard.contains(job++)) lines.push_back({number, text, expanded.message()});
      continue;
    }
    for (const std::string& one : *expanded) {
      if (shard.contains(job++)) lines.push_back({number, one, {}});
    }
  }
  if (in.bad()) return makeError("cannot read job file " + path);
  return lines;
}

std::string defaultResultsPath(const std::string& jobsPath, const BatchShard& shard) {
  const fs::path p(jobsPath);
  std::string name = p.stem().string() + ".results";
  if (shard.count > 1) {
    char part[48];  // (snprintf: GCC 12 warns falsely on "." + std::to_string)
    std::snprintf(part, sizeof part, ".%d-of-%d", shard.index, shard.count);
    name += part;
  }
  return (p.parent_path() / (name + ".jsonl")).string();
}

// The renderer and what it holds from the previous job.
struct Session {
  Renderer& renderer;
  EnvironmentCache environments;
  std::string uploadedEnvironment;  // key of the environment on the GPU, empty: unknown
};

Status render(const BatchJob& job, Session& s, BatchResult& result) {
  const auto start = Clock::now();
  JobRequest request = job.request;
  request.environments = &s.environments;
  auto loaded = RenderJob::load(request);
  if (!loaded) return loaded.error();
  result.warnings = loaded->warnings;
  Renderer& r = s.renderer;
  // The same environment as the last job's stays on the GPU.
  PN_TRY(loaded->applyTo(r, &s.uploadedEnvironment));
  result.loadSeconds = secondsSince(start);

  const auto frames = Clock::now();
  while (!r.converged()) {
    auto frame = r.step();
    if (!frame) return frame.error();
  }
  PN_TRY(writeOutput(job.output, r));
  result.renderSeconds = secondsSince(frames);
  const ConvergenceInfo c = r.convergence();
  result.frames = r.framesDone();
  result.width = loaded->settings.width;
  result.height = loaded->settings.height;
  result.automatic = c.automatic;
  result.converged = c.converged;
  result.errorEstimate = c.error;
  result.camera = loaded->camera;
  result.time = job.request.time;
  return {};
}

const char* statusWord(BatchResult::Status s) {
  return s == BatchResult::Status::Ok        ? "ok"
         : s == BatchResult::Status::Skipped ? "skipped"
                                             : "failed";
}

}  // namespace

int runBatch(const BatchOptions& o) {
  auto lines = readJobs(o.jobsPath, o.shard);
  if (!lines) return fail(lines.message());
  const std::string resultsPath =
      o.resultsPath.empty() ? defaultResultsPath(o.jobsPath, o.shard) : o.resultsPath;
  std::FILE* results = std::fopen(resultsPath.c_str(), "w");
  if (!results) return fail("cannot write results file " + resultsPath);

  auto context = GlContext::create({.backend = o.backend});
  if (!context) {
    std::fclose(results);
    return fail(context.message());
  }
  auto renderer =
      Renderer::create({.desktopGl = (*context)->isDesktopGl(), .forceHalfFloat = o.halfFloat});
  if (!renderer) {
    std::fclose(results);
    return fail(renderer.message());
  }
  if (o.info) {
    std::fprintf(stderr, "%s\n%s", (*context)->description().c_str(),
                 (*renderer)->capabilityReport().c_str());
  }
  Session session{**renderer, EnvironmentCache(), {}};
  const bool tty = !o.quiet && isatty(STDERR_FILENO);
  const int total = static_cast<int>(lines->size());
  ProgressBar bar("batch", total, tty, "job");
  int done = 0, failed = 0, skipped = 0;
  const auto start = Clock::now();
  for (const JobLine& line : *lines) {
    BatchResult result;
    result.line = line.number;
    auto job = line.error.empty() ? parseBatchJob(line.text, line.number, o.defaults)
                                  : Result<BatchJob>(makeError(line.error));
    if (job) {
      result.scene = job->request.scenePath;
      result.output = job->output;
      const fs::path outDir = fs::path(job->output).parent_path();
      if (!o.force && fs::exists(job->output)) {
        result.status = BatchResult::Status::Skipped;
      } else if (!outDir.empty() && !fs::is_directory(outDir)) {
        result.error = "output folder '" + outDir.string() + "' does not exist";
      } else if (auto st = render(*job, session, result); st) {
        result.status = BatchResult::Status::Ok;
      } else {
        result.error = st.message();
      }
    } else {
      result.error = job.message();
    }
    if (result.status == BatchResult::Status::Failed) ++failed;
    if (result.status == BatchResult::Status::Skipped) ++skipped;
    std::fprintf(results, "%s\n", batchResultJson(result).c_str());
    std::fflush(results);
    ++done;
    if (result.status == BatchResult::Status::Failed && !o.quiet) {
      std::fprintf(stderr, "%spenumbra-render: job at line %d failed: %s\n", tty ? "\r" : "",
                   line.number, result.error.c_str());
    } else if (!tty && !o.quiet) {
      std::fprintf(stderr, "penumbra-render: job %d of %d (line %d) %s: %s\n", done, total,
                   line.number, statusWord(result.status), result.output.c_str());
    }
    bar.update(done, total);
  }
  bar.finish();
  std::fclose(results);
  if (!o.quiet) {
    std::fprintf(stderr,
                 "penumbra-render: %d jobs in %.2f s: %d rendered, %d skipped (output exists), "
                 "%d failed -> %s\n",
                 total, secondsSince(start), total - failed - skipped, skipped, failed,
                 resultsPath.c_str());
  }
  return failed > 0 ? 1 : 0;
}

}  // namespace penumbra::tools
