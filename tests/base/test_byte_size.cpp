// parseByteSize: the byte sizes of --memory-budget and --budget, exact, overflow-checked, strict.
#include <gtest/gtest.h>

#include <string>

#include "base/byte_size.h"
#include "base/error.h"

namespace tessera {
namespace {

std::string messageOf(std::string_view text) {
  try {
    parseByteSize(text, "--memory-budget");
  } catch (const Error& e) {
    return e.what();
  }
  return "(accepted)";
}

TEST(ByteSize, BinaryUnitsMultiplyExactly) {
  EXPECT_EQ(parseByteSize("4096", "x"), 4096u);
  EXPECT_EQ(parseByteSize("300B", "x"), 300u);
  EXPECT_EQ(parseByteSize("512MiB", "x"), 512u << 20);
  EXPECT_EQ(parseByteSize("8GiB", "x"), uint64_t(8) << 30);
  EXPECT_EQ(parseByteSize("16TiB", "x"), uint64_t(16) << 40);
  EXPECT_EQ(parseByteSize("3k", "x"), 3072u);
  EXPECT_EQ(parseByteSize("2G", "x"), uint64_t(2) << 30);
  // 2^64 - 1 written out: exact, where a trip through double would round it up to 2^64.
  EXPECT_EQ(parseByteSize("18446744073709551615", "x"), UINT64_MAX);
  EXPECT_EQ(parseByteSize("0", "x"), 0u);
}

TEST(ByteSize, FractionsAndExponentsAreTruncatedToWholeBytes) {
  EXPECT_EQ(parseByteSize("1.5KiB", "x"), 1536u);
  EXPECT_EQ(parseByteSize("0.5MiB", "x"), 512u * 1024);
  EXPECT_EQ(parseByteSize("1e3", "x"), 1000u);
  EXPECT_EQ(parseByteSize("2.7", "x"), 2u);
}

TEST(ByteSize, SizesThatDoNotFitIn64BitsAreRefusedNotWrapped) {
  // 2^64 bytes = 16 EiB = 16777216 TiB: one past the end, in each form.
  EXPECT_NE(messageOf("18446744073709551616").find("more than 2^64 - 1 bytes"), std::string::npos);
  EXPECT_NE(messageOf("16777216TiB").find("more than 2^64 - 1 bytes"), std::string::npos);
  EXPECT_NE(messageOf("16777216.0TiB").find("more than 2^64 - 1 bytes"), std::string::npos);
  EXPECT_NE(messageOf("1e17GiB").find("more than 2^64 - 1 bytes"), std::string::npos);
  EXPECT_EQ(parseByteSize("16777215TiB", "x"), uint64_t(16777215) << 40);
}

TEST(ByteSize, AnythingButANumberAndAUnitIsAClearError) {
  for (const char* bad : {"", "MiB", "-1", "-0", "nan", "inf", "+5", " 5", "e5"})
    EXPECT_NE(messageOf(bad).find("not a byte size"), std::string::npos) << bad << ": " << messageOf(bad);
  for (const char* bad : {"5 MiB", "0x10", "1.5.5", "5MiB "})
    EXPECT_NE(messageOf(bad).find("unknown unit"), std::string::npos) << bad << ": " << messageOf(bad);
  EXPECT_EQ(messageOf("8GB"), "--memory-budget '8GB': unknown unit 'GB' (use B, KiB, MiB, GiB or TiB)");
  EXPECT_EQ(messageOf("3furlongs"),
            "--memory-budget '3furlongs': unknown unit 'furlongs' (use B, KiB, MiB, GiB or TiB)");
}

TEST(ByteSize, UnitsAreRecognisedOnTheirOwn) {
  for (const char* u : {"", "B", "KiB", "k", "MiB", "M", "GiB", "G", "TiB", "T"}) EXPECT_TRUE(isByteUnit(u)) << u;
  for (const char* u : {"KB", "blocks", "ms", "b", "mib"}) EXPECT_FALSE(isByteUnit(u)) << u;
}

}  // namespace
}  // namespace tessera
