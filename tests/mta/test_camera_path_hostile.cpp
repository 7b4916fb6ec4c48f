// Hostile camera path files (docs/mta-camera-path.md): every refusal is an Error naming the file and the
// line; reading is bounded in bytes per line and frames per path; the writer refuses what the reader
// would, so that a written path always reads back.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <string>

#include "base/error.h"
#include "base/resource_limits.h"
#include "mta/camera_path.h"
#include "mta_test_scene.h"

namespace tessera::mta {
namespace {

using testing::TempFile;
using testing::writeText;

const std::string kHeader = "tessera-camera-path 1\n";

std::string readError(const std::string& path) {
  try {
    readPathFile(path);
  } catch (const Error& e) {
    return e.what();
  }
  return "(no Error thrown)";
}

// Reads `text` as a path file and expects an Error at `line` containing `reason`.
void expectPathRefused(const std::string& text, size_t line, const std::string& reason) {
  TempFile f("bad.path");
  writeText(f.path, text);
  const std::string m = readError(f.path);
  EXPECT_EQ(m.rfind(f.path + ":" + std::to_string(line) + ": ", 0), 0u) << m;
  EXPECT_NE(m.find(reason), std::string::npos) << m;
}

TEST(CameraPathFile, ACoordinateAbove1e15IsRefused) {
  // 1e16 is finite, but eye, target and the view matrix would leave float range together with a narrow
  // field of view.
  expectPathRefused(kHeader + "0 0 0 1e16 0 0\n", 2, "'1e16' exceeds 1e+15 in magnitude");
  expectPathRefused(kHeader + "-1e300 0 0 1 0 0\n", 2, "'-1e300' exceeds 1e+15");
  expectPathRefused(kHeader + "near 2e15\n0 0 0 1 0 0\n", 2, "'2e15' exceeds");
  expectPathRefused(kHeader + "up 0 1e20 0\n0 0 0 1 0 0\n", 2, "'1e20' exceeds");
}

TEST(CameraPathFile, ATanHalfFovOutsideItsRangeIsRefused) {
  expectPathRefused(kHeader + "tan_half_fov 1e-7\n0 0 0 1 0 0\n", 2, "tan_half_fov '1e-7': must be in [1e-06, 1e+06]");
  expectPathRefused(kHeader + "tan_half_fov 2e6\n0 0 0 1 0 0\n", 2, "must be in [1e-06, 1e+06]");
  // fov in (0, 180) but so narrow that tan(fov / 2) is below 1e-6.
  expectPathRefused(kHeader + "fov 1e-5\n0 0 0 1 0 0\n", 2, "fov '1e-5': tan(fov / 2) = ");
}

TEST(CameraPathFile, MoreThanAMillionFramesAreRefused) {
  ASSERT_EQ(kMaxPathFrames, 1000000u);
  std::string text = kHeader;
  text.reserve(kHeader.size() + 12 * (size_t(kMaxPathFrames) + 1));
  for (uint32_t i = 0; i <= kMaxPathFrames; ++i) text += "0 0 0 1 0 0\n";
  expectPathRefused(text, size_t(kMaxPathFrames) + 2, "more than 1000000 frames");
}

TEST(CameraPathFile, ALineLongerThan4096BytesIsRefused) {
  ASSERT_EQ(kMaxPathLineBytes, 4096u);
  // A complete line (even a comment) of 4097 bytes.
  expectPathRefused(kHeader + "#" + std::string(4096, 'x') + "\n0 0 0 1 0 0\n", 2,
                    "the line is 4097 bytes long, over the limit of 4096");
  // 4096 bytes are accepted.
  TempFile ok("ok.path");
  writeText(ok.path, kHeader + "#" + std::string(4095, 'x') + "\n0 0 0 1 0 0\n");
  EXPECT_EQ(readPathFile(ok.path).frames.size(), 1u);
  // A line without an end is refused once it passes the limit, without reading the rest.
  expectPathRefused(kHeader + "0 0 0 1 0 0\n" + std::string(200000, '7'), 3, "the line is longer than 4096 bytes");
}

TEST(CameraPathFile, DevZeroIsRefusedAtItsFirstLine) {
  // An endless input: reading stops at the line limit, without trying to hold the whole "file".
  const std::string m = readError("/dev/zero");
  EXPECT_EQ(m.rfind("/dev/zero:1: the line is longer than 4096 bytes", 0), 0u) << m;
}

TEST(CameraPathFile, BinaryGarbageIsRefused) {
  expectPathRefused(kHeader + "0 0 0 1 0 0\n" + std::string("\x00\x01\x02 7", 5) + "\n", 3,
                    "byte 0x00 at column 1 is a control character (a camera path file is text)");
  // A PNG file given as a path: 0x89 cannot start a UTF-8 character.
  expectPathRefused("\x89PNG\r\n\x1a\n", 1, "invalid UTF-8 at column 1");
  expectPathRefused(kHeader + "0 0 0 1 0 0 \x7f\n", 2, "byte 0x7f at column 13 is a control character");
}

TEST(CameraPathFile, InvalidUtf8IsRefusedEvenInANameOrAComment) {
  // The name goes into frames.json, which must be UTF-8.
  expectPathRefused(kHeader + "name caf\xe9\n0 0 0 1 0 0\n", 2, "invalid UTF-8 at column 9");
  expectPathRefused(kHeader + "# \xed\xa0\x80 a surrogate\n0 0 0 1 0 0\n", 2, "invalid UTF-8 at column 3");
  expectPathRefused(kHeader + "# \xc0\xaf overlong\n0 0 0 1 0 0\n", 2, "invalid UTF-8 at column 3");
  TempFile ok("ok.path");
  writeText(ok.path, kHeader + "name caf\xc3\xa9 \xe2\x86\x92 \xf0\x9f\x9a\x86\n0 0 0 1 0 0\n");
  EXPECT_EQ(readPathFile(ok.path).name, "caf\xc3\xa9 \xe2\x86\x92 \xf0\x9f\x9a\x86");
}

TEST(CameraPathFile, ADirectoryIsRefused) {
  const std::string dir = std::filesystem::temp_directory_path().string();
  const std::string m = readError(dir);
  EXPECT_NE(m.find(dir + ": is a directory"), std::string::npos) << m;
}

TEST(CameraPathFile, ALongTokenIsQuotedShortInTheMessage) {
  TempFile f("long.path");
  writeText(f.path, kHeader + "0 0 0 1 0 " + std::string(3000, 'x') + "\n");
  const std::string m = readError(f.path);
  EXPECT_NE(m.find("'" + std::string(40, 'x') + "...' is not a number"), std::string::npos) << m;
  EXPECT_LT(m.size(), f.path.size() + 120) << m;
}

TEST(CameraPathFile, AFileNameThatIsNotUtf8GivesANameThatIs) {
  const std::string dir = std::filesystem::temp_directory_path().string();
  const std::string path = dir + "/tessera_mta_" + std::to_string(::getpid()) + "_caf\xe9.path";
  writeText(path, kHeader + "0 0 0 1 0 0\n");
  const CameraPath p = readPathFile(path);
  std::filesystem::remove(path);
  EXPECT_EQ(p.name, "tessera_mta_" + std::to_string(::getpid()) + "_caf?");
}

std::string writeError(const CameraPath& p) {
  TempFile f("w.path");
  try {
    writePathFile(p, f.path);
  } catch (const Error& e) {
    return e.what();
  }
  return "(no Error thrown)";
}

TEST(CameraPathFile, TheWriterRefusesWhatTheReaderWouldRefuse) {
  const CameraPath base = builtinPath("orbit", {0, 0, 0, 100, 10, 100}, 3);
  CameraPath p = base;
  p.frames[1].farPlane = 1e16;
  EXPECT_NE(writeError(p).find("frame 1: camera far: exceeds 1e+15"), std::string::npos) << writeError(p);
  p = base;
  p.frames[2].tanHalfFovX = 1e-9;
  EXPECT_NE(writeError(p).find("frame 2: camera tan_half_fov: 1e-09 is outside"), std::string::npos) << writeError(p);
  p = base;
  p.name = "caf\xe9";
  EXPECT_NE(writeError(p).find("not UTF-8"), std::string::npos) << writeError(p);
  p.name = std::string(kMaxPathLineBytes, 'n');
  EXPECT_NE(writeError(p).find("its line would exceed 4096 bytes"), std::string::npos) << writeError(p);
  // The longest name that fits its line reads back.
  p.name = std::string(kMaxPathLineBytes - 5, 'n');
  TempFile f("longest.path");
  writePathFile(p, f.path);
  EXPECT_EQ(readPathFile(f.path).name, p.name);
}

TEST(CameraPathFile, ABuiltinPathOfMoreThanAMillionFramesIsRefused) {
  try {
    builtinPath("orbit", {0, 0, 0, 1, 1, 1}, kMaxPathFrames + 1);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("1000001 frames requested, at most 1000000"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace tessera::mta
