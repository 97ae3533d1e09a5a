// Internal to the glTF loader: typed, path-reporting access to the glTF JSON (nlohmann). Every
// getter returns a default and records the first error with its JSON path
// ("accessors[3].bufferView: ..."), so the parser reads straight through and checks once.
#pragma once

#include <cmath>
#include <limits>
#include <string>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

namespace penumbra::gltf {

using json = nlohmann::json;

// Every glTF number ends up in a float: a finite double beyond float's range would become
// infinity there, so it is refused here like NaN.
inline bool finiteFloat(double d) {
  return std::isfinite(d) && std::fabs(d) <= static_cast<double>(std::numeric_limits<float>::max());
}

class Parser {
 public:
  bool failed() const { return !error_.empty(); }
  const std::string& error() const { return error_; }
  void fail(const std::string& path, const std::string& message) {
    if (error_.empty()) error_ = path + ": " + message;
  }

  static const json* find(const json& o, const char* key) {
    if (!o.is_object()) return nullptr;
    auto it = o.find(key);
    return it == o.end() ? nullptr : &*it;
  }

  const json* object(const json& o, const char* key, const std::string& path) {
    const json* v = find(o, key);
    if (v && !v->is_object()) {
      fail(path + "." + key, "must be an object");
      return nullptr;
    }
    return v;
  }

  const json* array(const json& o, const char* key, const std::string& path) {
    const json* v = find(o, key);
    if (v && !v->is_array()) {
      fail(path + "." + key, "must be an array");
      return nullptr;
    }
    return v;
  }

  // An integer in [lo, hi]; integral floats (3.0) are accepted since some writers emit them.
  bool asInteger(const json& v, int64_t lo, int64_t hi, int64_t& out) {
    if (v.is_number_unsigned()) {
      const uint64_t u = v.get<uint64_t>();
      if (u > static_cast<uint64_t>(std::numeric_limits<int64_t>::max())) return false;
      out = static_cast<int64_t>(u);
    } else if (v.is_number_integer()) {
      out = v.get<int64_t>();
    } else if (v.is_number_float()) {
      const double d = v.get<double>();
      if (!std::isfinite(d) || d != std::floor(d) || std::fabs(d) > 9.0e15) return false;
      out = static_cast<int64_t>(d);
    } else {
      return false;
    }
    return out >= lo && out <= hi;
  }

  int64_t integer(const json& o, const char* key, const std::string& path, int64_t def,
                  bool required = false, int64_t lo = 0,
                  int64_t hi = std::numeric_limits<int64_t>::max()) {
    const json* v = find(o, key);
    if (!v) {
      if (required) fail(path, std::string("missing required '") + key + "'");
      return def;
    }
    int64_t out = 0;
    if (!asInteger(*v, lo, hi, out)) {
      fail(path + "." + key,
           "must be an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
      return def;
    }
    return out;
  }

  // An index into an array of `count` elements called `arrayName`.
  int index(const json& o, const char* key, const std::string& path, size_t count,
            const char* arrayName, bool required = false) {
    const json* v = find(o, key);
    if (!v) {
      if (required) fail(path, std::string("missing required '") + key + "'");
      return -1;
    }
    return checkIndex(*v, path + "." + key, count, arrayName);
  }

  int checkIndex(const json& v, const std::string& path, size_t count, const char* arrayName) {
    int64_t i = 0;
    if (!asInteger(v, 0, std::numeric_limits<int32_t>::max(), i)) {
      fail(path, "must be a non-negative integer index");
      return -1;
    }
    if (static_cast<uint64_t>(i) >= count) {
      fail(path, "index " + std::to_string(i) + " is out of range (" + arrayName + " count is " +
                     std::to_string(count) + ")");
      return -1;
    }
    return static_cast<int>(i);
  }

  double number(const json& o, const char* key, const std::string& path, double def,
                bool required = false) {
    const json* v = find(o, key);
    if (!v) {
      if (required) fail(path, std::string("missing required '") + key + "'");
      return def;
    }
    if (!v->is_number() || !finiteFloat(v->get<double>())) {
      fail(path + "." + key, "must be a finite number within float range (|x| <= 3.4e38)");
      return def;
    }
    return v->get<double>();
  }

  bool boolean(const json& o, const char* key, const std::string& path, bool def) {
    const json* v = find(o, key);
    if (!v) return def;
    if (!v->is_boolean()) {
      fail(path + "." + key, "must be true or false");
      return def;
    }
    return v->get<bool>();
  }

  std::string string(const json& o, const char* key, const std::string& path,
                     const std::string& def = {}, bool required = false) {
    const json* v = find(o, key);
    if (!v) {
      if (required) fail(path, std::string("missing required '") + key + "'");
      return def;
    }
    if (!v->is_string()) {
      fail(path + "." + key, "must be a string");
      return def;
    }
    return v->get<std::string>();
  }

  // A fixed-length array of finite numbers.
  template <int N>
  bool numbers(const json& o, const char* key, const std::string& path, float* out) {
    const json* v = find(o, key);
    if (!v) return false;
    if (!v->is_array() || v->size() != N) {
      fail(path + "." + key, "must be an array of " + std::to_string(N) + " numbers");
      return false;
    }
    for (int i = 0; i < N; ++i) {
      const json& e = (*v)[static_cast<size_t>(i)];
      if (!e.is_number() || !finiteFloat(e.get<double>())) {
        fail(path + "." + key,
             "must contain only finite numbers within float range (|x| <= 3.4e38)");
        return false;
      }
      out[i] = static_cast<float>(e.get<double>());
    }
    return true;
  }

  template <int N>
  glm::vec<N, float> vec(const json& o, const char* key, const std::string& path,
                         glm::vec<N, float> def) {
    float v[N];
    if (!numbers<N>(o, key, path, v)) return def;
    glm::vec<N, float> out;
    for (int i = 0; i < N; ++i) out[i] = v[i];
    return out;
  }

 private:
  std::string error_;
};

inline size_t arraySize(const json& root, const char* key) {
  const json* v = Parser::find(root, key);
  return v && v->is_array() ? v->size() : 0;
}

inline int componentsOf(const std::string& type) {
  if (type == "SCALAR") return 1;
  if (type == "VEC2") return 2;
  if (type == "VEC3") return 3;
  if (type == "VEC4") return 4;
  if (type == "MAT2") return 4;
  if (type == "MAT3") return 9;
  if (type == "MAT4") return 16;
  return 0;
}

// Iterates an optional top-level array, calling fn(element, path, index).
template <class Fn>
void forEach(Parser& p, const json& root, const char* key, Fn&& fn) {
  const json* arr = p.array(root, key, "glTF");
  if (!arr) return;
  for (size_t i = 0; i < arr->size() && !p.failed(); ++i) {
    const std::string path = std::string(key) + "[" + std::to_string(i) + "]";
    const json& e = (*arr)[i];
    if (!e.is_object()) {
      p.fail(path, "must be an object");
      return;
    }
    fn(e, path, i);
  }
}

// Parses the 'materials' array into doc.materials (gltf_parse_materials.cpp); texture indices are
// checked against textureCount.
struct Document;
struct LoadContext;
void parseMaterials(Parser& p, const json& root, Document& doc, LoadContext& ctx,
                    size_t textureCount);
// Parses the 'animations' array into doc.animations (gltf_animation.cpp).
void parseAnimations(Parser& p, const json& root, Document& doc, size_t accessorCount,
                     size_t nodeCount);

}  // namespace penumbra::gltf
