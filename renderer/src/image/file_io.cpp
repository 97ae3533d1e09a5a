// Whole-file reads and atomic writes (temporary name in the same folder, then rename). Kept
// apart from image_common.cpp so code that only writes bytes (SH JSON, packed environments)
// does not pull the image back ends, and with them OpenImageIO, into a static link.
#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "image/image_internal.h"

namespace penumbra {
namespace detail {
namespace {

std::string errnoText(int err) {
  return std::strerror(err);
}

std::string parentFolder(const std::string& path) {
  std::filesystem::path parent = std::filesystem::path(path).parent_path();
  return parent.empty() ? std::string(".") : parent.string();
}

}  // namespace

std::string lowerExtension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

Result<std::vector<uint8_t>> readFileBytes(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) {
    return makeError("cannot read '" + path + "': no such file");
  }
  if (std::filesystem::is_directory(path, ec)) {
    return makeError("cannot read '" + path + "': it is a folder");
  }
  std::ifstream file(path, std::ios::binary);
  if (!file) return makeError("cannot read '" + path + "': " + errnoText(errno));
  file.seekg(0, std::ios::end);
  const std::streamoff size = file.tellg();
  if (size < 0) return makeError("cannot read '" + path + "': cannot determine its size");
  file.seekg(0, std::ios::beg);
  std::vector<uint8_t> bytes(static_cast<size_t>(size));
  if (size > 0 && !file.read(reinterpret_cast<char*>(bytes.data()), size)) {
    return makeError("cannot read '" + path + "': read error");
  }
  return bytes;
}

Status writeAtomic(const std::string& path,
                   const std::function<Status(const std::string& tempPath)>& writeTemp) {
  const std::string folder = parentFolder(path);
  std::error_code ec;
  if (!std::filesystem::is_directory(folder, ec)) {
    return makeError("cannot write '" + path + "': folder '" + folder + "' does not exist");
  }
  if (std::filesystem::is_directory(path, ec)) {
    return makeError("cannot write '" + path + "': a folder has that name");
  }
  // Reserve a unique temporary name with O_EXCL (mode 0666 less the umask, like any new file;
  // mkstemp would leave the final file readable by its owner only).
  static std::atomic<unsigned> counter{0};
  std::string temp;
  int fd = -1;
  for (int attempt = 0; attempt < 100 && fd < 0; ++attempt) {
    temp = path + ".tmp-" + std::to_string(getpid()) + "-" + std::to_string(counter++);
    fd = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_EXCL, 0666);
    if (fd < 0 && errno != EEXIST) {
      return makeError("cannot write '" + path + "': " + errnoText(errno));
    }
  }
  if (fd < 0) return makeError("cannot write '" + path + "': no free temporary name");
  ::close(fd);
  Status written = writeTemp(temp);
  if (!written.ok()) {
    std::filesystem::remove(temp, ec);
    return written;
  }
  if (std::rename(temp.c_str(), path.c_str()) != 0) {
    const int err = errno;
    std::filesystem::remove(temp, ec);
    return makeError("cannot write '" + path + "': " + errnoText(err));
  }
  return {};
}

Status writeFileAtomic(const std::string& path, std::span<const uint8_t> bytes) {
  return writeAtomic(path, [&](const std::string& temp) -> Status {
    std::FILE* f = std::fopen(temp.c_str(), "wb");
    if (!f) return makeError("cannot write '" + path + "': " + errnoText(errno));
    const size_t n = bytes.empty() ? 0 : std::fwrite(bytes.data(), 1, bytes.size(), f);
    const bool ok = n == bytes.size() && std::fflush(f) == 0;
    const int err = errno;
    if (std::fclose(f) != 0 || !ok) {
      return makeError("cannot write '" + path + "': " + errnoText(ok ? errno : err));
    }
    return {};
  });
}

}  // namespace detail
}  // namespace penumbra
