// Helpers shared by the test binaries: where the source tree and the test output folder are,
// and golden-image comparison with stated tolerances that writes a diff image on failure.
#pragma once

#include <string>

#include <gtest/gtest.h>

#include "penumbra/image.h"

namespace penumbra::test {

// The repository root (PENUMBRA_SOURCE_DIR, set by ctest).
std::string sourceDir();
// A folder for files the tests write (PENUMBRA_TEST_OUTPUT), created on demand.
std::string outputDir();
// outputDir()/relative, emptied (or created) for one test's files.
std::string freshOutputDir(const std::string& relative);

struct Tolerance {
  double maxAbs;   // largest allowed per-channel difference
  double meanAbs;  // largest allowed mean per-channel difference
};

// Compares `actual` with `expected` over RGB; on failure writes actual, expected and a heat
// map of the difference into outputDir() and names them in the failure message.
::testing::AssertionResult matchesImage(const Image& actual, const Image& expected,
                                        Tolerance tolerance, const std::string& name);

// Compares `actual` with the golden image at `goldenPath` over RGB. On failure it writes
// actual, expected and a heat map of the difference into outputDir() and names them in the
// failure message. When PENUMBRA_UPDATE_GOLDEN=1 it writes `actual` as the new golden instead.
::testing::AssertionResult matchesGolden(const Image& actual, const std::string& goldenPath,
                                         Tolerance tolerance, const std::string& name);

}  // namespace penumbra::test
