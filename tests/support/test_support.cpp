#include "test_support.h"

#include <cstdlib>
#include <filesystem>
#include <sstream>

namespace penumbra::test {

std::string sourceDir() {
  const char* dir = std::getenv("PENUMBRA_SOURCE_DIR");
  return dir ? dir : ".";
}

std::string outputDir() {
  const char* env = std::getenv("PENUMBRA_TEST_OUTPUT");
  std::string dir = env ? env : "test-output";
  std::filesystem::create_directories(dir);
  return dir;
}

std::string freshOutputDir(const std::string& relative) {
  const std::string dir = outputDir() + "/" + relative;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

::testing::AssertionResult matchesGolden(const Image& actual, const std::string& goldenPath,
                                         Tolerance tolerance, const std::string& name) {
  const char* update = std::getenv("PENUMBRA_UPDATE_GOLDEN");
  if (update && std::string(update) == "1") {
    std::filesystem::create_directories(std::filesystem::path(goldenPath).parent_path());
    auto written = writeImage(goldenPath, actual);
    if (!written) return ::testing::AssertionFailure() << written.message();
    return ::testing::AssertionSuccess() << "golden updated: " << goldenPath;
  }
  auto golden = readImage(goldenPath, ReadOptions{.srgbToLinear = false});
  if (!golden) {
    return ::testing::AssertionFailure()
           << golden.message() << " (run with PENUMBRA_UPDATE_GOLDEN=1 to create it)";
  }
  return matchesImage(actual, *golden, tolerance, name);
}

::testing::AssertionResult matchesImage(const Image& actual, const Image& expected,
                                        Tolerance tolerance, const std::string& name) {
  auto diff = compareImages(actual, expected);
  const std::string base = outputDir() + "/" + name;
  if (!diff) {
    (void)writeImage(base + ".actual.png", actual);
    return ::testing::AssertionFailure() << diff.message() << "; wrote " << base << ".actual.png";
  }
  if (diff->maxAbs <= tolerance.maxAbs && diff->meanAbs <= tolerance.meanAbs) {
    return ::testing::AssertionSuccess();
  }
  (void)writeImage(base + ".actual.png", actual);
  (void)writeImage(base + ".expected.png", expected);
  (void)writeImage(base + ".diff.png", diff->heatmap);
  std::ostringstream msg;
  msg << name << ": max diff " << diff->maxAbs << " (allowed " << tolerance.maxAbs
      << "), mean diff " << diff->meanAbs << " (allowed " << tolerance.meanAbs << "); see " << base
      << ".{actual,expected,diff}.png";
  return ::testing::AssertionFailure() << msg.str();
}

}  // namespace penumbra::test
