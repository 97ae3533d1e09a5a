#include "penumbra/environment.h"

#include <fstream>

#include "penumbra/ibl.h"
#include "penumbra/image.h"
#include "penumbra/version.h"

namespace penumbra {

bool isPackedEnvironmentFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return false;
  std::string head(8192, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<size_t>(in.gcount()));
  const size_t end = head.find("\n\n");
  return head.rfind("#?", 0) == 0 && head.find(std::string("\n") + kPackedHeaderKey + "=") < end;
}

Result<PackedEnvironment> loadEnvironment(const std::string& path,
                                          const EnvironmentLoadOptions& options) {
  if (isPackedEnvironmentFile(path)) return readPackedEnvironment(path);
  auto image = readImage(path);
  if (!image) return image.error();
  const int64_t bad = ibl::sanitizeRadiance(*image);
  (void)bad;  // counted by the prefilter CLI; here silently clamped like any renderer would
  ibl::PrefilterOptions po;
  po.faceSize = options.faceSize;
  po.samples = options.samples;
  auto env = ibl::prefilterCpu(*image, po);
  if (!env) return makeError(path + ": " + env.message());
  return env;
}

PackedEnvironment uniformEnvironment(const glm::vec3& radiance, int faceSize) {
  PackedEnvironment env;
  const int mips = ibl::mipCountFor(faceSize, 1);
  env.specular = ibl::Cubemap(faceSize, mips);
  for (int m = 0; m < mips; ++m) {
    for (int f = 0; f < ibl::kFaceCount; ++f) {
      Image& img = env.specular.face(m, f);
      for (size_t i = 0; i < img.pixels.size(); i += 3) {
        img.pixels[i] = radiance.r;
        img.pixels[i + 1] = radiance.g;
        img.pixels[i + 2] = radiance.b;
      }
    }
    env.roughness.push_back(ibl::roughnessForMip(m, mips));
  }
  env.sh = ibl::projectSh(env.specular, 0, 1);
  env.generator = std::string("penumbra ") + version() + " uniform";
  return env;
}

}  // namespace penumbra
