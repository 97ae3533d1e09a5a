// penumbra-host-example: how a C++ host (a path tracer's viewer, an editor) shows Penumbra in
// its own OpenGL ES context. The host creates an EGL context and a framebuffer object, sets
// some GL state of its own, and then lets Penumbra render a scene progressively and present
// the image into a viewport of that framebuffer. It checks that its GL state is unchanged,
// that nothing outside the viewport was touched, writes the viewport as a PNG and, with
// --reference, compares it with an image from penumbra-render.
//
//   penumbra-host-example SCENE -o OUT.png [--set key=value ...] [--reference REF.png]
//                         [--max-diff D] [--mean-diff D]
// --set takes any key of the settings schema (width, height, frames, shadowMapSize, ...).
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GLES3/gl3.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

#include "penumbra/gl_context.h"
#include "penumbra/image.h"
#include "penumbra/render_job.h"
#include "penumbra/renderer.h"

namespace {

int fail(const std::string& message) {
  std::fprintf(stderr, "penumbra-host-example: error: %s\n", message.c_str());
  return 1;
}

// The host's own context: EGL surfaceless on Mesa, OpenGL ES 3.0, rendering into FBOs only.
bool createHostContext() {
  auto getDisplay = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
      eglGetProcAddress("eglGetPlatformDisplayEXT"));
  EGLDisplay dpy = getDisplay
                       ? getDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr)
                       : EGL_NO_DISPLAY;
  if (dpy == EGL_NO_DISPLAY || !eglInitialize(dpy, nullptr, nullptr)) return false;
  const EGLint configAttribs[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_ES3_BIT, EGL_SURFACE_TYPE,
                                  EGL_PBUFFER_BIT, EGL_NONE};
  EGLConfig config = nullptr;
  EGLint count = 0;
  if (!eglBindAPI(EGL_OPENGL_ES_API) || !eglChooseConfig(dpy, configAttribs, &config, 1, &count) ||
      count < 1) {
    return false;
  }
  const EGLint contextAttribs[] = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_CONTEXT_MINOR_VERSION, 0,
                                   EGL_NONE};
  EGLContext ctx = eglCreateContext(dpy, config, EGL_NO_CONTEXT, contextAttribs);
  return ctx != EGL_NO_CONTEXT && eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, ctx);
}

// The host state this example sets and expects back after Penumbra's calls.
std::vector<int> hostState() {
  std::vector<int> v;
  for (GLenum name :
       {GL_DRAW_FRAMEBUFFER_BINDING, GL_CURRENT_PROGRAM, GL_VERTEX_ARRAY_BINDING, GL_ACTIVE_TEXTURE,
        GL_PACK_ALIGNMENT, GL_UNPACK_ALIGNMENT, GL_DEPTH_FUNC, GL_BLEND_SRC_RGB, GL_BLEND_DST_RGB,
        GL_CULL_FACE_MODE, GL_FRONT_FACE, GL_SAMPLER_BINDING, GL_TEXTURE_BINDING_2D}) {
    GLint x = 0;
    glGetIntegerv(name, &x);
    v.push_back(x);
  }
  GLint box[4];
  glGetIntegerv(GL_VIEWPORT, box);
  v.insert(v.end(), box, box + 4);
  glGetIntegerv(GL_SCISSOR_BOX, box);
  v.insert(v.end(), box, box + 4);
  for (GLenum cap : {GL_SCISSOR_TEST, GL_BLEND, GL_CULL_FACE, GL_DEPTH_TEST}) {
    v.push_back(glIsEnabled(cap));
  }
  GLfloat clear[4];
  glGetFloatv(GL_COLOR_CLEAR_VALUE, clear);
  for (float c : clear) v.push_back(static_cast<int>(c * 1000.0f));
  return v;
}

}  // namespace

