// golden/manifest.h: the shipped manifest round-trips byte for byte, and every malformed manifest is an
// Error that names the file and the field.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "base/error.h"
#include "golden/manifest.h"

namespace tessera {

namespace {

const std::string kManifest = std::string(TESSERA_SOURCE_DIR) + "/golden/manifest.json";

std::string fileText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// One valid entry with `field` replaced by `value` (raw JSON), or removed when value is empty.
std::string manifestWith(const std::string& field, const std::string& value) {
  const std::pair<const char*, const char*> fields[] = {
      {"attachment", "0"},
      {"command", "\"tessera render blend --size 256x128\""},
      {"file", "\"images/blend.png\""},
      {"format", "\"RGBA8\""},
      {"height", "128"},
      {"image_sha256", "\"6dfc1574bf3870c39f6c50d153e85b71e1ef0cc1d48d9a193a62603f13390751\""},
      {"layer", "0"},
      {"scene", "\"blend\""},
      {"width", "256"}};
  std::string entry;
  bool replaced = false;
  for (const auto& [k, v] : fields) {
    if (k == field) {
      replaced = true;
      if (value.empty()) continue;
    }
    entry += std::string(entry.empty() ? "" : ", ") + "\"" + k + "\": " + (k == field ? value : v);
  }
  if (!replaced && !field.empty()) entry += ", \"" + field + "\": " + value;
  return "{\"tests\": {\"blend\": {" + entry + "}}, \"version\": 1}";
}

// The message of the Error that parsing `text` throws, or "" when it parses.
std::string errorOf(const std::string& text) {
  try {
    golden::parseManifest(text, "dir/manifest.json");
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(GoldenManifest, ReadingAndWritingBackReproducesTheShippedFileByteForByte) {
  const golden::Manifest m = golden::readManifest(kManifest);
  EXPECT_EQ(m.version, 1);
  ASSERT_TRUE(m.tests.count("city_ids.a1"));
  const golden::ManifestEntry& e = m.tests.at("city_ids.a1");
  EXPECT_EQ(e.file, "images/city_ids.a1.exr");
  EXPECT_EQ(e.format, "R32UI");
  EXPECT_EQ(e.attachment, 1u);
  EXPECT_EQ(e.width, 320u);
  EXPECT_EQ(golden::manifestText(m), fileText(kManifest));
}

TEST(GoldenManifest, AValidEntryParsesIntoItsFields) {
  ASSERT_EQ(errorOf(manifestWith("", "")), "");
  const golden::Manifest m = golden::parseManifest(manifestWith("", ""), "m.json");
  const golden::ManifestEntry& e = m.tests.at("blend");
  EXPECT_EQ(e.scene, "blend");
  EXPECT_EQ(e.height, 128u);
  EXPECT_EQ(e.command, "tessera render blend --size 256x128");
}

TEST(GoldenManifest, AMissingFieldIsAnErrorNamingTheFileAndTheField) {
  EXPECT_EQ(errorOf(manifestWith("width", "")), "dir/manifest.json: tests[\"blend\"].width: missing");
  EXPECT_EQ(errorOf("{\"version\": 1}"), "dir/manifest.json: tests: missing");
}

TEST(GoldenManifest, AFieldOfTheWrongTypeIsAnErrorNamingTheField) {
  EXPECT_EQ(errorOf(manifestWith("width", "\"256\"")),
            "dir/manifest.json: tests[\"blend\"].width: expected an unsigned 32-bit integer, found a string");
  EXPECT_EQ(errorOf(manifestWith("layer", "-1")),
            "dir/manifest.json: tests[\"blend\"].layer: expected an unsigned 32-bit integer, found a negative integer");
  EXPECT_EQ(errorOf(manifestWith("scene", "7")),
            "dir/manifest.json: tests[\"blend\"].scene: expected a string, found an unsigned integer");
  EXPECT_EQ(errorOf("{\"tests\": [], \"version\": 1}"), "dir/manifest.json: tests: expected an object, found an array");
  EXPECT_EQ(errorOf("{\"tests\": {\"blend\": 3}, \"version\": 1}"),
            "dir/manifest.json: tests[\"blend\"]: expected an object, found an unsigned integer");
}

TEST(GoldenManifest, ValuesOutsideTheirDomainAreRefused) {
  EXPECT_NE(errorOf(manifestWith("image_sha256", "\"6DFC\""))
                .find("tests[\"blend\"].image_sha256: expected 64 lower-case hex"),
            std::string::npos);
  EXPECT_NE(errorOf(manifestWith("format", "\"RGB9\"")).find("tests[\"blend\"].format: unknown format 'RGB9'"),
            std::string::npos);
  EXPECT_NE(errorOf(manifestWith("width", "0")).find("tests[\"blend\"].width: must be at least 1"), std::string::npos);
  EXPECT_NE(
      errorOf(manifestWith("file", "\"../elsewhere.png\"")).find("tests[\"blend\"].file: '../elsewhere.png' leaves"),
      std::string::npos);
  EXPECT_NE(errorOf(manifestWith("file", "\"/tmp/x.png\"")).find("tests[\"blend\"].file: expected a path relative"),
            std::string::npos);
}

TEST(GoldenManifest, AnUnknownFieldIsRefusedBecauseWritingBackWouldDropIt) {
  EXPECT_EQ(errorOf(manifestWith("comment", "\"x\"")), "dir/manifest.json: tests[\"blend\"].comment: unknown field");
  EXPECT_EQ(errorOf("{\"tests\": {}, \"version\": 1, \"extra\": 0}"), "dir/manifest.json: extra: unknown field");
}

TEST(GoldenManifest, TextThatIsNotAJsonObjectOrAnotherVersionIsAnErrorNamingTheFile) {
  EXPECT_EQ(errorOf("{\"tests\": {").rfind("dir/manifest.json: not JSON: ", 0), 0u);
  EXPECT_EQ(errorOf("[1, 2]"),
            "dir/manifest.json: expected a JSON object with \"version\" and \"tests\", found an array");
  EXPECT_EQ(errorOf("{\"tests\": {}, \"version\": 2}"),
            "dir/manifest.json: version: expected 1 (the only manifest version), found 2");
}

TEST(GoldenManifest, AnUnreadableFileIsAnErrorNamingIt) {
  try {
    golden::readManifest("/nonexistent-dir/manifest.json");
    FAIL() << "read a missing file";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), "/nonexistent-dir/manifest.json: cannot open");
  }
}

TEST(GoldenManifest, ADirectoryWithoutAManifestHoldsAnEmptyOne) {
  const golden::Manifest m = golden::loadManifest("/nonexistent-dir");
  EXPECT_TRUE(m.tests.empty());
  EXPECT_EQ(golden::manifestText(m), "{\n  \"tests\": {},\n  \"version\": 1\n}\n");
}

}  // namespace tessera
