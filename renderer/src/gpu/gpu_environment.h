// GpuEnvironment: the environment on the GPU — the prefiltered specular cube (RGB16F, one
// explicit level per prefiltered mip), the SH irradiance coefficients pre-convolved with the
// clamped cosine, and the DFG lookup table (computed once per process on the CPU).
#pragma once

#include <array>
#include <memory>

#include <glm/glm.hpp>

#include "gl/program.h"
#include "gl/texture.h"
#include "penumbra/environment_format.h"

namespace penumbra {

class GpuEnvironment {
 public:
  static Result<std::unique_ptr<GpuEnvironment>> create(const PackedEnvironment& env);

  // Binds the cube and the LUT to the program's uEnvSpecular and uDfgLut and sets the
  // environment uniforms (the program in use).
  void bind(const gl::Program& program, float intensity, const glm::mat3& rotation) const;
  int mipCount() const { return cube_.levels(); }

 private:
  gl::TextureCube cube_;
  gl::Texture2D lut_;
  std::array<glm::vec3, 9> irradianceSh_{};
};

}  // namespace penumbra
