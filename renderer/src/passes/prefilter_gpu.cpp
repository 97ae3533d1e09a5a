// GPU prefilter: panorama -> cube mip 0 (2x2 supersampled), a box-filtered source pyramid
// (glGenerateMipmap), then each specular mip with filtered importance sampling; faces are read
// back into the CPU Cubemap layout so everything downstream is shared with the CPU path.
#include <algorithm>
#include <cmath>
#include <string>

#include "gl/capabilities.h"
#include "gl/errors.h"
#include "gl/objects.h"
#include "gl/program.h"
#include "passes/fullscreen_pass.h"
#include "penumbra/prefilter_gpu.h"
#include "penumbra/version.h"

namespace penumbra {
namespace {

bool isPowerOfTwo(int v) {
  return v > 0 && (v & (v - 1)) == 0;
}

}  // namespace

bool gpuPrefilterIsFaster() {
  const std::string renderer = gl::queryCapabilities(false).renderer;
  for (const char* soft : {"llvmpipe", "softpipe", "SwiftShader", "swiftshader"}) {
    if (renderer.find(soft) != std::string::npos) return false;
  }
  return true;
}

namespace {

Status checkInputs(const Image& panorama, const ibl::PrefilterOptions& options) {
  if (panorama.width != 2 * panorama.height || panorama.height < 1) {
    return makeError("expected a 2:1 equirectangular panorama, got " +
                     std::to_string(panorama.width) + "x" + std::to_string(panorama.height));
  }
  if (!isPowerOfTwo(options.faceSize) || !isPowerOfTwo(options.minFaceSize) ||
      options.minFaceSize > options.faceSize) {
    return makeError("face sizes must be powers of two with minFaceSize <= faceSize");
  }
  return {};
}

// The panorama as RGBA float with a full mip chain (box-filtered pyramid for minification).
Result<gl::Texture2D> uploadPanorama(const Image& panorama, gl::PixelFormat format) {
  std::vector<float> rgba(static_cast<size_t>(panorama.width) * panorama.height * 4, 1.0f);
  for (size_t i = 0, n = static_cast<size_t>(panorama.width) * panorama.height; i < n; ++i) {
    for (int c = 0; c < 3; ++c) {
      rgba[i * 4 + c] = panorama.pixels[i * panorama.channels + std::min(c, panorama.channels - 1)];
    }
  }
  auto pano = gl::Texture2D::create({.width = panorama.width,
                                     .height = panorama.height,
                                     .format = format,
                                     .levels = gl::fullMipCount(panorama.width, panorama.height),
                                     .sampler = {.minFilter = gl::Filter::LinearMipLinear,
                                                 .magFilter = gl::Filter::Linear,
                                                 .wrapS = gl::Wrap::Repeat,
                                                 .wrapT = gl::Wrap::ClampToEdge}});
  if (!pano) return makeError("panorama texture: " + pano.message());
  pano->upload(0, rgba.data(), gl::DataType::Float);
  pano->generateMipmaps();
  return std::move(*pano);
}

}  // namespace

Result<PackedEnvironment> prefilterGpu(const Image& input, const ibl::PrefilterOptions& options) {
  // The sun leaves the panorama first, as in prefilterCpu.
  Image withoutSun;
  std::optional<ibl::Sun> sun;
  if (options.sunThreshold != 0.0f) {
    withoutSun = input;
    sun = ibl::extractSun(withoutSun, {.threshold = options.sunThreshold});
  }
  const Image& panorama = sun ? withoutSun : input;
  PN_TRY(checkInputs(panorama, options));
  const gl::Capabilities caps = gl::queryCapabilities(false);
  const bool full = caps.colorBufferFloat && caps.floatLinear;
  const gl::PixelFormat format = full ? gl::PixelFormat::RGBA32F : gl::PixelFormat::RGBA16F;
  if (!full && !caps.colorBufferHalfFloat) {
    return makeError("the GPU prefilter needs renderable float textures");
  }

  auto pano = uploadPanorama(panorama, format);
  if (!pano) return pano.error();

  const int size = options.faceSize;
  const int mips = ibl::mipCountFor(size, options.minFaceSize);
  const int sourceLevels = gl::fullMipCount(size, size);
  auto source = gl::TextureCube::create(
      {.width = size,
       .format = format,
       .levels = sourceLevels,
       .sampler = {.minFilter = gl::Filter::LinearMipLinear, .magFilter = gl::Filter::Linear}});
  if (!source) return makeError("source cube: " + source.message());
  auto target = gl::TextureCube::create({.width = size, .format = format, .levels = mips});
  if (!target) return makeError("prefiltered cube: " + target.message());

  gl::ShaderLibrary library;
  auto toCube = passes::FullscreenPass::create(library, "ibl/panorama_to_cube.frag");
  if (!toCube) return toCube.error();
  auto ggx = passes::FullscreenPass::create(library, "ibl/prefilter_ggx.frag");
  if (!ggx) return ggx.error();
  auto direct = passes::FullscreenPass::create(library, "ibl/prefilter_direct.frag");
  if (!direct) return direct.error();
  // Rough mips (wide lobes) are convolved exactly over a source level of at most 32 px faces.
  const int directSize = std::min(size, 32);
  const float directLevel = std::log2(static_cast<float>(size / directSize));

  gl::Framebuffer fb = gl::Framebuffer::create();
  // Step 1: mip 0 of the source cube. A cube texel spans about (pi/2)/size radians and a
  // panorama texel 2 pi / width; each of the 2x2 samples covers half a cube texel, so read
  // the panorama level whose texels are that wide: log2(width / (8 size)).
  const float lod = std::max(0.0f, std::log2(static_cast<float>(panorama.width) / (8.0f * size)));
  for (int face = 0; face < ibl::kFaceCount; ++face) {
    fb.attachColor(0, *source, face, 0);
    fb.setDrawBuffers(1);
    PN_TRY(fb.checkComplete());
    gl::setViewport(0, 0, size, size);
    const gl::Program& p = toCube->begin();
    p.bind("uPanorama", *pano);
    p.set("uFace", face);
    p.set("uFaceSize", static_cast<float>(size));
    p.set("uLod", lod);
    toCube->draw();
  }
  source->generateMipmaps();

  PackedEnvironment env;
  env.specular = ibl::Cubemap(size, mips);
  auto readFace = [&](const gl::TextureCube& cube, int face, int mip, Image& out) {
    const int s = std::max(1, size >> mip);
    fb.attachColor(0, cube, face, mip);
    auto data = fb.readRgbaFloat(0, 0, 0, s, s);
    // Rendering and read-back both use texture row order: row 0 is t = 0, as the CPU path.
    for (size_t i = 0, n = static_cast<size_t>(s) * s; i < n; ++i) {
      for (int c = 0; c < 3; ++c) out.pixels[i * 3 + c] = data[i * 4 + c];
    }
  };
  for (int face = 0; face < ibl::kFaceCount; ++face) {
    readFace(*source, face, 0, env.specular.face(0, face));
  }
  // Step 2: mips 1.. with GGX filtered importance sampling.
  for (int m = 1; m < mips; ++m) {
    const int s = std::max(1, size >> m);
    const float r = ibl::roughnessForMip(m, mips);
    for (int face = 0; face < ibl::kFaceCount; ++face) {
      fb.attachColor(0, *target, face, m);
      fb.setDrawBuffers(1);
      PN_TRY(fb.checkComplete());
      gl::setViewport(0, 0, s, s);
      const bool exact = r >= 0.5f;
      const passes::FullscreenPass& pass = exact ? *direct : *ggx;
      const gl::Program& p = pass.begin();
      p.bind("uSource", *source);
      p.set("uFace", face);
      p.set("uFaceSize", static_cast<float>(s));
      p.set("uAlpha", r * r);
      if (exact) {
        p.set("uSourceSize", directSize);
        p.set("uSourceLevel", directLevel);
      } else {
        p.set("uSourceSize", static_cast<float>(size));
        p.set("uSamples", std::clamp(options.samples, 1, 4096));
        p.set("uMaxLod", static_cast<float>(std::max(0, sourceLevels - 3)));
      }
      pass.draw();
      readFace(*target, face, m, env.specular.face(m, face));
      if (options.progress) {
        options.progress(static_cast<float>((m - 1) * 6 + face + 1) / ((mips - 1) * 6));
      }
    }
  }
  gl::Framebuffer::bindDefault();
  PN_TRY(gl::checkError("GPU prefilter"));
  for (int m = 0; m < mips; ++m) env.roughness.push_back(ibl::roughnessForMip(m, mips));
  env.sh = ibl::projectSh(env.specular, 0, options.threads);
  env.samples = options.samples;
  env.sun = sun;
  env.generator = std::string("penumbra-prefilter ") + version() + " (GPU)";
  return env;
}

}  // namespace penumbra
