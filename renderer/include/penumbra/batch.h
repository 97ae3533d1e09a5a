// Batch rendering (penumbra-render --batch JOBS.jsonl): a job file's lines as render requests,
// which shard of a job file a job belongs to (for a scheduler's array of tasks), and the lines
// of the results file. GL-free; the loop that renders the jobs with one context and one
// Renderer is in tools/render.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "penumbra/error.h"
#include "penumbra/render_job.h"

namespace penumbra {

// One job: the request and where its image goes.
struct BatchJob {
  int line = 0;  // 1-based line of the job file
  JobRequest request;
  std::string output;  // .png (displayed image), .exr or .hdr (linear radiance)
};

// A job line that asks for an animation sequence ("times": [t0, t1, ...], or "fps" and "count"
// with an optional "start" in seconds) as one job line per time: each with its "time" and its
// output numbered (OUT.png -> OUT_0000.png, ...; a "####" in the name is replaced instead). A
// line without them comes back as it is; an error names the line.
Result<std::vector<std::string>> expandSequence(std::string_view text, int line);

// True for the image outputs penumbra-render writes: .png, .exr or .hdr (any case).
bool isImageOutputPath(const std::string& path);

// "WxH" (or "WXH"), both positive.
Result<std::pair<int, int>> parseSize(std::string_view text);

// One line of a job file: a JSON object whose keys are penumbra-render's option names:
// "scene" and "output" (required), "size" ("WxH" or [w, h]), "env", "camera" and "variant"
// (name or index),
// "memory-budget" (MB), and any setting by its flag without the dashes ("frames", "tonemap",
// "no-probe-volume") or its key ("toneMapper"). Values are strings, numbers or booleans. The
// request starts as `defaults` (the command line's options) and the line's values override them.
// Errors start with "line N: ".
Result<BatchJob> parseBatchJob(std::string_view text, int line, const JobRequest& defaults);

// Which part of a job file one process renders: jobs k with k % count == index (round robin, so
// that long and short jobs spread evenly), k counting the job file's non-blank lines from 0.
struct BatchShard {
  int index = 0;
  int count = 1;
  bool contains(int job) const { return job % count == index; }
};
// "I/N" with 0 <= I < N, e.g. a Slurm array task's "$SLURM_ARRAY_TASK_ID/$SLURM_ARRAY_TASK_COUNT".
Result<BatchShard> parseShard(std::string_view text);

// One line of the results file, written when a job ends.
struct BatchResult {
  int line = 0;
  std::string scene, output;
  enum class Status { Ok, Failed, Skipped } status = Status::Failed;
  std::string error;  // Failed: the one-line message
  std::vector<std::string> warnings;
  double loadSeconds = 0.0;    // reading the scene and environment, setting up the renderer
  double renderSeconds = 0.0;  // frames and writing the image
  int frames = 0, width = 0, height = 0;
  bool automatic = false;      // frames "auto": stopped by the convergence estimate
  bool converged = false;      // automatic: the estimate met its criterion before maxFrames
  double errorEstimate = 0.0;  // automatic: estimated RMS error in 8-bit steps
  std::optional<float> time;   // the animation time it was posed at, when it asked for one
  // The camera the job rendered with (a file's, or the automatic framing), so another renderer
  // (Blender, tools/fidelity) can see the same view.
  Camera camera;
};
// A JSON object on one line (no newline at the end).
std::string batchResultJson(const BatchResult& result);

}  // namespace penumbra
