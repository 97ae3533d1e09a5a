#include "output.h"

#include <cctype>
#include <filesystem>

#include "penumbra/image.h"

namespace penumbra::tools {

bool hasExtension(const std::string& path, const char* ext) {
  std::string e = std::filesystem::path(path).extension().string();
  for (auto& c : e) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return e == ext;
}

Status writeOutput(const std::string& path, Renderer& renderer) {
  if (hasExtension(path, ".exr") || hasExtension(path, ".hdr")) {
    auto radiance = renderer.readRadiance();
    if (!radiance) return radiance.error();
    return writeImage(path, *radiance);
  }
  auto display = renderer.readDisplay();
  if (!display) return display.error();
  return writeImage(path, *display);
}

}  // namespace penumbra::tools
