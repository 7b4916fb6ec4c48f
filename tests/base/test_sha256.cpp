// SHA-256 against the FIPS 180-2 / NIST CSRC example vectors, and streaming in arbitrary pieces.
#include <gtest/gtest.h>

#include <string>
#include <string_view>
#include <vector>

#include "base/sha256.h"

namespace tessera {
namespace {

std::span<const uint8_t> bytesOf(std::string_view s) { return {reinterpret_cast<const uint8_t*>(s.data()), s.size()}; }

TEST(Sha256, HashesTheEmptyMessage) {
  EXPECT_EQ(sha256Hex({}), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
}

TEST(Sha256, HashesAbcAsInTheStandardsExample) {
  EXPECT_EQ(sha256Hex(bytesOf("abc")), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
}

TEST(Sha256, HashesTheTwoBlock448BitExample) {
  EXPECT_EQ(sha256Hex(bytesOf("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq")),
            "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
}

TEST(Sha256, HashesThe896BitExample) {
  EXPECT_EQ(sha256Hex(bytesOf("abcdefghbcdefghicdefghijdefghijkefghijklfghijklmghijklmnhijklmnoijklmnopjklmnopqklmnopqr"
                              "lmnopqrsmnopqrstnopqrstu")),
            "cf5b16a778af8380036ce59e7b0492370b249b11e8f07a51afac45037afee9d1");
}

TEST(Sha256, HashesOneMillionLetterAs) {
  const std::string a(1000000, 'a');
  EXPECT_EQ(sha256Hex(bytesOf(a)), "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
}

TEST(Sha256, GivesTheSameDigestWhateverTheChunking) {
  // Lengths around the 55 / 56 / 64-byte padding boundaries are where streaming bugs hide.
  for (size_t len : {0u, 1u, 55u, 56u, 57u, 63u, 64u, 65u, 119u, 120u, 128u, 1000u}) {
    std::vector<uint8_t> msg(len);
    for (size_t i = 0; i < len; ++i) msg[i] = uint8_t(i * 131 + 7);
    const auto whole = sha256(msg);
    for (size_t piece : {1u, 3u, 63u, 64u, 65u}) {
      Sha256 s;
      for (size_t at = 0; at < len; at += piece) s.update(std::span(msg).subspan(at, std::min(piece, len - at)));
      EXPECT_EQ(s.finish(), whole) << "length " << len << " in pieces of " << piece;
    }
  }
}

TEST(Sha256, StartsAFreshMessageAfterFinish) {
  Sha256 s;
  s.update(bytesOf("something else"));
  (void)s.finish();
  s.update(bytesOf("abc"));
  EXPECT_EQ(toHex(s.finish()), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
}

TEST(Sha256, AnEmptyPieceWithNoStorageInsideAPartialBlockChangesNothing) {
  // An empty vector's data() may be null; the UBSan build caught memcpy from it (an empty .tab section).
  const std::vector<uint8_t> empty;
  Sha256 s;
  s.update(bytesOf("ab"));
  s.update(std::span<const uint8_t>(empty.data(), empty.size()));
  s.update(std::span<const uint8_t>());
  s.update(bytesOf("c"));
  EXPECT_EQ(toHex(s.finish()), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
}

}  // namespace
}  // namespace tessera