int main(int argc, char** argv) {
  std::string scene, out, reference;
  double maxDiff = 0.02, meanDiff = 0.002;
  penumbra::JobRequest request;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto next = [&]() -> std::string { return i + 1 < argc ? argv[++i] : ""; };
    if (a == "-o") {
      out = next();
    } else if (a == "--set") {
      const std::string kv = next();
      const size_t eq = kv.find('=');
      if (eq == std::string::npos) return fail("--set takes key=value, got '" + kv + "'");
      request.settings.emplace_back(kv.substr(0, eq), kv.substr(eq + 1));
    } else if (a == "--reference") {
      reference = next();
    } else if (a == "--max-diff") {
      maxDiff = std::atof(next().c_str());
    } else if (a == "--mean-diff") {
      meanDiff = std::atof(next().c_str());
    } else if (scene.empty() && !a.empty() && a[0] != '-') {
      scene = a;
    } else {
      return fail("unknown argument '" + a + "'");
    }
  }
  if (scene.empty() || out.empty()) {
    return fail(
        "usage: penumbra-host-example SCENE -o OUT.png [--set key=value ...] "
        "[--reference REF.png] [--max-diff D] [--mean-diff D]");
  }
  if (!createHostContext()) return fail("the host could not create its EGL context");

  // Penumbra's settings decide the image size; the host's target is larger, with a border.
  request.scenePath = scene;
  auto job = penumbra::RenderJob::load(request);
  if (!job) return fail(job.message());
  const int w = job->settings.width, h = job->settings.height, border = 8;
  const int fw = w + 2 * border, fh = h + 2 * border;

  // The host's framebuffer object, cleared to magenta, and some host state of its own.
  GLuint tex = 0, fbo = 0, vao = 0, sampler = 0;
  glGenTextures(1, &tex);
  glBindTexture(GL_TEXTURE_2D, tex);
  glTexStorage2D(GL_TEXTURE_2D, 1, GL_RGBA8, fw, fh);
  glGenFramebuffers(1, &fbo);
  glBindFramebuffer(GL_FRAMEBUFFER, fbo);
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, tex, 0);
  if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
    return fail("the host's framebuffer is incomplete");
  }
  glClearColor(1.0f, 0.0f, 1.0f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT);
  glGenVertexArrays(1, &vao);
  glBindVertexArray(vao);
  glGenSamplers(1, &sampler);
  glBindSampler(0, sampler);
  glSamplerParameteri(sampler, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glEnable(GL_SCISSOR_TEST);
  glScissor(1, 1, 2, 2);
  glEnable(GL_CULL_FACE);
  glCullFace(GL_FRONT);
  glDepthFunc(GL_GREATER);
  glBlendFunc(GL_DST_COLOR, GL_ZERO);
  glPixelStorei(GL_PACK_ALIGNMENT, 8);
  glViewport(3, 5, 7, 11);
  glClearColor(0.25f, 0.5f, 0.75f, 1.0f);
  const std::vector<int> before = hostState();

  auto context = penumbra::GlContext::adoptCurrent();
  if (!context) return fail(context.message());
  auto renderer = penumbra::Renderer::create({.preserveHostState = true});
  if (!renderer) return fail(renderer.message());
  if (auto st = job->applyTo(**renderer); !st) return fail(st.message());
  const penumbra::PresentTarget viewport{
      .framebuffer = fbo, .x = border, .y = border, .width = w, .height = h};
  // While its view moves, a host shows previews (frame 1 at a quarter of the pixels); once the
  // view rests, it steps to convergence (the preview is not part of the image).
  if (auto st = (*renderer)->preview(); !st) return fail(st.message());
  if (auto st = (*renderer)->present(viewport); !st) return fail(st.message());
  if (hostState() != before) return fail("Penumbra's preview changed the host's GL state");
  while (!(*renderer)->converged()) {
    if (auto f = (*renderer)->step(); !f) return fail(f.message());
  }
  if (auto st = (*renderer)->present(viewport); !st) return fail(st.message());
  if (hostState() != before) return fail("Penumbra changed the host's GL state");

  // Read the host's framebuffer (with the host's own state: pack alignment 8 is fine for
  // RGBA8 rows) and check that only the viewport was drawn.
  std::vector<unsigned char> pixels(static_cast<size_t>(fw) * fh * 4);
  glDisable(GL_SCISSOR_TEST);
  glReadPixels(0, 0, fw, fh, GL_RGBA, GL_UNSIGNED_BYTE, pixels.data());
  penumbra::Image image(w, h, 4, 0.0f);
  int outside = 0;
  for (int y = 0; y < fh; ++y) {
    for (int x = 0; x < fw; ++x) {
      const unsigned char* p = &pixels[(static_cast<size_t>(y) * fw + x) * 4];
      const bool inside = x >= border && x < border + w && y >= border && y < border + h;
      if (!inside) {
        outside += !(p[0] == 255 && p[1] == 0 && p[2] == 255);
        continue;
      }
      float* q = image.pixel(x - border, h - 1 - (y - border));  // GL rows run bottom-up
      for (int c = 0; c < 4; ++c) q[c] = static_cast<float>(p[c]) / 255.0f;
    }
  }
  if (outside > 0) return fail(std::to_string(outside) + " pixels outside the viewport changed");
  if (auto st = penumbra::writeImage(out, image); !st) return fail(st.message());
  std::printf("penumbra-host-example: %dx%d, %d frames into framebuffer %u at (%d, %d) -> %s\n", w,
              h, (*renderer)->framesDone(), fbo, border, border, out.c_str());
  if (!reference.empty()) {
    auto ref = penumbra::readImage(reference, {.srgbToLinear = false});
    if (!ref) return fail(ref.message());
    auto diff = penumbra::compareImages(image, *ref);
    if (!diff) return fail(diff.message());
    std::printf("penumbra-host-example: against %s: max %.4f, mean %.5f (allowed %.4f, %.5f)\n",
                reference.c_str(), diff->maxAbs, diff->meanAbs, maxDiff, meanDiff);
    if (diff->maxAbs > maxDiff || diff->meanAbs > meanDiff) {
      return fail("the host's image differs from the reference");
    }
  }
  return 0;
}
