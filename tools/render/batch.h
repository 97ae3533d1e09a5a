// penumbra-render --batch: renders the jobs of a job file (penumbra/batch.h) in one process,
// with one GL context and one Renderer, so that programs compile once and each panorama is
// prefiltered once; a results line is written per job as it ends, a failing job is recorded and
// the batch goes on, and a job whose output exists is skipped (unless forced).
#pragma once

#include <string>

#include "penumbra/batch.h"
#include "penumbra/gl_context.h"
#include "penumbra/render_job.h"

namespace penumbra::tools {

struct BatchOptions {
  std::string jobsPath;
  std::string resultsPath;  // empty: beside the job file, JOBS.results[.I-of-N].jsonl
  BatchShard shard;
  GlBackend backend = GlBackend::Auto;
  JobRequest defaults;  // the command line's options, under each line's
  bool force = false;   // render jobs whose output exists
  bool quiet = false;
  bool info = false;
  bool halfFloat = false;
};

// The process's exit status: 0 when every job of the shard rendered or was skipped, 1 when
// one failed (the others still ran) or the batch could not start.
int runBatch(const BatchOptions& options);

}  // namespace penumbra::tools
