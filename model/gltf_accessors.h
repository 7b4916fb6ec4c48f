// Internal to tessera_model: range-checked reading of glTF 2.0 accessors from a tinygltf::Model
// (load_gltf.cpp). Every bufferView, buffer, stride, sparse index and element range is checked, in
// 128-bit arithmetic, before anything is allocated or read, so a `count` of 2^32 or 2^62 is an Error
// naming the file and the JSON pointer, not an allocation. check() does that alone, so a loader can
// validate every accessor of a mesh and count its triangles before it reads any of them.
#pragma once

#include <tiny_gltf.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <optional>
#include <string>
#include <vector>

#include "base/error.h"
#include "base/resource_limits.h"

namespace tessera::model::detail::gltf {

inline uint32_t le32(const uint8_t* p) {
  return uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24;
}

[[noreturn]] inline void fail(const std::string& path, const std::string& pointer, const std::string& why) {
  throw Error(path + ": " + pointer + ": " + why);
}

inline int componentCount(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR:
      return 1;
    case TINYGLTF_TYPE_VEC2:
      return 2;
    case TINYGLTF_TYPE_VEC3:
      return 3;
    case TINYGLTF_TYPE_VEC4:
      return 4;
    default:
      return 0;
  }
}
inline int componentBytes(int ct) {
  switch (ct) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      return 2;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
      return 4;
    default:
      return 0;
  }
}

// One component at p as float: floats bit-exactly, normalized integers per glTF 2.0 §3.11,
// unnormalized integers by value (KHR_mesh_quantization).
inline float readComponent(const uint8_t* p, int ct, bool normalized) {
  switch (ct) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT: {
      float f;
      std::memcpy(&f, p, 4);
      return f;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return normalized ? float(p[0]) / 255.0f : float(p[0]);
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
      const int8_t v = int8_t(p[0]);
      return normalized ? std::max(float(v) / 127.0f, -1.0f) : float(v);
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      uint16_t v;
      std::memcpy(&v, p, 2);
      return normalized ? float(v) / 65535.0f : float(v);
    }
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
      int16_t v;
      std::memcpy(&v, p, 2);
      return normalized ? std::max(float(v) / 32767.0f, -1.0f) : float(v);
    }
    default: {  // UNSIGNED_INT
      uint32_t v;
      std::memcpy(&v, p, 4);
      return float(v);
    }
  }
}

class Reader {
 public:
  Reader(const std::string& path, const tinygltf::Model& m) : path_(path), m_(m) {}

  // Validates that `count` elements of `elemBytes` at byteOffset with the view's stride lie inside
  // the view and the view inside its buffer; returns the first element and the stride.
  std::pair<const uint8_t*, size_t> locate(const std::string& ptr, int view, size_t byteOffset, size_t count,
                                           size_t elemBytes, bool allowStride) const {
    if (view < 0 || size_t(view) >= m_.bufferViews.size())
      fail(path_, ptr + "/bufferView", std::to_string(view) + " is not a bufferView index");
    const tinygltf::BufferView& bv = m_.bufferViews[size_t(view)];
    const std::string vptr = "/bufferViews/" + std::to_string(view);
    if (bv.buffer < 0 || size_t(bv.buffer) >= m_.buffers.size())
      fail(path_, vptr + "/buffer", std::to_string(bv.buffer) + " is not a buffer index");
    const auto& data = m_.buffers[size_t(bv.buffer)].data;
    if (bv.byteOffset > data.size() || bv.byteLength > data.size() - bv.byteOffset)
      fail(path_, vptr,
           "byte range [" + std::to_string(bv.byteOffset) + ", +" + std::to_string(bv.byteLength) +
               ") lies outside buffer " + std::to_string(bv.buffer) + " (" + std::to_string(data.size()) + " bytes)");
    const size_t stride = allowStride && bv.byteStride ? bv.byteStride : elemBytes;
    if (stride < elemBytes)
      fail(path_, vptr + "/byteStride", "smaller than the element (" + std::to_string(elemBytes) + " bytes)");
    if (count) {
      const unsigned __int128 end = (unsigned __int128)byteOffset + (unsigned __int128)stride * (count - 1) + elemBytes;
      if (end > bv.byteLength)
        fail(path_, ptr,
             std::to_string(count) + " elements from byteOffset " + std::to_string(byteOffset) +
                 " overrun bufferView " + std::to_string(view) + " (" + std::to_string(bv.byteLength) + " bytes)");
    }
    // With no element, byteOffset is never added: it may be anything, and a pointer past the buffer is UB.
    return {data.data() + bv.byteOffset + (count ? byteOffset : 0), stride};
  }

  const tinygltf::Accessor& accessor(int index, const std::string& from) const {
    if (index < 0 || size_t(index) >= m_.accessors.size())
      fail(path_, from, std::to_string(index) + " is not an accessor index");
    return m_.accessors[size_t(index)];
  }

