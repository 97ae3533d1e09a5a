// Program: a move-only linked GLSL ES 3.00 program with cached uniform locations, whose
// samplers get their texture units at link: each program numbers the samplers it uses from 0,
// so no two roles share a unit by hand and no pass names a unit; passes bind by sampler name.
// ShaderLibrary: composes shaders from the GLSL files embedded at build time (glsl/), adding
// the shared prelude, resolved #include "chunk" lines and generated #defines, compiles them,
// and caches each program by its files and defines. Compile and link errors come back as
// errors that carry the info log with file names and lines of the original files.
#pragma once

#include <map>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <unordered_map>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "gl/handle.h"
#include "penumbra/error.h"

namespace penumbra::gl {

enum class ShaderStage { Vertex, Fragment };
using Defines = std::vector<std::pair<std::string, std::string>>;

// A composed shader: the text handed to GL and the file behind each source-string number.
struct ShaderSource {
  std::string name;  // the top-level file, for messages
  ShaderStage stage = ShaderStage::Vertex;
  std::string text;
  std::vector<std::string> files;  // files[k] is source-string number k in #line directives
};

// Rewrites "0:12(5): error" / "ERROR: 2:7: ..." log lines to "file.glsl:12: error ...".
std::string mapInfoLog(const std::string& log, const std::vector<std::string>& files);

class Program {
 public:
  Program() = default;
  // `feedback`: vertex outputs a transform feedback captures, one buffer each (in order).
  static Result<Program> build(const ShaderSource& vertex, const ShaderSource& fragment,
                               const std::vector<std::string>& feedback = {});

  void use() const;
  // Uniform setters act on this program, which must be in use (call use() first).
  GLint location(std::string_view name) const;
  bool has(std::string_view name) const { return location(name) >= 0; }
  void set(std::string_view name, int v) const;
  void set(std::string_view name, float v) const;
  void set(std::string_view name, const glm::vec2& v) const;
  void set(std::string_view name, const glm::vec3& v) const;
  void set(std::string_view name, const glm::vec4& v) const;
  void set(std::string_view name, const glm::mat3& v) const;
  void set(std::string_view name, const glm::mat4& v) const;
  void set(std::string_view name, std::span<const int> v) const;
  void set(std::string_view name, std::span<const glm::vec2> v) const;
  void set(std::string_view name, std::span<const glm::vec3> v) const;
  void set(std::string_view name, std::span<const glm::vec4> v) const;
  void set(std::string_view name, std::span<const glm::mat3> v) const;
  void set(std::string_view name, std::span<const glm::mat4> v) const;
  GLuint id() const { return handle_.id(); }

  // The unit the sampler `name` got at link, or -1 where this program does not use it (the
  // linker dropped it, or the variant's #defines left it out).
  int unit(std::string_view name) const;
  int samplerCount() const { return static_cast<int>(samplers_.size()); }
  // Puts `texture` (Texture2D, Texture2DArray or TextureCube) on the sampler's unit, if this
  // program uses the sampler: a caller binds every sampler a variant might read.
  template <class Texture>
  void bind(std::string_view sampler, const Texture& texture) const {
    const int u = unit(sampler);
    if (u < 0) return;
    texture.bind(u);
    samplers_[static_cast<size_t>(u)].bound = texture.id();
  }
  // Binds again what bind() last put on this program's units: a pass that returns to a program
  // it set up, after another program's binds took the same units.
  void rebind() const;
  // Leaves the sampler's unit empty: a render target sampled here and drawn into later must
  // not be bound then (a feedback loop to WebGL).
  void release(std::string_view sampler) const;
  // The first sampler this program uses that bind() never filled ("" when all are): a unit
  // left to chance may hold a target being drawn into.
  std::string unboundSampler() const;

 private:
  struct Sampler {
    std::string name;
    GLenum target = 0;  // GL_TEXTURE_2D, GL_TEXTURE_2D_ARRAY or GL_TEXTURE_CUBE_MAP
    mutable GLuint bound = 0;
  };
  // Reads the linked program's samplers and gives each its unit (in name order, so that a
  // program's units do not depend on the driver's listing).
  Status assignUnits(const std::string& what);

  Handle<deleteProgram> handle_;
  mutable std::unordered_map<std::string, GLint> locations_;
  std::vector<Sampler> samplers_;  // samplers_[u]: the sampler on unit u
};

// An error naming the program and both numbers when it needs more texture units than the
// context offers (WebGL2 and OpenGL ES 3.0 guarantee 16).
Status checkSamplerCount(const std::string& program, int samplers, int available);

class ShaderLibrary {
 public:
  // The files embedded from glsl/ at build time.
  ShaderLibrary();
  // Explicit files (tests use this to inject a broken shader).
  explicit ShaderLibrary(std::map<std::string, std::string, std::less<>> files);

  // Defines put in every program before its own (limits shared with the C++ side). Set them
  // before the first program is built.
  void setCommonDefines(Defines defines) { common_ = std::move(defines); }

  Result<ShaderSource> compose(std::string_view file, ShaderStage stage,
                               const Defines& defines) const;
  // The program for (vertex file, fragment file, defines), built on first use and cached.
  Result<Program*> program(std::string_view vertexFile, std::string_view fragmentFile,
                           const Defines& defines = {},
                           const std::vector<std::string>& feedback = {});
  size_t cachedPrograms() const { return cache_.size(); }
  bool hasFile(std::string_view file) const { return files_.count(file) != 0; }

 private:
  Status expand(std::string_view file, std::string& out, std::vector<std::string>& files,
                std::vector<std::string>& stack) const;
  std::map<std::string, std::string, std::less<>> files_;
  std::map<std::string, std::unique_ptr<Program>, std::less<>> cache_;
  Defines common_;
};

}  // namespace penumbra::gl
