#include "penumbra/environment.h"

#include <fstream>
#include <span>

#include "image/image_internal.h"
#include "image/rgbe.h"
#include "penumbra/ibl.h"
#include "penumbra/image.h"
#include "penumbra/version.h"

namespace penumbra {
namespace embedded {
std::span<const unsigned char> studioHdr();  // cmake/EmbedBinaryScript.cmake
}  // namespace embedded

bool isPackedEnvironmentFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return false;
  std::string head(8192, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<size_t>(in.gcount()));
  const size_t end = head.find("\n\n");
  return head.rfind("#?", 0) == 0 && head.find(std::string("\n") + kPackedHeaderKey + "=") < end;
}

namespace {

Result<PackedEnvironment> prefilterPanorama(Image& image, const EnvironmentLoadOptions& options,
                                            const std::string& name) {
  auto verdict = ibl::radianceVerdict(ibl::sanitizeRadiance(image), name);
  if (!verdict) return verdict.error();
  if (!verdict->empty() && options.warnings) options.warnings->push_back(*verdict);
  ibl::PrefilterOptions po;
  po.faceSize = options.faceSize;
  po.samples = options.samples;
  po.sunThreshold = options.sunThreshold;
  auto env = ibl::prefilterCpu(image, po);
  if (!env) return makeError(name + ": " + env.message());
  return env;
}

}  // namespace

Result<PackedEnvironment> loadEnvironment(const std::string& path,
                                          const EnvironmentLoadOptions& options) {
  if (isPackedEnvironmentFile(path)) {
    auto env = readPackedEnvironment(path);
    if (!env) return env;
    // RGBE holds no NaN, but a crafted file can hold absurd exponents: the same policy.
    ibl::RadianceReport total;
    for (int m = 0; m < env->specular.mipCount(); ++m) {
      for (int f = 0; f < ibl::kFaceCount; ++f) {
        const ibl::RadianceReport r = ibl::sanitizeRadiance(env->specular.face(m, f));
        total.pixels += r.pixels;
        total.nan += r.nan;
        total.infinite += r.infinite;
        total.negative += r.negative;
        total.tooBright += r.tooBright;
        total.replaced += r.replaced;
      }
    }
    auto verdict = ibl::radianceVerdict(total, path);
    if (!verdict) return verdict.error();
    if (!verdict->empty() && options.warnings) options.warnings->push_back(*verdict);
    return env;
  }
  ReadOptions read;
  read.maxPixels = options.maxPanoramaPixels;
  read.maxWidth = kPanoramaWidthPerFace * options.faceSize;
  auto image = readImage(path, read);
  if (!image) return image.error();
  return prefilterPanorama(*image, options, path);
}

Result<PackedEnvironment> studioEnvironment(const EnvironmentLoadOptions& options) {
  auto file = rgbe::decodeFile(embedded::studioHdr(), "studio environment");
  if (!file) return file.error();
  auto env = prefilterPanorama(file->image, options, "studio environment");
  if (env) env->generator = std::string("penumbra ") + version() + " studio";
  return env;
}

struct PanoramaLoader::Impl {
  rgbe::Decoder decoder;
  EnvironmentLoadOptions options;
  std::string path;
};

PanoramaLoader::PanoramaLoader() = default;
PanoramaLoader::PanoramaLoader(PanoramaLoader&&) noexcept = default;
PanoramaLoader& PanoramaLoader::operator=(PanoramaLoader&&) noexcept = default;
PanoramaLoader::~PanoramaLoader() = default;

Result<PanoramaLoader> PanoramaLoader::start(const std::string& path,
                                             const EnvironmentLoadOptions& options) {
  auto bytes = detail::readFileBytes(path);
  if (!bytes) return bytes.error();
  return start(std::move(*bytes), path, options);
}

Result<PanoramaLoader> PanoramaLoader::start(std::vector<uint8_t> bytes, const std::string& name,
                                             const EnvironmentLoadOptions& options) {
  auto decoder = rgbe::Decoder::start(std::move(bytes), name, options.maxPanoramaPixels,
                                      kPanoramaWidthPerFace * options.faceSize);
  if (!decoder) return decoder.error();
  PanoramaLoader loader;
  loader.impl_ = std::make_unique<Impl>(Impl{std::move(*decoder), options, name});
  return loader;
}

int PanoramaLoader::width() const { return impl_->decoder.width(); }
int PanoramaLoader::height() const { return impl_->decoder.height(); }
bool PanoramaLoader::done() const { return impl_->decoder.done(); }
Status PanoramaLoader::step(int rows) { return impl_->decoder.step(rows); }

Result<PackedEnvironment> PanoramaLoader::finish() {
  PN_CHECK(done(), "PanoramaLoader::finish before every row was decoded");
  rgbe::DecodedFile file = impl_->decoder.finish();
  return prefilterPanorama(file.image, impl_->options, impl_->path);
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
