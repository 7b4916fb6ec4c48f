// The expectations file (verify/expectations.h): validation with clear errors, matching by
// implementation / version / condition / frame, and re-labelling only the pixels the named draw writes.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>

#include "base/sha256.h"
#include "raster/cpu_backend.h"
#include "raster/image_io.h"
#include "raster/serialize.h"
#include "raster/validate.h"
#include "tools/scenes/scenes.h"
#include "verify/crosscheck.h"
#include "verify/expectations.h"

namespace tessera::verify {

namespace {

nlohmann::json entry() {
  return {{"id", "e1"},
          {"implementation", "llvmpipe"},
          {"versions", "22\\.3\\.[0-9]+"},
          {"condition", {{"strict", false}, {"lp_threads", ">=1"}}},
          {"frame", "wrap_filter"},
          {"draw", 2},
          {"pixels", 3364},
          {"reason", "test"},
          {"reproducer", "tests/expectations/repro/e1.tframe"}};
}

nlohmann::json doc(const nlohmann::json& e) { return {{"schema", 1}, {"entries", {e}}}; }

std::string errorOf(const nlohmann::json& d) {
  try {
    parseExpectations(d, "x.json");
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

RunCondition llvmpipe(int threads, bool strict = false) { return {"llvmpipe", "22.3.6", strict, threads}; }

// Renders like the oracle, but paints every pixel that draw `bad` covers white (as llvmpipe did),
// and optionally one more pixel elsewhere.
OtherBackend whiteDraw(size_t bad, bool alsoElsewhere) {
  return {"fake", [=](const CommandList& l, std::string_view name, double& ms) {
            ms = 0;
            size_t draws = 0, command = l.commands().size();
            for (size_t i = 0; i < l.commands().size(); ++i)
              if (std::holds_alternative<Draw>(l.commands()[i]) && draws++ == bad) command = i;
            CpuBackend full;
            full.execute(l, name);
            std::vector<std::vector<uint8_t>> out;
            for (const PresentedImage& p : full.presented()) out.push_back(imagePixels(*full.texture(p.texture), p.level, p.layer));
            if (command < l.commands().size()) {
              CommandList before = l, after = l;
              before.truncate(command);
              after.truncate(command + 1);
              CpuBackend b, a;
              b.execute(before, name);
              a.execute(after, name);
              const auto pb = imagePixels(*b.texture(b.presented()[0].texture), 0, 0);
              const auto pa = imagePixels(*a.texture(a.presented()[0].texture), 0, 0);
              for (size_t p = 0; p < pa.size(); p += 4)
                if (!std::equal(pa.begin() + p, pa.begin() + p + 4, pb.begin() + p))
                  for (int k = 0; k < 4; ++k) out[0][p + k] = 255;
            }
            if (alsoElsewhere) out[0][0] ^= 0x40;  // top-left pixel: background, unclassed
            return out;
          }};
}

}  // namespace

TEST(Expectations, TheRepositorysFileLoadsAndEveryReproducerIsAValidFrame) {
  const std::string root = TESSERA_SOURCE_DIR;
  const ExpectationSet set = loadExpectations(root + "/tests/expectations/gl-deviations.json");
  ASSERT_FALSE(set.entries.empty());
  for (const Expectation& e : set.entries) {
    const std::string path = root + "/" + e.reproducer;
    ASSERT_TRUE(std::filesystem::exists(path)) << path;
    const CommandList repro = readFrame(path);
    EXPECT_NO_THROW(validateOrThrow(repro, path));
    if (e.draw) {
      size_t draws = 0;
      for (const Command& c : repro.commands()) draws += std::holds_alternative<Draw>(c);
      EXPECT_GT(draws, 0u) << e.id;
    }
  }
}

TEST(Expectations, MalformedEntriesAreRefusedNamingTheFileEntryAndField) {
  EXPECT_EQ(errorOf(doc(entry())), "");  // the valid entry
  auto with = [](const char* key, nlohmann::json v) {
    nlohmann::json e = entry();
    e[key] = v;
    return doc(e);
  };
  EXPECT_NE(errorOf(with("pixels", 0)).find("x.json: entry 0 (e1): field 'pixels'"), std::string::npos);
  EXPECT_NE(errorOf(with("versions", "22.(")).find("field 'versions': not a regular expression"), std::string::npos);
  EXPECT_NE(errorOf(with("condition", {{"lp_threads", ">=two"}})).find("field 'condition.lp_threads'"), std::string::npos);
  EXPECT_NE(errorOf(with("condition", {{"cpu", "x"}})).find("unknown field 'condition.cpu'"), std::string::npos);
  EXPECT_NE(errorOf(with("draw", -1)).find("field 'draw'"), std::string::npos);
  EXPECT_NE(errorOf(with("reproducer", "/abs/x.tframe")).find("field 'reproducer'"), std::string::npos);
  EXPECT_NE(errorOf(with("id", "Has Space")).find("field 'id'"), std::string::npos);
  EXPECT_NE(errorOf(with("colour", "x")).find("unknown field 'colour'"), std::string::npos);
  nlohmann::json e = entry();
  e.erase("reason");
  EXPECT_NE(errorOf(doc(e)).find("field 'reason' must be a non-empty string"), std::string::npos);
  EXPECT_NE(errorOf({{"schema", 1}, {"entries", {entry(), entry()}}}).find("entry 1 (e1): field 'id': duplicate"),
            std::string::npos);
  EXPECT_NE(errorOf({{"entries", nlohmann::json::array()}}).find("field 'schema'"), std::string::npos);
}

// frame_sha256 is the sha256sum of the .tframe file: the oracle hashes the list's encoding, which must
// therefore be the file's bytes (a read frame encodes back to them).
TEST(Expectations, AnEntryWithAFrameHashMatchesOnlyThatExactFrameUnderItsName) {
  const std::string dir = std::string(TESSERA_SOURCE_DIR) + "/tests/expectations/repro/";
  const std::string f1 = dir + "softpipe-tex-tile-cache-alias.tframe", f2 = dir + "softpipe-tex-tile-cache-alias-s-wrap-bc1.tframe";
  std::ifstream in(f1, std::ios::binary);
  const std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_FALSE(bytes.empty());
  nlohmann::json e = entry();
  e["frame"] = "frame_0000.tframe";
  e["frame_sha256"] = sha256Hex(bytes);
  const ExpectationSet set = parseExpectations(doc(e), "x.json");
  const CommandList a = readFrame(f1), b = readFrame(f2);
  EXPECT_EQ(set.matching(llvmpipe(2), "r/frame_0000.tframe", &a).size(), 1u);
  EXPECT_TRUE(set.matching(llvmpipe(2), "r/frame_0000.tframe", &b).empty()) << "same name, other frame";
  EXPECT_TRUE(set.matching(llvmpipe(2), "r/frame_0000.tframe").empty()) << "no list to hash";
  EXPECT_TRUE(set.matching(llvmpipe(2), "r/frame_0002.tframe", &a).empty()) << "same frame, other name";
  for (const char* bad : {"ABC", "1AA3D9E977364D01BC6CB7A6397EC131199A731C09B7EC96BC540CEC56D6D1C3"}) {
    e["frame_sha256"] = bad;
    EXPECT_NE(errorOf(doc(e)).find("field 'frame_sha256' must be 64 lowercase hex digits"), std::string::npos) << bad;
  }
}

TEST(Expectations, EntriesMatchOnlyTheirImplementationVersionConditionAndFrame) {
  const ExpectationSet set = parseExpectations(doc(entry()), "x.json");
  EXPECT_EQ(set.matching(llvmpipe(2), "wrap_filter").size(), 1u);
  EXPECT_EQ(set.matching(llvmpipe(1), "wrap_filter").size(), 1u);
  EXPECT_TRUE(set.matching(llvmpipe(0), "wrap_filter").empty());        // one CPU: no rasterizer threads
  EXPECT_TRUE(set.matching(llvmpipe(2, true), "wrap_filter").empty());  // strict
  EXPECT_TRUE(set.matching(llvmpipe(2), "city_block").empty());
  EXPECT_TRUE(set.matching({"softpipe", "22.3.6", false, 2}, "wrap_filter").empty());
  EXPECT_TRUE(set.matching({"llvmpipe", "23.0.1", false, 2}, "wrap_filter").empty());
  EXPECT_TRUE(set.matching({"llvmpipe", "122.3.6", false, 2}, "wrap_filter").empty());  // whole-string match
  nlohmann::json e = entry();
  e["frame"] = "tests/expectations/repro/x.tframe";
  const ExpectationSet byFile = parseExpectations(doc(e), "x.json");
  EXPECT_EQ(byFile.matching(llvmpipe(2), "/elsewhere/x.tframe").size(), 1u);  // by file name
  EXPECT_EQ(parseIntCondition("<=3", "w").text(), "<=3");
  EXPECT_TRUE(parseIntCondition("2", "w").matches(2));
  EXPECT_FALSE(parseIntCondition("!=2", "w").matches(2));
}

// The deviation llvmpipe showed: draw 2 of wrap_filter white. Covered by the entry: passes, and the
// 58 x 58 = 3364 pixels of the cell (x, y in [3.2, 60.8] px) count as expected deviations.
TEST(Expectations, APinnedDeviationIsCountedAndPassesOnlyInsideItsDraw) {
  const CommandList list = scenes::build("wrap_filter", 256, 192);
  const ExpectationSet set = parseExpectations(doc(entry()), "x.json");
  CrosscheckOptions o;
  o.expectations = &set;
  o.condition = llvmpipe(2);
  const auto pinned = crosscheck(list, "wrap_filter", o, whiteDraw(2, false));
  EXPECT_TRUE(pinned.passed);
  EXPECT_EQ(pinned.json["unexplained"].get<uint64_t>(), 0u);
  EXPECT_EQ(pinned.json["expected_deviation"].get<uint64_t>(), 58u * 58u);
  EXPECT_EQ(pinned.json["expectations"]["matched"][0]["mask_pixels"].get<uint64_t>(), 58u * 58u);

  // One more wrong pixel outside the draw still fails, and bisection still runs.
  const auto extra = crosscheck(list, "wrap_filter", o, whiteDraw(2, true));
  EXPECT_FALSE(extra.passed);
  EXPECT_EQ(extra.json["unexplained"].get<uint64_t>(), 1u);
  EXPECT_EQ(extra.json["expected_deviation"].get<uint64_t>(), 58u * 58u);

  // The same fault in another draw (draw 5, MIRRORED_REPEAT) is not covered.
  const auto other = crosscheck(list, "wrap_filter", o, whiteDraw(5, false));
  EXPECT_FALSE(other.passed);
  EXPECT_EQ(other.json["expected_deviation"].get<uint64_t>(), 0u);

  // Under another condition (strict) the entry does not apply.
  o.condition = llvmpipe(2, true);
  EXPECT_FALSE(crosscheck(list, "wrap_filter", o, whiteDraw(2, false)).passed);

  // More pixels than the entry allows: nothing is covered.
  nlohmann::json small = entry();
  small["pixels"] = 100;
  const ExpectationSet tight = parseExpectations(doc(small), "x.json");
  o.expectations = &tight;
  o.condition = llvmpipe(2);
  const auto over = crosscheck(list, "wrap_filter", o, whiteDraw(2, false));
  EXPECT_FALSE(over.passed);
  EXPECT_EQ(over.json["unexplained"].get<uint64_t>(), 58u * 58u);
  EXPECT_FALSE(over.json["expectations"]["matched"][0]["covered"].get<bool>());
}

}  // namespace tessera::verify
