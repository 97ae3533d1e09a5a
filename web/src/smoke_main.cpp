// Browser smoke test of the platform layer and GL wrappers: creates the WebGL2 context on
// #canvas, probes capabilities, clears a float render target to known values and reads them
// back. Results go to JS as JSON strings; failures are JSON {"error": "..."}, never a throw or
// abort crossing the boundary (the page would die and the test would only see a timeout).
#include <emscripten/emscripten.h>
#include <emscripten/html5.h>

#include <array>
#include <exception>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "gl/capabilities.h"
#include "gl/errors.h"
#include "gl/gl.h"
#include "gl/objects.h"
#include "gl/texture.h"
#include "penumbra/gl_context.h"

namespace {

using nlohmann::json;
using namespace penumbra;

constexpr int kSize = 4;  // render-target size; every pixel is checked

// One context for the page: a second emscripten_webgl_create_context on the same canvas would
// alias the browser's single WebGL context.
std::unique_ptr<GlContext> gContext;
std::string gResult;  // backs the char* handed to JS until the next call

Result<GlContext*> context() {
  if (!gContext) {
    auto created = GlContext::create({.backend = GlBackend::WebGL2, .canvasSelector = "#canvas"});
    if (!created) return created.error();
    gContext = std::move(*created);
  }
  PN_TRY(gContext->makeCurrent());
  return gContext.get();
}

json extensionList() {
  json list = json::array();
  GLint n = 0;
  glGetIntegerv(GL_NUM_EXTENSIONS, &n);
  for (GLint i = 0; i < n; ++i) {
    const auto* e =
        reinterpret_cast<const char*>(glGetStringi(GL_EXTENSIONS, static_cast<GLuint>(i)));
    // Emscripten lists each WebGL extension twice, plain and "GL_"-prefixed: keep the plain.
    if (e && std::string_view(e).rfind("GL_", 0) != 0) list.push_back(e);
  }
  return list;
}

// Paints half of the visible canvas (band 0 top, 1 bottom; green: read-back matched, red: it did
// not), so a screenshot of the page shows at a glance that WebGL2 ran.
void paintBand(int band, bool ok) {
  int w = 0, h = 0;
  emscripten_get_canvas_element_size("#canvas", &w, &h);
  h /= 2;
  gl::Framebuffer::bindDefault();
  gl::setViewport(0, 0, w, 2 * h);
  glEnable(GL_SCISSOR_TEST);
  const int y = band == 0 ? h : 0;
  glScissor(0, y, w, h);
  gl::clearColor(ok ? 0.1f : 0.9f, ok ? 0.75f : 0.1f, 0.2f, 1.0f);
  // Inner square tells the runs apart: blue for RGBA32F (top), orange for RGBA16F (bottom).
  glScissor(w / 4, y + h / 4, w / 2, h / 2);
  if (band == 0) {
    gl::clearColor(0.15f, 0.35f, 0.95f, 1.0f);
  } else {
    gl::clearColor(0.95f, 0.65f, 0.1f, 1.0f);
  }
  glDisable(GL_SCISSOR_TEST);
}

json runSmoke(bool forceHalfFloat) {
  auto ctx = context();
  if (!ctx) return {{"error", ctx.message()}};
  gl::clearErrors();
  gl::Capabilities caps =
      gl::queryCapabilities((*ctx)->isDesktopGl(), {.forceHalfFloat = forceHalfFloat});

  // Values exact in both float32 and float16 (the half path must round-trip them bit-exactly).
  const std::array<float, 4> clear = forceHalfFloat
                                         ? std::array<float, 4>{0.125f, -0.75f, 3.5f, 2048.0f}
                                         : std::array<float, 4>{0.25f, 0.5f, 1.5f, 2.0f};
  auto tex = gl::Texture2D::create(
      {.width = kSize,
       .height = kSize,
       .format = caps.accumulationFormat,
       .sampler = {.minFilter = gl::Filter::Nearest, .magFilter = gl::Filter::Nearest}});
  if (!tex) return {{"error", tex.message()}};
  gl::Framebuffer fb = gl::Framebuffer::create();
  fb.attachColor(0, *tex);
  fb.setDrawBuffers(1);
  if (auto st = fb.checkComplete(); !st) return {{"error", st.message()}};
  fb.bind();
  gl::setViewport(0, 0, kSize, kSize);
  gl::clearBufferFloat(0, clear[0], clear[1], clear[2], clear[3]);
  std::vector<float> px = fb.readRgbaFloat(0, 0, 0, kSize, kSize);
  if (auto st = gl::checkError("smoke clear/read-back"); !st) return {{"error", st.message()}};

  bool uniform = true;
  for (size_t i = 0; i < px.size(); ++i) uniform = uniform && px[i] == px[i % 4];
  const std::array<float, 4> got = {px[0], px[1], px[2], px[3]};

  paintBand(forceHalfFloat ? 1 : 0, uniform && got == clear);

  json extensions = extensionList();
  return {{"context", (*ctx)->description()},
          {"backend", backendName((*ctx)->backend())},
          {"format", gl::formatName(caps.accumulationFormat)},
          {"expected", clear},
          {"values", got},
          {"uniform", uniform},
          {"colorBufferFloat", caps.colorBufferFloat},
          {"colorBufferHalfFloat", caps.colorBufferHalfFloat},
          {"floatLinear", caps.floatLinear},
          {"floatBlend", caps.floatBlend},
          {"maxTextureSize", caps.maxTextureSize},
          {"report", caps.report()},
          {"extensions", extensions}};
}

const char* finish(const json& j) {
  // replace: a driver string with invalid UTF-8 must not make dump() throw.
  gResult = j.dump(-1, ' ', false, json::error_handler_t::replace);
  return gResult.c_str();
}

}  // namespace

extern "C" {

// Runs the smoke test; forceHalfFloat != 0 takes the RGBA16F accumulation fallback path.
EMSCRIPTEN_KEEPALIVE const char* penumbra_smoke_run(int forceHalfFloat) {
  try {
    return finish(runSmoke(forceHalfFloat != 0));
  } catch (const std::exception& e) {
    return finish({{"error", std::string("exception: ") + e.what()}});
  } catch (...) {
    return finish({{"error", "unknown exception"}});
  }
}

// Checks that C++ exceptions work in this build (-fexceptions at compile and link): without it
// the throw below would abort the module instead of being caught, as the glTF loader relies on.
EMSCRIPTEN_KEEPALIVE const char* penumbra_smoke_exceptions() {
  try {
    (void)json::parse("{ \"malformed\": ");
    return finish({{"error", "malformed JSON parsed without an exception"}});
  } catch (const json::exception& e) {
    return finish({{"caught", e.what()}});
  } catch (...) {
    return finish({{"error", "unexpected exception type"}});
  }
}

}  // extern "C"
