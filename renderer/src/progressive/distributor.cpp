#include "progressive/distributor.h"

#include <algorithm>
#include <cmath>

namespace penumbra::progressive {

int directStartFrame(int frames, float directDelay, bool firstLight) {
  if (frames <= 1) return 1;
  if (firstLight) return 2;
  int start = static_cast<int>(std::floor(static_cast<double>(frames) * directDelay));
  return std::clamp(start, 2, frames);
}

std::vector<int> autoCheckpoints(int cap) {
  std::vector<int> out;
  int c = 2;
  while (c < cap) {
    out.push_back(c);
    c = c < 8 ? c + 2 : std::max(c + 1, static_cast<int>(std::lround(c * kCheckpointRatio)));
  }
  out.push_back(std::max(cap, 1));
  return out;
}

namespace {

// About two shadow-map passes per direct frame in all, at most 64 per light (the paper's
// Figure 9: banding is gone at 64).
int samplesFor(int directFrames, int lightCount) {
  return std::clamp(2 * directFrames / std::max(lightCount, 1), 1, 64);
}

// An automatic view's blocks: samples at a steady rate (two shadow-map passes a frame in all,
// at most one every two frames a light, the rate of a 128-frame view's 64), counted from the
// light's first frame to the block's end, so that at every checkpoint the light's samples so far
// are in proportion to its frames whatever the blocks' lengths; at least one a block, so every
// checkpoint has each light complete.
int blockSamples(int framesSoFar, uint32_t usedSoFar, int lightCount) {
  const double rate = std::min(2.0 / std::max(lightCount, 1), 0.5);
  const long due = std::lround(framesSoFar * rate) - static_cast<long>(usedSoFar);
  return static_cast<int>(std::max(1L, due));
}

struct Block {
  int begin, end;   // frames, inclusive
  int directStart;  // first frame of its non-environment light samples
};

std::vector<Block> planBlocks(const ProgressiveSettings& s, bool firstLight) {
  const int m = std::max(1, planFrames(s));
  if (s.frames > 0 || m <= 2) return {{1, m, directStartFrame(m, s.directDelay, firstLight)}};
  std::vector<Block> blocks;
  int begin = 1;
  for (const int end : autoCheckpoints(m)) {
    // Direct light from frame 2 on: frame 1 is the environment's (and first light's) alone.
    blocks.push_back({begin, end, std::max(begin, 2)});
    begin = end + 1;
  }
  return blocks;
}

// One block's light samples: per light n centre-outward points whose weights add up to the
// block's frames (less frame 1's first light in the first block), spread by Algorithm 1.
void distributeBlock(std::vector<FramePlan>& plan, const ProgressiveSettings& s,
                     const std::vector<LightInfo>& lights, const Block& block,
                     std::vector<uint32_t>& used, bool firstLight) {
  struct Pending {
    float rank;  // normalised position in the light's own order, for merging
    int light;
    LightSample sample;
  };
  const int len = block.end - block.begin + 1;
  const bool single = planFrames(s) == 1;
  std::vector<Pending> all;
  for (size_t i = 0; i < lights.size(); ++i) {
    const bool early = lights[i].fromFrameOne;
    const int directFrames = block.end - (early ? block.begin : block.directStart) + 1;
    const int lightCount = static_cast<int>(lights.size());
    const int n = single               ? 1
                  : s.lightSamples > 0 ? s.lightSamples
                  : s.frames > 0       ? samplesFor(directFrames, lightCount)
                                 : blockSamples(block.end - (early ? 0 : 1), used[i], lightCount);
    // Frame 1's first light took one frame of the first block's weight.
    const int share = len - (firstLight && !early && block.begin == 1 && !single ? 1 : 0);
    if (share <= 0) continue;
    const uint32_t lightSeed = s.seed + 7919u * static_cast<uint32_t>(i);
    // A fixed m: one stratified set. An automatic view: the next n points of the light's own
    // open-ended sequence, so the samples of every block so far are one stratified prefix.
    std::vector<glm::vec2> pts;
    if (s.frames > 0 || single) {
      pts = lightSamplePoints(n, lights[i].shape, lights[i].aspect, lightSeed);
    } else {
      for (int j = 0; j < n; ++j) {
        pts.push_back(lightSequencePoint(used[i]++, lights[i].shape, lightSeed));
      }
      sortFromCentre(pts, lights[i].shape, lights[i].aspect);
    }
    for (int j = 0; j < n; ++j) {
      LightSample ls;
      ls.light = static_cast<int>(i);
      ls.point = pts[static_cast<size_t>(j)];
      ls.weight = static_cast<float>(share) / static_cast<float>(n);
      ls.shadowed = lights[i].shape != LightShape::Point;
      all.push_back({(j + 0.5f) / n, static_cast<int>(i), ls});
    }
  }
  std::stable_sort(all.begin(), all.end(), [](const Pending& a, const Pending& b) {
    return a.rank < b.rank || (a.rank == b.rank && a.light < b.light);
  });
  // Algorithm 1 over [directStart, end]; the environment's own lights over the whole block.
  for (const bool early : {false, true}) {
    std::vector<const Pending*> group;
    for (const Pending& p : all) {
      if (lights[static_cast<size_t>(p.light)].fromFrameOne == early) group.push_back(&p);
    }
    if (group.empty()) continue;
    const int first = early ? block.begin : block.directStart;
    const double framesPerSample = (block.end - first + 1) / static_cast<double>(group.size());
    double index = first;
    for (const Pending* p : group) {
      const int frame = std::min(static_cast<int>(std::floor(index + 1e-9)), block.end);
      plan[static_cast<size_t>(frame - 1)].lights.push_back(p->sample);
      index += framesPerSample;
    }
  }
}

}  // namespace

float rayFilterWeight(int frame, int fadeFrames) {
  if (frame < 2 || fadeFrames < 2) return 0.0f;
  const float t = static_cast<float>(frame - 2) / static_cast<float>(fadeFrames - 1);
  return std::clamp(1.0f - t, 0.0f, 1.0f);
}

std::vector<FramePlan> distributeSamples(const ProgressiveSettings& s,
                                         const std::vector<LightInfo>& lights, bool firstLight) {
  const int m = std::max(1, planFrames(s));
  std::vector<FramePlan> plan(static_cast<size_t>(m));
  for (int k = 0; k < m; ++k) {
    FramePlan& f = plan[static_cast<size_t>(k)];
    f.frame = k + 1;
    f.totalFrames = m;
    f.jitter = jitter(f.frame, s.seed);
    f.occlusion = f.frame >= 2;
    f.rayFilter = rayFilterWeight(f.frame, s.rayFilterFrames);
    f.renderPrepass = f.frame == 2;
    glm::vec2 seq = r2(static_cast<uint32_t>(k)) + seedOffset(s.seed, 3);
    f.sequence = seq - glm::floor(seq);
    // Halton (5, 7): independent of the jitter's (2, 3) and of the occlusion's R2 points.
    const glm::vec2 sky = glm::vec2(radicalInverse(static_cast<uint32_t>(k), 5),
                                    radicalInverse(static_cast<uint32_t>(k), 7)) +
                          seedOffset(s.seed, 5);
    f.skyPoint = sky - glm::floor(sky);
  }
  const std::vector<Block> blocks = planBlocks(s, firstLight);
  for (const Block& b : blocks) plan[static_cast<size_t>(b.end - 1)].checkpoint = true;
  if (lights.empty()) return plan;
  // First light: every light of the scene from its centre, with weight 1, in frame 1.
  if (firstLight && m > 1) {
    for (size_t i = 0; i < lights.size(); ++i) {
      if (lights[i].fromFrameOne) continue;
      plan[0].lights.push_back({.light = static_cast<int>(i),
                                .point = glm::vec2(0.5f),
                                .weight = 1.0f,
                                .shadowed = lights[i].shape != LightShape::Point});
    }
  }
  std::vector<uint32_t> used(lights.size(), 0);  // each light's sequence points taken
  for (const Block& b : blocks) distributeBlock(plan, s, lights, b, used, firstLight);
  return plan;
}

}  // namespace penumbra::progressive
