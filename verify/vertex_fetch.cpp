#include "verify/vertex_fetch.h"

#include <cstring>
#include <string>

#include "raster/command_list.h"

namespace tessera::verify {

namespace {

uint32_t loadU32(const uint8_t* p) {
  uint32_t v;
  std::memcpy(&v, p, 4);
  return v;
}

}  // namespace

void fetchVertex(std::span<const uint8_t> vertexBytes, const VertexLayout& layout, uint32_t index, VertexIn& out) {
  for (Vec4& a : out.attr) a = {0.0f, 0.0f, 0.0f, 1.0f};
  for (const VertexAttrib& at : layout.attribs) {
    if (at.components == 0 || at.location >= kMaxAttribs) continue;
    const uint64_t start = uint64_t(index) * layout.stride + at.offset;
    const uint64_t end = start + 4ull * at.components;
    if (end > vertexBytes.size())
      throw Error("visibility: vertex " + std::to_string(index) + " attribute " + std::to_string(at.location) +
                  " reads past the vertex buffer");
    Vec4& v = out.attr[at.location];
    for (int k = 0; k < at.components && k < 4; ++k) {
      const uint8_t* p = vertexBytes.data() + start + 4 * uint64_t(k);
      if (at.type == AttribType::F32) {
        std::memcpy(&v[size_t(k)], p, 4);
      } else {
        v[size_t(k)] = float(loadU32(p));
      }
    }
  }
  out.vertexId = index;
}

uint32_t readIndex(std::span<const uint8_t> indexBytes, IndexType type, uint64_t i) {
  const uint64_t size = type == IndexType::U16 ? 2 : 4;
  if ((i + 1) * size > indexBytes.size())
    throw Error("visibility: index " + std::to_string(i) + " lies outside the index buffer");
  if (type == IndexType::U16) {
    uint16_t v;
    std::memcpy(&v, indexBytes.data() + i * 2, 2);
    return v;
  }
  return loadU32(indexBytes.data() + i * 4);
}

}  // namespace tessera::verify
