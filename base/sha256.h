// SHA-256 (FIPS 180-4 §6.2), streaming. Used for the .tframe checksum and for golden-image digests.
//
// Implements: the hash only; no HMAC, no other SHA-2 variants.
// Written from the standard: big-endian message schedule, 64 rounds, padding with 0x80, zeros and
// the 64-bit message length in bits.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string>

namespace tessera {

class Sha256 {
 public:
  Sha256();
  void update(std::span<const uint8_t> bytes);
  // Pads, returns the digest and resets the object so it can hash a new message.
  std::array<uint8_t, 32> finish();

 private:
  void compress(const uint8_t* block);  // one 64-byte block

  std::array<uint32_t, 8> h_;
  std::array<uint8_t, 64> pending_{};  // a partial block waiting for more input
  size_t pendingSize_ = 0;
  uint64_t totalBytes_ = 0;
};

std::array<uint8_t, 32> sha256(std::span<const uint8_t> bytes);
// Lower-case hex of the digest (64 characters).
std::string sha256Hex(std::span<const uint8_t> bytes);
std::string toHex(std::span<const uint8_t> bytes);

}  // namespace tessera
