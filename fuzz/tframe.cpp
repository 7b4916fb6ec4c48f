// Fuzz target `tframe`: the .tframe decoder (raster/serialize.h), the semantic validator
// (raster/validate.h) and, on lists that validate, the counters (raster/counters.h).
//
// The input is a .tframe file. Its SHA-256 field (bytes 40..71, over every byte after the 72-byte header)
// is recomputed before decoding, so that mutations reach the command decoder instead of stopping at the
// checksum; when the input's own checksum was wrong, the unmodified input is decoded too and must be
// rejected. A decoded list must encode back to exactly the decoded bytes (docs/tframe-format.md: "encoding
// a decoded file gives back the same bytes"); anything else is reported as a finding.
// Does not run the renderer: a frame can legitimately take seconds to draw, which would hide everything
// else behind timeouts.
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "base/error.h"
#include "base/sha256.h"
#include "fuzz/fuzz_support.h"
#include "raster/counters.h"
#include "raster/serialize.h"
#include "raster/validate.h"

namespace {

constexpr size_t kChecksumOffset = 40;

// Returns true when the checksum had to be changed.
bool fixChecksum(std::vector<uint8_t>& bytes) {
  using namespace tessera;
  if (bytes.size() < kFrameHeaderSize || std::memcmp(bytes.data(), kFrameMagic, 8) != 0) return false;
  const auto digest = sha256(std::span<const uint8_t>(bytes).subspan(kFrameHeaderSize));
  if (std::memcmp(bytes.data() + kChecksumOffset, digest.data(), 32) == 0) return false;
  std::memcpy(bytes.data() + kChecksumOffset, digest.data(), 32);
  return true;
}

void run(const uint8_t* data, size_t size) {
  using namespace tessera;
  std::vector<uint8_t> bytes(data, data + size);
  if (fixChecksum(bytes)) {
    try {
      decodeFrame(std::span<const uint8_t>(data, size), "input.tframe");
      fuzz::propertyViolated("tframe", "a frame with a wrong checksum was accepted");
    } catch (const Error&) {
    }
  }
  CommandList list;
  try {
    list = decodeFrame(bytes, "input.tframe");
  } catch (const Error& e) {
    fuzz::note("tframe", e.what());
    return;
  }
  if (encodeFrame(list) != bytes) fuzz::propertyViolated("tframe", "decode then encode does not give back the input");
  const std::vector<Diagnostic> diagnostics = validate(list);
  if (!diagnostics.empty()) {
    if (fuzz::verbose())
      fuzz::note("tframe", "decoded, " + std::to_string(diagnostics.size()) + " problem(s), first: command " +
                               std::to_string(diagnostics[0].command) + ": " + diagnostics[0].message);
    return;
  }
  const FrameCounters counters = countCommands(list);
  const std::string json = toJson(counters).dump();
  if (fuzz::verbose()) fuzz::note("tframe", "valid, counters " + json.substr(0, 120) + "...");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const tessera::fuzz::DescriptorCheck descriptors;
  run(data, size);
  descriptors.expectNoLeak("tframe");
  return 0;
}
