#include "gl_fixture.h"

namespace penumbra::test {

void GlFixture::SetUpTestSuite() {
  if (context_) return;
  auto ctx = GlContext::create();
  if (!ctx) {
    error_ = ctx.message();
    return;
  }
  context_ = std::move(*ctx);
  caps_ = gl::queryCapabilities(context_->isDesktopGl());
}

void GlFixture::SetUp() {
  ASSERT_TRUE(context_) << error_;
  ASSERT_TRUE(context_->makeCurrent().ok());
}

}  // namespace penumbra::test
