// Accessor reading: strided gathers of any component type, the glTF normalisation rules,
// sparse substitution, and a bounds check of every read against its buffer view.
#include <algorithm>
#include <cstring>

#include "scene/gltf_document.h"

namespace penumbra::gltf {
namespace {

template <class T>
T load(const uint8_t* p) {
  T v;
  std::memcpy(&v, p, sizeof(T));  // glTF data need not be aligned for the host
  return v;
}

float componentToFloat(const uint8_t* p, int componentType, bool normalized) {
  switch (componentType) {
    case kByte: {
      const float v = static_cast<float>(load<int8_t>(p));
      return normalized ? std::max(v / 127.0f, -1.0f) : v;
    }
    case kUnsignedByte: {
      const float v = static_cast<float>(load<uint8_t>(p));
      return normalized ? v / 255.0f : v;
    }
    case kShort: {
      const float v = static_cast<float>(load<int16_t>(p));
      return normalized ? std::max(v / 32767.0f, -1.0f) : v;
    }
    case kUnsignedShort: {
      const float v = static_cast<float>(load<uint16_t>(p));
      return normalized ? v / 65535.0f : v;
    }
    case kUnsignedInt: {
      const double v = static_cast<double>(load<uint32_t>(p));
      return static_cast<float>(normalized ? v / 4294967295.0 : v);
    }
    case kFloat:
      return load<float>(p);
    default:
      return 0.0f;
  }
}

// The byte range [offset, offset + stride * (count - 1) + elementSize) must lie inside `size`.
bool rangeFits(uint64_t offset, uint64_t stride, uint64_t count, uint64_t elementSize,
               uint64_t size) {
  if (count == 0) return offset <= size;
  if (offset > size || elementSize > size - offset) return false;
  if (stride == 0) return true;
  return (count - 1) <= (size - offset - elementSize) / stride;
}

std::string accessorName(int accessor, const std::string& what) {
  return "accessor " + std::to_string(accessor) + " (" + what + ")";
}

// The accessor's elements, tightly packed in their own component type, sparse values applied.
// `outputBytesPerElement` is what the caller will convert each element to, reserved against
// the memory budget before anything is allocated.
Result<std::vector<uint8_t>> readTight(Document& doc, int index, LoadContext& ctx,
                                       const std::string& what, uint64_t outputBytesPerElement) {
  const AccessorDesc& a = doc.accessors[static_cast<size_t>(index)];
  const std::string name = accessorName(index, what);
  const uint64_t compSize = componentSize(a.componentType);
  const uint64_t elementSize = compSize * static_cast<uint64_t>(a.components);
  if (a.count > 0xFFFFFFFFull) {
    return ctx.error(name + " has an absurd count (" + std::to_string(a.count) + ")");
  }
  PN_TRY(ctx.reserve(a.count * outputBytesPerElement, name));

  std::vector<uint8_t> out;
  if (a.bufferView >= 0) {
    auto view = viewBytes(doc, a.bufferView, ctx);
    if (!view.ok()) return view.error();
    const uint64_t stride = view->stride ? view->stride : elementSize;
    if (stride < elementSize) {
      return ctx.error(name + ": byteStride " + std::to_string(stride) +
                       " is smaller than the element size " + std::to_string(elementSize));
    }
    if (!rangeFits(a.byteOffset, stride, a.count, elementSize, view->size)) {
      return ctx.error(name + " is out of range: offset " + std::to_string(a.byteOffset) +
                       ", count " + std::to_string(a.count) + ", stride " + std::to_string(stride) +
                       " reads past the end of bufferView " + std::to_string(a.bufferView) + " (" +
                       std::to_string(view->size) + " bytes)");
    }
    out.resize(static_cast<size_t>(a.count * elementSize));
    const uint8_t* src = view->data + a.byteOffset;
    if (stride == elementSize) {
      if (!out.empty()) std::memcpy(out.data(), src, out.size());
    } else {
      for (uint64_t i = 0; i < a.count; ++i) {
        std::memcpy(out.data() + i * elementSize, src + i * stride, elementSize);
      }
    }
  } else {
    out.assign(static_cast<size_t>(a.count * elementSize), 0);
  }

  if (a.sparse) {
    const SparseDesc& s = *a.sparse;
    const uint64_t indexSize = componentSize(s.indicesComponentType);
    if (indexSize == 0 || s.indicesComponentType == kByte || s.indicesComponentType == kShort ||
        s.indicesComponentType == kFloat) {
      return ctx.error(name + ": sparse indices must be unsigned byte, short or int");
    }
    if (s.count > a.count) {
      return ctx.error(name + ": sparse count " + std::to_string(s.count) +
                       " exceeds the accessor count " + std::to_string(a.count));
    }
    auto iv = viewBytes(doc, s.indicesView, ctx);
    if (!iv.ok()) return iv.error();
    auto vv = viewBytes(doc, s.valuesView, ctx);
    if (!vv.ok()) return vv.error();
    if (!rangeFits(s.indicesOffset, indexSize, s.count, indexSize, iv->size)) {
      return ctx.error(name + ": sparse indices are out of range of bufferView " +
                       std::to_string(s.indicesView));
    }
    if (!rangeFits(s.valuesOffset, elementSize, s.count, elementSize, vv->size)) {
      return ctx.error(name + ": sparse values are out of range of bufferView " +
                       std::to_string(s.valuesView));
    }
    for (uint64_t i = 0; i < s.count; ++i) {
      const uint8_t* ip = iv->data + s.indicesOffset + i * indexSize;
      const uint64_t target = indexSize == 1   ? load<uint8_t>(ip)
                              : indexSize == 2 ? load<uint16_t>(ip)
                                               : load<uint32_t>(ip);
      if (target >= a.count) {
        return ctx.error(name + ": sparse index " + std::to_string(target) +
                         " is out of range of the accessor count " + std::to_string(a.count));
      }
      std::memcpy(out.data() + target * elementSize, vv->data + s.valuesOffset + i * elementSize,
                  elementSize);
    }
  }
  return out;
}

}  // namespace

void convertToFloat(const uint8_t* src, uint64_t stride, uint64_t count, int componentType,
                    int components, bool normalized, float* out) {
  const uint64_t compSize = componentSize(componentType);
  for (uint64_t i = 0; i < count; ++i) {
    const uint8_t* e = src + i * stride;
    for (int c = 0; c < components; ++c) {
      *out++ = componentToFloat(e + static_cast<uint64_t>(c) * compSize, componentType, normalized);
    }
  }
}

Result<std::vector<float>> readFloats(Document& doc, int index, LoadContext& ctx,
                                      const std::string& what) {
  const AccessorDesc& a = doc.accessors[static_cast<size_t>(index)];
  auto tight = readTight(doc, index, ctx, what, 4ull * static_cast<uint64_t>(a.components));
  if (!tight.ok()) return tight.error();
  std::vector<float> out(static_cast<size_t>(a.count) * static_cast<size_t>(a.components));
  const uint64_t elementSize = componentSize(a.componentType) * static_cast<uint64_t>(a.components);
  convertToFloat(tight->data(), elementSize, a.count, a.componentType, a.components, a.normalized,
                 out.data());
  return out;
}

Result<std::vector<uint32_t>> readIndices(Document& doc, int index, LoadContext& ctx,
                                          const std::string& what) {
  const AccessorDesc& a = doc.accessors[static_cast<size_t>(index)];
  if (a.components != 1 || (a.componentType != kUnsignedByte && a.componentType != kUnsignedShort &&
                            a.componentType != kUnsignedInt)) {
    return ctx.error(accessorName(index, what) +
                     " must be SCALAR unsigned byte, short or int to hold indices");
  }
  auto tight = readTight(doc, index, ctx, what, 4);
  if (!tight.ok()) return tight.error();
  std::vector<uint32_t> out(static_cast<size_t>(a.count));
  const uint8_t* src = tight->data();
  for (size_t i = 0; i < out.size(); ++i) {
    switch (a.componentType) {
      case kUnsignedByte:
        out[i] = src[i];
        break;
      case kUnsignedShort:
        out[i] = load<uint16_t>(src + 2 * i);
        break;
      default:
        out[i] = load<uint32_t>(src + 4 * i);
        break;
    }
  }
  return out;
}

}  // namespace penumbra::gltf
