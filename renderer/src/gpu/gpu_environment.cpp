#include "gpu/gpu_environment.h"

#include <mutex>
#include <string>

#include "penumbra/ibl.h"

namespace penumbra {
namespace {

// The DFG table depends on nothing but the BRDF: compute it once per process. Its alpha holds
// the sheen lobe's directional albedo (KHR_materials_sheen), which needs no texture unit of its
// own that way (the lighting shader uses all 16 of WebGL2's).
const Image& dfgLut() {
  static Image lut;
  static std::once_flag once;
  std::call_once(once, [] {
    const int size = 64;
    const Image dfg = ibl::computeBrdfLut({.size = size, .samples = 256});
    const Image sheen = ibl::computeSheenLut(size, 128);
    lut = Image(size, size, 4);
    for (int y = 0; y < size; ++y) {
      for (int x = 0; x < size; ++x) {
        const float* d = dfg.pixel(x, y);
        float* p = lut.pixel(x, y);
        p[0] = d[0];
        p[1] = d[1];
        p[2] = d[2];
        p[3] = sheen.pixel(x, y)[0];
      }
    }
  });
  return lut;
}

}  // namespace

Result<std::unique_ptr<GpuEnvironment>> GpuEnvironment::create(const PackedEnvironment& env) {
  const int mips = env.specular.mipCount();
  if (mips < 1 || env.specular.size < 1) return makeError("environment has no cube map");
  auto ge = std::make_unique<GpuEnvironment>();
  auto cube = gl::TextureCube::create(
      {.width = env.specular.size,
       .format = gl::PixelFormat::RGB16F,
       .levels = mips,
       .sampler = {.minFilter = gl::Filter::LinearMipLinear, .magFilter = gl::Filter::Linear}});
  if (!cube) return makeError("environment cube: " + cube.message());
  for (int m = 0; m < mips; ++m) {
    for (int f = 0; f < ibl::kFaceCount; ++f) {
      const Image& img = env.specular.face(m, f);
      if (img.channels != 3 || img.width != env.specular.faceSize(m)) {
        return makeError("environment face " + std::to_string(f) + " of mip " + std::to_string(m) +
                         " has the wrong size or channels");
      }
      cube->upload(f, m, img.pixels.data(), gl::DataType::Float);
    }
  }
  ge->cube_ = std::move(*cube);

  const Image& lut = dfgLut();
  auto lutTex = gl::Texture2D::create({.width = lut.width,
                                       .height = lut.height,
                                       .format = gl::PixelFormat::RGBA16F,
                                       .sampler = {.minFilter = gl::Filter::Linear}});
  if (!lutTex) return makeError("DFG table: " + lutTex.message());
  // The LUT image has row 0 = roughness near 0, which is what texture t = 0 should read.
  lutTex->upload(0, lut.pixels.data(), gl::DataType::Float);
  ge->lut_ = std::move(*lutTex);

  // Pre-convolve with the clamped cosine: E(n) = sum A_l L_lm Y_lm(n).
  const float a[9] = {3.14159265f, 2.09439510f, 2.09439510f, 2.09439510f, 0.78539816f,
                      0.78539816f, 0.78539816f, 0.78539816f, 0.78539816f};
  for (int i = 0; i < 9; ++i)
    ge->irradianceSh_[static_cast<size_t>(i)] = env.sh.c[static_cast<size_t>(i)] * a[i];
  return ge;
}

void GpuEnvironment::bind(const gl::Program& program, float intensity,
                          const glm::mat3& rotation) const {
  program.bind("uEnvSpecular", cube_);
  program.bind("uDfgLut", lut_);
  program.set("uShIrradiance", std::span<const glm::vec3>(irradianceSh_));
  program.set("uEnvMaxMip", static_cast<float>(cube_.levels() - 1));
  program.set("uEnvIntensity", intensity);
  program.set("uEnvRotation", rotation);
}

}  // namespace penumbra