  // Checks that accessor `index` can be read as `comps` components per element (kIndices: as indices):
  // its type and component type, and the byte range of its elements, sparse indices and sparse values
  // inside their bufferViews and buffers. Reads and allocates nothing. Returns its element count.
  static constexpr int kIndices = 0;
  size_t check(int index, int comps, const std::string& from) const {
    const tinygltf::Accessor& a = accessor(index, from);
    const std::string ptr = "/accessors/" + std::to_string(index);
    size_t elemBytes = 0;
    if (comps == kIndices) {
      if (a.type != TINYGLTF_TYPE_SCALAR) fail(path_, ptr + "/type", "indices must be SCALAR");
      const int ct = a.componentType;
      if (ct != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && ct != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
          ct != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
        fail(path_, ptr + "/componentType", "indices must be an unsigned integer type");
      elemBytes = size_t(componentBytes(ct));
    } else {
      if (componentCount(a.type) != comps)
        fail(path_, ptr + "/type", "expected " + std::to_string(comps) + " components for " + from);
      const int cb = componentBytes(a.componentType);
      if (!cb) fail(path_, ptr + "/componentType", std::to_string(a.componentType) + " is not a component type");
      elemBytes = size_t(cb) * size_t(comps);
    }
    if (a.bufferView >= 0) locate(ptr, a.bufferView, a.byteOffset, a.count, elemBytes, true);
    if (a.sparse.isSparse) {
      sparseIndexRange(a, ptr);
      locate(ptr + "/sparse/values", a.sparse.values.bufferView, a.sparse.values.byteOffset, size_t(a.sparse.count),
             elemBytes, false);
    }
    return a.count;
  }

  // Every component of accessor `index` as float, `count * comps` values; the accessor's type must
  // have `comps` components. Sparse substitution applied.
  std::vector<float> floats(int index, int comps, const std::string& from) const {
    const size_t count = check(index, comps, from);  // before the allocation
    const tinygltf::Accessor& a = m_.accessors[size_t(index)];
    const std::string ptr = "/accessors/" + std::to_string(index);
    const int cb = componentBytes(a.componentType);
    const std::optional<uint64_t> values = checkedMul(count, uint64_t(comps));
    if (!values || *values > std::vector<float>().max_size())
      fail(path_, ptr + "/count", std::to_string(count) + " elements do not fit in memory");
    std::vector<float> out(size_t(*values), 0.0f);
    if (a.bufferView >= 0) {
      auto [p, stride] = locate(ptr, a.bufferView, a.byteOffset, a.count, size_t(cb) * comps, true);
      for (size_t i = 0; i < a.count; ++i)
        for (int c = 0; c < comps; ++c)
          out[i * comps + c] = readComponent(p + i * stride + c * cb, a.componentType, a.normalized);
    }
    if (a.sparse.isSparse) {
      const std::vector<uint32_t> which = sparseIndices(a, ptr);
      auto [vp, vstride] = locate(ptr + "/sparse/values", a.sparse.values.bufferView, a.sparse.values.byteOffset,
                                  which.size(), size_t(cb) * comps, false);
      for (size_t k = 0; k < which.size(); ++k)
        for (int c = 0; c < comps; ++c)
          out[size_t(which[k]) * comps + c] = readComponent(vp + k * vstride + c * cb, a.componentType, a.normalized);
    }
    return out;
  }

  std::vector<uint32_t> indices(int index, const std::string& from) const {
    const size_t count = check(index, kIndices, from);  // before the allocation
    const tinygltf::Accessor& a = m_.accessors[size_t(index)];
    const std::string ptr = "/accessors/" + std::to_string(index);
    const int ct = a.componentType;
    if (count > std::vector<uint32_t>().max_size())
      fail(path_, ptr + "/count", std::to_string(count) + " elements do not fit in memory");
    std::vector<uint32_t> out(count, 0);
    if (a.bufferView >= 0) {
      auto [p, stride] = locate(ptr, a.bufferView, a.byteOffset, a.count, size_t(componentBytes(ct)), true);
      for (size_t i = 0; i < a.count; ++i) out[i] = readUint(p + i * stride, ct);
    }
    if (a.sparse.isSparse) {
      const std::vector<uint32_t> which = sparseIndices(a, ptr);
      auto [vp, vstride] = locate(ptr + "/sparse/values", a.sparse.values.bufferView, a.sparse.values.byteOffset,
                                  which.size(), size_t(componentBytes(ct)), false);
      for (size_t k = 0; k < which.size(); ++k) out[which[k]] = readUint(vp + k * vstride, ct);
    }
    return out;
  }

  size_t count(int index, const std::string& from) const { return accessor(index, from).count; }

 private:
  static uint32_t readUint(const uint8_t* p, int ct) {
    if (ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE) return p[0];
    if (ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT) return uint32_t(p[0]) | uint32_t(p[1]) << 8;
    return le32(p);
  }
  // The sparse indices' component type, count and byte range; returns their first byte and stride.
  std::pair<const uint8_t*, size_t> sparseIndexRange(const tinygltf::Accessor& a, const std::string& ptr) const {
    const int ct = a.sparse.indices.componentType;
    const int cb = componentBytes(ct);
    if (!cb || ct == TINYGLTF_COMPONENT_TYPE_FLOAT || ct == TINYGLTF_COMPONENT_TYPE_BYTE ||
        ct == TINYGLTF_COMPONENT_TYPE_SHORT)
      fail(path_, ptr + "/sparse/indices/componentType", "must be an unsigned integer type");
    if (a.sparse.count < 0) fail(path_, ptr + "/sparse/count", "negative");
    return locate(ptr + "/sparse/indices", a.sparse.indices.bufferView, a.sparse.indices.byteOffset,
                  size_t(a.sparse.count), size_t(cb), false);
  }
  std::vector<uint32_t> sparseIndices(const tinygltf::Accessor& a, const std::string& ptr) const {
    const int ct = a.sparse.indices.componentType;
    auto [p, stride] = sparseIndexRange(a, ptr);  // before the allocation
    std::vector<uint32_t> which(size_t(a.sparse.count));
    for (size_t k = 0; k < which.size(); ++k) {
      which[k] = readUint(p + k * stride, ct);
      if (which[k] >= a.count)
        fail(path_, ptr + "/sparse/indices",
             "index " + std::to_string(which[k]) + " >= count " + std::to_string(a.count));
    }
    return which;
  }
  const std::string& path_;
  const tinygltf::Model& m_;
};

}  // namespace tessera::model::detail::gltf
