#include "progressive/distributor.h"

#include <algorithm>
#include <cmath>

namespace penumbra::progressive {

int directStartFrame(int frames, float directDelay, bool darkEnvironment) {
  if (frames <= 1) return 1;
  if (darkEnvironment) return 2;
  int start = static_cast<int>(std::floor(static_cast<double>(frames) * directDelay));
  return std::clamp(start, 2, frames);
}

int automaticLightSamples(int frames, float directDelay, int lightCount) {
  if (frames <= 1) return 1;
  const int directFrames = frames - directStartFrame(frames, directDelay) + 1;
  // About two shadow-map passes per direct frame in all, at most 64 per light (the paper's
  // Figure 9: banding is gone at 64).
  return std::clamp(2 * directFrames / std::max(lightCount, 1), 1, 64);
}

std::vector<FramePlan> distributeSamples(const ProgressiveSettings& s,
                                         const std::vector<LightInfo>& lights,
                                         bool darkEnvironment) {
  const int m = std::max(1, s.frames);
  std::vector<FramePlan> plan(static_cast<size_t>(m));
  for (int k = 0; k < m; ++k) {
    FramePlan& f = plan[static_cast<size_t>(k)];
    f.frame = k + 1;
    f.totalFrames = m;
    f.jitter = jitter(f.frame, s.seed);
    f.occlusion = f.frame >= 2;
    f.renderPrepass = f.frame == 2;
    glm::vec2 seq = r2(static_cast<uint32_t>(k)) + seedOffset(s.seed, 3);
    f.sequence = seq - glm::floor(seq);
    // Halton (5, 7): independent of the jitter's (2, 3) and of the occlusion's R2 points.
    const glm::vec2 sky = glm::vec2(radicalInverse(static_cast<uint32_t>(k), 5),
                                    radicalInverse(static_cast<uint32_t>(k), 7)) +
                          seedOffset(s.seed, 5);
    f.skyPoint = sky - glm::floor(sky);
  }
  if (lights.empty()) return plan;

  // Per light: n_i centre-outward points with weight m / n_i.
  struct Pending {
    float rank;  // normalised position in the light's own order, for merging
    int light;
    LightSample sample;
  };
  std::vector<Pending> all;
  const int perLight =
      s.lightSamples > 0 ? s.lightSamples
                         : automaticLightSamples(m, s.directDelay, static_cast<int>(lights.size()));
  for (size_t i = 0; i < lights.size(); ++i) {
    const int n = m == 1 ? 1 : perLight;
    auto pts = lightSamplePoints(n, lights[i].shape, lights[i].aspect,
                                 s.seed + 7919u * static_cast<uint32_t>(i));
    for (int j = 0; j < n; ++j) {
      LightSample ls;
      ls.light = static_cast<int>(i);
      ls.point = pts[static_cast<size_t>(j)];
      ls.weight = static_cast<float>(m) / static_cast<float>(n);
      ls.shadowed = lights[i].shape != LightShape::Point;
      all.push_back({(j + 0.5f) / n, static_cast<int>(i), ls});
    }
  }
  std::stable_sort(all.begin(), all.end(), [](const Pending& a, const Pending& b) {
    return a.rank < b.rank || (a.rank == b.rank && a.light < b.light);
  });

  // Algorithm 1 over frames [start, m]; the environment's own lights over [1, m].
  const int start = directStartFrame(m, s.directDelay, darkEnvironment);
  for (const bool early : {false, true}) {
    std::vector<const Pending*> group;
    for (const Pending& p : all) {
      if (lights[static_cast<size_t>(p.light)].fromFrameOne == early) group.push_back(&p);
    }
    if (group.empty()) continue;
    const int first = early ? 1 : start;
    const double framesPerSample = (m - first + 1) / static_cast<double>(group.size());
    double index = first;
    for (const Pending* p : group) {
      const int frame = std::min(static_cast<int>(std::floor(index + 1e-9)), m);
      plan[static_cast<size_t>(frame - 1)].lights.push_back(p->sample);
      index += framesPerSample;
    }
  }
  return plan;
}

}  // namespace penumbra::progressive
