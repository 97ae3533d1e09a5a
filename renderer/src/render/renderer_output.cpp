// The renderer's output: the running mean read back as linear radiance, tone mapped into the
// display target or read back as 8-bit, and presented into a host's framebuffer.
#include <algorithm>

#include "gl/errors.h"
#include "gl/state_guard.h"
#include "render/renderer_impl.h"

namespace penumbra {
namespace {

// GL rows run bottom-up; Image rows top-down. Flips in place and takes the buffer: a
// 1280x720 float image is 15 MB, and fresh pages cost more than the copy on some machines.
Image flipRows(std::vector<float> data, int w, int h, int channels) {
  const auto row = static_cast<std::ptrdiff_t>(w) * channels;
  for (int y = 0; y < h / 2; ++y) {
    std::swap_ranges(data.begin() + y * row, data.begin() + (y + 1) * row,
                     data.begin() + (h - 1 - y) * row);
  }
  Image img;
  img.width = w;
  img.height = h;
  img.channels = channels;
  img.pixels = std::move(data);
  return img;
}

}  // namespace

Result<Image> Renderer::readRadiance() {
  gl::StateGuard guard(impl_->options.preserveHostState);
  PN_TRY(impl_->ensureFrameResources());
  auto& t = *impl_->targets;
  auto data = t.accumulation[static_cast<size_t>(t.current)].framebuffer.readRgbaFloat(
      0, 0, 0, t.width, t.height);
  PN_TRY(gl::checkError("reading the accumulated image"));
  // The diffuse rays' control variate (glsl/occlusion_trace.frag) makes single samples negative
  // in dark pixels, so an early mean can be: radiance is not, and the display clamps them too.
  for (size_t i = 0; i < data.size(); i += 4) {
    for (size_t c = 0; c < 3; ++c) data[i + c] = std::max(data[i + c], 0.0f);
  }
  return flipRows(std::move(data), t.width, t.height, 4);
}

Status Renderer::toneMap() {
  gl::StateGuard guard(impl_->options.preserveHostState);
  PN_TRY(impl_->ensureFrameResources());
  auto& t = *impl_->targets;
  PN_TRY(impl_->drawDisplayed({t.display.framebuffer.id(), 0, 0, t.width, t.height}));
  return gl::checkError("tone mapping");
}

void Renderer::finish() {
  gl::finish();
}

Result<Image> Renderer::readDisplay() {
  gl::StateGuard guard(impl_->options.preserveHostState);
  PN_TRY(impl_->ensureFrameResources());
  PN_TRY(toneMap());
  auto& t = *impl_->targets;
  auto bytes = t.display.framebuffer.readRgba8(0, 0, 0, t.width, t.height);
  PN_TRY(gl::checkError("reading the displayed image"));
  // Converted straight into the flipped float image: one allocation, no intermediate copy.
  Image img;
  img.width = t.width;
  img.height = t.height;
  img.channels = 4;
  img.pixels.resize(bytes.size());
  const size_t row = static_cast<size_t>(t.width) * 4;
  for (int y = 0; y < t.height; ++y) {
    const uint8_t* src = bytes.data() + static_cast<size_t>(t.height - 1 - y) * row;
    float* dst = img.pixels.data() + static_cast<size_t>(y) * row;
    for (size_t i = 0; i < row; ++i) dst[i] = static_cast<float>(src[i]) * (1.0f / 255.0f);
  }
  return img;
}

Status Renderer::present(int canvasWidth, int canvasHeight) {
  return present({.framebuffer = 0, .width = canvasWidth, .height = canvasHeight});
}

Status Renderer::present(const PresentTarget& target) {
  if (target.width <= 0 || target.height <= 0) {
    return makeError("present: viewport " + std::to_string(target.width) + "x" +
                     std::to_string(target.height) + " is empty");
  }
  gl::StateGuard guard(impl_->options.preserveHostState);
  PN_TRY(impl_->ensureFrameResources());
  PN_TRY(impl_->drawDisplayed(
      {target.framebuffer, target.x, target.y, target.width, target.height}));
  return gl::checkError("presenting to framebuffer " + std::to_string(target.framebuffer));
}

}  // namespace penumbra
