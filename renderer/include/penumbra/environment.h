// Environment loading for the renderer: a packed file from penumbra-prefilter (one request,
// already filtered), or an HDR panorama that is prefiltered on load (slower; smaller faces),
// or a constant environment for tests and scenes without one.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "penumbra/environment_format.h"
#include "penumbra/error.h"
#include "penumbra/image.h"

namespace penumbra {

struct EnvironmentLoadOptions {
  int faceSize = 128;  // for panoramas prefiltered on load
  int samples = 64;
  float sunThreshold = -1.0f;  // RenderSettings::sunThreshold: -1 automatic, 0 off
  // Receives a warning when radiance had to be replaced (ibl::radianceVerdict); null: dropped.
  std::vector<std::string>* warnings = nullptr;
  // A panorama with more pixels is refused with a message naming its size and this limit.
  int64_t maxPanoramaPixels = int64_t{1} << 28;
};

// A Radiance panorama wider than this many times the face size is box-filtered down while it
// decodes (ReadOptions::maxWidth): 16 panorama pixels per face edge is 4 per cube texel around
// the equator, and an 8192x4096 file then costs its decoding, not 1.4 GB and 12 s.
inline constexpr int kPanoramaWidthPerFace = 16;

// True when the file starts like a packed environment (a Radiance header with PENUMBRA_ENV).
bool isPackedEnvironmentFile(const std::string& path);
Result<PackedEnvironment> loadEnvironment(const std::string& path,
                                          const EnvironmentLoadOptions& options = {});
// A Radiance (.hdr) panorama loaded in steps, for a caller that must not block (the browser
// viewer yields to the page between steps): start() reads the file and its header (refusing
// what loadEnvironment refuses), step() decodes some scanlines (box-filtered as loadEnvironment
// does), finish() prefilters. The result equals loadEnvironment's for the same file.
class PanoramaLoader {
 public:
  static Result<PanoramaLoader> start(const std::string& path,
                                      const EnvironmentLoadOptions& options);
  // The file's bytes, already in memory (`name` in messages).
  static Result<PanoramaLoader> start(std::vector<uint8_t> bytes, const std::string& name,
                                      const EnvironmentLoadOptions& options);
  PanoramaLoader(PanoramaLoader&&) noexcept;
  PanoramaLoader& operator=(PanoramaLoader&&) noexcept;
  ~PanoramaLoader();
  int width() const;  // the file's
  int height() const;
  bool done() const;
  Status step(int rows);
  Result<PackedEnvironment> finish();

 private:
  PanoramaLoader();
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// A uniform environment of the given radiance (white furnace, or a neutral default).
PackedEnvironment uniformEnvironment(const glm::vec3& radiance, int faceSize = 8);
// The neutral studio environment (assets/env/studio.hdr, compiled into the library: grey, two
// softboxes and an overhead light, no sun): what lights a scene that has no lights of its own
// and names no environment. Prefiltered on each call (small faces: tens of milliseconds).
Result<PackedEnvironment> studioEnvironment(const EnvironmentLoadOptions& options = {
                                                .faceSize = 64, .samples = 64});

}  // namespace penumbra
