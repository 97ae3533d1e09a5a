// Handle: the move-only ownership of one GL object name, shared by every wrapper class.
// Each wrapper (Texture2D, Buffer, ...) holds one Handle with the right delete function.
#pragma once

#include <utility>

#include "gl/gl.h"

namespace penumbra::gl {

using DeleteFn = void (*)(GLuint);

template <DeleteFn Delete>
class Handle {
 public:
  Handle() = default;
  explicit Handle(GLuint id) : id_(id) {}
  ~Handle() { reset(); }
  Handle(Handle&& other) noexcept : id_(std::exchange(other.id_, 0)) {}
  Handle& operator=(Handle&& other) noexcept {
    if (this != &other) {
      reset();
      id_ = std::exchange(other.id_, 0);
    }
    return *this;
  }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;

  GLuint id() const { return id_; }
  explicit operator bool() const { return id_ != 0; }
  void reset() {
    if (id_) Delete(id_);
    id_ = 0;
  }

 private:
  GLuint id_ = 0;
};

inline void deleteTexture(GLuint id) {
  glDeleteTextures(1, &id);
}
inline void deleteBuffer(GLuint id) {
  glDeleteBuffers(1, &id);
}
inline void deleteVertexArray(GLuint id) {
  glDeleteVertexArrays(1, &id);
}
inline void deleteTransformFeedback(GLuint id) {
  glDeleteTransformFeedbacks(1, &id);
}
inline void deleteFramebuffer(GLuint id) {
  glDeleteFramebuffers(1, &id);
}
inline void deleteRenderbuffer(GLuint id) {
  glDeleteRenderbuffers(1, &id);
}
inline void deleteProgram(GLuint id) {
  glDeleteProgram(id);
}
inline void deleteShader(GLuint id) {
  glDeleteShader(id);
}
inline void deleteQuery(GLuint id) {
  glDeleteQueries(1, &id);
}

}  // namespace penumbra::gl
