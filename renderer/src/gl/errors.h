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

}  // namespace penumbra::gl
