#include "rtta/record_buffer.h"

#include <fmt/format.h>

#include "base/error.h"

namespace tessera::rtta {

std::vector<float> encodeRecordBuffer(std::span<const Record> records) {
  std::vector<float> texels;
  texels.reserve(records.size() * 8);
  for (size_t i = 0; i < records.size(); ++i) {
    const Record& r = records[i];
    if (r.id != i) throw Error(fmt::format("record {} has id {}: the record buffer is indexed by id", i, r.id));
    const float layer = r.layer >= 0 ? float(r.layer) : -1.0f;
    texels.insert(texels.end(), {r.T.a, r.T.b, r.T.c, r.T.d, r.T.tx, r.T.ty, layer, 0.0f});
  }
  return texels;
}

}  // namespace tessera::rtta
