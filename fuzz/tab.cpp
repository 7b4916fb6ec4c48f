// Fuzz target `tab`: the batched scene file reader and validator (batching/tab_file.h).
//
// The input is a .tab file, written to the scratch directory because readTabFile takes a path. Before that,
// the fields a mutation cannot keep consistent by chance are recomputed: the file size (bytes 24..31), the
// SHA-256 of every section the section table places inside the input (32 + 56 k + 24..), and the header's
// SHA-256 (424..455). So mutations of counts, indices, enums, floats and cross-references reach the
// decoder and the validator instead of stopping at a checksum; the section table itself is left as
// mutated, so its own checks run too.
// Property: a file that is accepted is canonical. Every field is stored, sections follow each other
// without gaps and reserved fields are 0, so encodeTabFile of the scene read must give back exactly the
// (repaired) input bytes.
// Does not record or render frames (batching/tab_record.h): too slow per input.
#include <array>
#include <cstdint>
#include <cstring>
#include <vector>

#include "base/error.h"
#include "base/sha256.h"
#include "batching/tab_file.h"
#include "fuzz/fuzz_support.h"

namespace {

using namespace tessera;
using namespace tessera::batching;

constexpr uint8_t kMagic[8] = {'T', 'E', 'S', 'S', 'T', 'A', 'B', 0x1a};

void fixChecksums(std::vector<uint8_t>& b) {
  if (b.size() < kTabHeaderSize || std::memcmp(b.data(), kMagic, 8) != 0) return;
  const uint64_t size = b.size();
  std::memcpy(b.data() + 24, &size, 8);  // the format is little-endian, as is every target we run on
  for (uint32_t k = 0; k < kTabSectionCount; ++k) {
    uint64_t offset = 0, length = 0;
    std::memcpy(&offset, b.data() + 32 + 56 * k + 8, 8);
    std::memcpy(&length, b.data() + 32 + 56 * k + 16, 8);
    if (offset > size || length > size - offset) continue;
    const auto sha = sha256(std::span<const uint8_t>(b.data() + offset, size_t(length)));
    std::memcpy(b.data() + 32 + 56 * k + 24, sha.data(), 32);
  }
  const auto sha = sha256(std::span<const uint8_t>(b.data(), kTabHeaderSize - 32));
  std::memcpy(b.data() + kTabHeaderSize - 32, sha.data(), 32);
}

void run(const uint8_t* data, size_t size) {
  std::vector<uint8_t> bytes(data, data + size);
  fixChecksums(bytes);
  const std::string path = fuzz::writeScratch("input.tab", bytes);
  try {
    const TabScene scene = readTabFile(path);
    if (encodeTabFile(scene) != bytes)
      fuzz::propertyViolated("tab", "an accepted file does not re-encode to the same bytes");
    if (fuzz::verbose())
      fuzz::note("tab", "accepted: " + std::to_string(scene.textures.size()) + " texture(s), " +
                            std::to_string(scene.batches.size()) + " output batch(es), " +
                            std::to_string(scene.vertices.size()) + " vertices");
  } catch (const Error& e) {
    fuzz::note("tab", e.what());
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const fuzz::DescriptorCheck descriptors;
  run(data, size);
  descriptors.expectNoLeak("tab");
  return 0;
}
