// GL error reporting: names for error codes and framebuffer statuses, and a check that turns a
// pending GL error (out of memory above all) into a returned error instead of silent garbage.
#pragma once

#include <string>

#include "gl/gl.h"
#include "penumbra/error.h"

namespace penumbra::gl {

const char* errorName(GLenum error);
const char* framebufferStatusName(GLenum status);
// Drains every pending GL error; returns an error naming `what` and the first code if any.
Status checkError(const std::string& what);
// Drains pending errors without reporting (after an operation whose failure is handled).
void clearErrors();

// An allocation's checks (textures, buffers, renderbuffers). Natively: pending errors are
// drained before it and a failure is reported at once. In WebGL every glGetError is a round
// trip that holds the page until the GPU process has run everything queued (0.6 s of the
// default page's first 3 s on SwiftShader, with the GPU process idle for part of that time),
// so there the allocation is only remembered: the next checkError() (every frame does one)
// reports a failure with the first allocation since the last check.
void beginAllocation();
Status checkAllocation(const std::string& what);
// Deferred checks are the WebGL build's default; tests turn them on natively.
void setDeferredAllocationChecks(bool deferred);

}  // namespace penumbra::gl
