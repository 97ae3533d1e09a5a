// A GL context shared by the tests of one binary: created on first use with the backend from
// PENUMBRA_GL (EGL surfaceless by default). Tests that need a context skip nothing: if no
// context can be made, they fail with the platform layer's one-line reason.
#pragma once

#include <memory>

#include <gtest/gtest.h>

#include "gl/capabilities.h"
#include "penumbra/gl_context.h"

namespace penumbra::test {

class GlFixture : public ::testing::Test {
 protected:
  static void SetUpTestSuite();
  void SetUp() override;
  static GlContext& context() { return *context_; }
  static const gl::Capabilities& caps() { return caps_; }

 private:
  static inline std::unique_ptr<GlContext> context_;
  static inline gl::Capabilities caps_;
  static inline std::string error_;
};

}  // namespace penumbra::test
