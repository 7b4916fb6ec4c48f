// The .tframe encoding: exact round trips, and a decoder that turns every truncated, corrupted or
// hostile file into an Error naming the place, never a crash (run under ASan/UBSan).
#include <gtest/gtest.h>
#include <unistd.h>

#include <bit>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <set>
#include <string>

#include "raster/counters.h"
#include "raster/serialize.h"
#include "base/sha256.h"
#include "raster/validate.h"

namespace tessera {
namespace {

// One command of every kind, with non-default values in as many fields as possible.
CommandList everyKind() {
  CommandList l;
  const ResourceId tex = l.createTexture({TextureKind::Tex2DArray, Format::RGBA32F, 4, 2, 3, 2});
  l.uploadTexture(tex, 1, 2, std::vector<uint8_t>(2 * 1 * 16, 0xab));
  const ResourceId vb = l.createBuffer(BufferKind::Vertex, 64);
  l.uploadBuffer(vb, 8, std::vector<uint8_t>{1, 2, 3, 4});
  SamplerState s;
  s.wrapS = Wrap::ClampToBorder;
  s.wrapT = Wrap::MirroredRepeat;
  s.minFilter = Filter::LinearMipmapLinear;
  s.magFilter = Filter::Nearest;
  s.minLod = -2.5f;
  s.maxLod = 7.25f;
  s.lodBias = -0.0f;
  s.borderColor = {1.0f, std::numeric_limits<float>::quiet_NaN(), -3.0f, 1e-40f};
  const ResourceId smp = l.createSampler(s);
  const ResourceId prog = l.createProgram("textured");
  l.bindTexture(3, tex);
  l.bindSampler(3, smp);
  l.useProgram(prog);
  l.setUniforms(5, std::vector<float>{1, 2, 3, 4, -5, 6.5f, 7, 8});
  l.bindVertexBuffer(vb);
  VertexLayout layout;
  layout.stride = 28;
  layout.attribs[0] = {0, 4, AttribType::F32, 0};
  layout.attribs[1] = {3, 2, AttribType::U32, 16};
  layout.attribs[7] = {7, 1, AttribType::F32, 24};
  l.setVertexLayout(layout);
  const ResourceId ib = l.createBuffer(BufferKind::Index, std::vector<uint8_t>{0, 0, 1, 0, 2, 0});
  l.bindIndexBuffer(ib, IndexType::U32);
  l.setViewport({-3, 4, 100, 200});
  l.setScissor({true, {1, -2, 30, 40}});
  l.setDepthState({true, false, CompareFunc::GEqual});
  BlendState b;
  b.enabled = true;
  b.eqRgb = BlendEq::Max;
  b.eqAlpha = BlendEq::ReverseSubtract;
  b.srcRgb = BlendFactor::SrcAlphaSaturate;
  b.dstRgb = BlendFactor::OneMinusConstantAlpha;
  b.srcAlpha = BlendFactor::DstColor;
  b.dstAlpha = BlendFactor::Zero;
  b.constant = {0.25f, 0.5f, 0.75f, -1.0f};
  l.setBlendState(b);
  l.setRasterState({CullMode::Front, false, 0x85});
  RenderTarget t;
  t.color = {tex, kNone, tex, kNone};
  t.depth = 77;
  t.level = 1;
  t.layer = kLayered;
  l.setRenderTarget(t);
  l.clearColor(2, {0.5f, -0.0f, 1.0f, 2.0f});
  l.clearDepth(0.75f);
  l.draw(5, 9);
  l.drawIndexed(1, 2);
  static constexpr char kText[] = "a marker with \0 a NUL and UTF-8 \xc3\xa9";
  l.marker(std::string_view(kText, sizeof kText - 1));
  return l;
}

// Recomputes the checksum after a deliberate edit, so the decoder's deeper checks are reached.
void reseal(std::vector<uint8_t>& f) {
  const auto d = sha256(std::span(f).subspan(kFrameHeaderSize));
  std::memcpy(f.data() + 40, d.data(), 32);
}

void putU32(std::vector<uint8_t>& f, size_t at, uint32_t v) {
  for (int i = 0; i < 4; ++i) f[at + i] = uint8_t(v >> (8 * i));
}
void putU64(std::vector<uint8_t>& f, size_t at, uint64_t v) {
  for (int i = 0; i < 8; ++i) f[at + i] = uint8_t(v >> (8 * i));
}

std::string errorOf(std::span<const uint8_t> bytes, std::string_view name = "frame.tframe") {
  try {
    (void)decodeFrame(bytes, name);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

template <class T>
const T& firstOf(const CommandList& l) {
  for (const Command& c : l.commands()) {
    if (const T* t = std::get_if<T>(&c)) return *t;
  }
  throw std::logic_error("no such command");
}

TEST(Serialize, EveryCommandKindIsInTheTestList) {
  const CommandList l = everyKind();  // named: a range-for over a temporary's member would dangle
  std::set<size_t> kinds;
  for (const Command& c : l.commands()) kinds.insert(c.index());
  EXPECT_EQ(kinds.size(), std::variant_size_v<Command>);
}

TEST(Serialize, ARoundTripOfEveryCommandKindReEncodesIdentically) {
  const CommandList l = everyKind();
  const std::vector<uint8_t> bytes = encodeFrame(l);
  const CommandList back = decodeFrame(bytes, "mem");
  EXPECT_EQ(back.commands().size(), l.commands().size());
  EXPECT_EQ(back.blob(), l.blob());
  EXPECT_EQ(back.nextId(), l.nextId());
  EXPECT_EQ(encodeFrame(back), bytes);
}

TEST(Serialize, DecodedFieldsKeepTheirExactValuesAndFloatBits) {
  const CommandList l = everyKind();
  const CommandList back = decodeFrame(encodeFrame(l), "mem");
  for (size_t i = 0; i < l.commands().size(); ++i) {
    ASSERT_EQ(back.commands()[i].index(), l.commands()[i].index()) << i;
  }
  const auto& smp = firstOf<CreateSampler>(back).state;
  EXPECT_EQ(smp.wrapS, Wrap::ClampToBorder);
  EXPECT_TRUE(std::isnan(smp.borderColor[1]));
  EXPECT_EQ(std::bit_cast<uint32_t>(smp.lodBias), 0x80000000u);  // -0 survives
  EXPECT_EQ(std::bit_cast<uint32_t>(smp.borderColor[3]), std::bit_cast<uint32_t>(1e-40f));
  const auto& vp = firstOf<SetViewport>(back).rect;
  EXPECT_EQ(vp, (Rect{-3, 4, 100, 200}));
  const auto& rt = firstOf<SetRenderTarget>(back).target;
  EXPECT_EQ(rt.layer, kLayered);
  EXPECT_EQ(rt.depth, 77u);
  const auto& m = std::get<Marker>(back.commands().back()).text;
  EXPECT_EQ(m, std::get<Marker>(l.commands().back()).text);
  const auto& u = firstOf<SetUniforms>(back);
  const auto data = back.bytes(u.data);
  float f[8];
  std::memcpy(f, data.data(), sizeof f);
  EXPECT_EQ(f[5], 6.5f);
}

TEST(Serialize, AnEmptyListRoundTrips) {
  const CommandList empty;
  const auto bytes = encodeFrame(empty);
  EXPECT_EQ(bytes.size(), kFrameHeaderSize);
  const CommandList back = decodeFrame(bytes, "empty");
  EXPECT_TRUE(back.commands().empty());
  EXPECT_EQ(back.nextId(), 1u);
}

TEST(Serialize, TheHeaderHasTheDocumentedLayout) {
  const CommandList l = everyKind();
  const auto f = encodeFrame(l);
  EXPECT_EQ(std::memcmp(f.data(), "TSFRAME\0", 8), 0);
  auto u32 = [&](size_t at) {
    return uint32_t(f[at]) | uint32_t(f[at + 1]) << 8 | uint32_t(f[at + 2]) << 16 | uint32_t(f[at + 3]) << 24;
  };
  auto u64 = [&](size_t at) { return uint64_t(u32(at)) | uint64_t(u32(at + 4)) << 32; };
  EXPECT_EQ(u32(8), 1u);
  EXPECT_EQ(u32(12), 72u);
  EXPECT_EQ(u64(16), l.commands().size());
  EXPECT_EQ(u64(24), l.blob().size());
  EXPECT_EQ(u64(32), l.nextId());
  EXPECT_EQ(toHex(std::span(f).subspan(40, 32)), sha256Hex(std::span(f).subspan(72)));
  // First command: CreateTexture, opcode 0, 26-byte payload.
  EXPECT_EQ(f[72] | f[73] << 8, 0);
  EXPECT_EQ(u32(74), 26u);
  // The blob is the tail of the file.
  EXPECT_TRUE(std::equal(l.blob().begin(), l.blob().end(), f.end() - ptrdiff_t(l.blob().size())));
}

TEST(Serialize, PayloadSizesAreThoseOfTheFormatDocument) {
  // docs/tframe-format.md, "Commands"; -1 marks the string-carrying kinds (fixed part + length).
  constexpr int kFixed[] = {26, 28, 13, 28, 36, -1, 8, 8, 4, 24, 4, 60, 5, 16, 17, 3, 23, 3, 28, 20, 4, 10, -1};
  static_assert(std::size(kFixed) == std::variant_size_v<Command>);
  const CommandList l = everyKind();
  const auto f = encodeFrame(l);
  size_t at = kFrameHeaderSize;
  for (const Command& c : l.commands()) {
    const size_t opcode = f[at] | f[at + 1] << 8;
    const uint32_t size = f[at + 2] | f[at + 3] << 8 | f[at + 4] << 16 | uint32_t(f[at + 5]) << 24;
    EXPECT_EQ(opcode, c.index());
    if (const auto* p = std::get_if<CreateProgram>(&c)) {
      EXPECT_EQ(size, 8 + p->name.size());
    } else if (const auto* m = std::get_if<Marker>(&c)) {
      EXPECT_EQ(size, 4 + m->text.size());
    } else {
      EXPECT_EQ(int(size), kFixed[opcode]) << commandName(opcode);
    }
    at += 6 + size;
  }
  EXPECT_EQ(at, f.size() - l.blob().size());
}

TEST(Serialize, TruncationAtEveryByteOffsetIsAnError) {
  const auto f = encodeFrame(everyKind());
  for (size_t n = 0; n < f.size(); ++n) {
    const std::string e = errorOf(std::span(f).first(n), "cut.tframe");
    ASSERT_FALSE(e.empty()) << "truncated to " << n << " bytes decoded without error";
    EXPECT_EQ(e.rfind("cut.tframe: ", 0), 0u) << e;
  }
}

TEST(Serialize, FlippingAnyByteAfterTheHeaderIsAChecksumError) {
  const auto good = encodeFrame(everyKind());
  for (size_t i = kFrameHeaderSize; i < good.size(); ++i) {
    auto f = good;
    f[i] ^= 0x5a;
    const std::string e = errorOf(f);
    EXPECT_NE(e.find("checksum"), std::string::npos) << "byte " << i << ": " << e;
  }
}

TEST(Serialize, FlippingAnyHeaderByteIsAClearError) {
  const auto good = encodeFrame(everyKind());
  for (size_t i = 0; i < kFrameHeaderSize; ++i) {
    for (uint8_t mask : {0x01, 0x80, 0xff}) {
      auto f = good;
      f[i] ^= mask;
      const std::string e = errorOf(f);
      ASSERT_FALSE(e.empty()) << "header byte " << i << " ^ " << int(mask) << " decoded without error";
      EXPECT_NE(e.find("frame.tframe: "), std::string::npos) << e;
      EXPECT_NE(e.find(" at byte "), std::string::npos) << e;
    }
  }
}

TEST(Serialize, AFlippedByteWithAValidChecksumIsAnErrorOrReEncodesToTheSameBytes) {
  // The checksum is bypassed by resealing, so this reaches every field check of the decoder: a
  // corrupted but well-formed file must decode to exactly what it says.
  const auto good = encodeFrame(everyKind());
  size_t decoded = 0, rejected = 0;
  for (size_t i = kFrameHeaderSize; i < good.size(); ++i) {
    for (uint8_t mask : {0x01, 0x10, 0x80, 0xff}) {
      auto f = good;
      f[i] ^= mask;
      reseal(f);
      try {
        const CommandList l = decodeFrame(f, "x");
        ASSERT_EQ(encodeFrame(l), f) << "byte " << i << " ^ " << int(mask);
        ++decoded;
      } catch (const Error&) {
        ++rejected;
      }
    }
  }
  EXPECT_GT(decoded, 0u);
  EXPECT_GT(rejected, 0u);
}

TEST(Serialize, RandomlyMutatedFramesNeverCrashTheDecoderValidatorOrCounters) {
  // Deterministic pseudo-random mutations (several bytes set to arbitrary values, resealed), to
  // reach combinations the single-byte tests do not. Whatever decodes must re-encode to the same
  // bytes and be safe to validate and count.
  const auto good = encodeFrame(everyKind());
  uint64_t state = 0x9e3779b97f4a7c15ull;
  auto next = [&] {
    state = state * 6364136223846793005ull + 1442695040888963407ull;  // PCG-style LCG step
    return uint32_t(state >> 33);
  };
  size_t decoded = 0;
  for (int iter = 0; iter < 4000; ++iter) {
    auto f = good;
    const int edits = 1 + int(next() % 4);
    for (int e = 0; e < edits; ++e) f[kFrameHeaderSize + next() % (f.size() - kFrameHeaderSize)] = uint8_t(next());
    reseal(f);
    try {
      const CommandList l = decodeFrame(f, "fuzz");
      ASSERT_EQ(encodeFrame(l), f) << "iteration " << iter;
      (void)validate(l);
      (void)countCommands(l);
      ++decoded;
    } catch (const Error&) {
    }
  }
  EXPECT_GT(decoded, 0u);
}

TEST(Serialize, AnOutOfRangeEnumNamesFileCommandByteAndField) {
  CommandList l;
  for (int i = 0; i < 12; ++i) l.clearDepth(1.0f);  // 10 bytes each: opcode 2 + size 4 + f32 4
  l.setBlendState({});
  auto f = encodeFrame(l);
  const size_t eqRgbAt = 72 + 12 * 10 + 6 + 1;  // after the opcode, the payload size and `enabled`
  ASSERT_EQ(f[eqRgbAt], 0);
  f[eqRgbAt] = 9;
  reseal(f);
  EXPECT_EQ(errorOf(f), "frame.tframe: command 12 (SetBlendState) at byte 199: field eqRgb = 9 is out of range (0..4)");
}

TEST(Serialize, AnUnknownOpcodeIsAnError) {
  CommandList l;
  l.clearDepth(1.0f);
  auto f = encodeFrame(l);
  f[72] = 23;
  reseal(f);
  EXPECT_EQ(errorOf(f), "frame.tframe: command 0 at byte 72: field opcode = 23 is out of range (0..22)");
}

TEST(Serialize, APayloadSizeThatDoesNotMatchTheFieldsIsAnError) {
  CommandList l;
  l.clearDepth(1.0f);
  l.clearDepth(0.5f);
  auto f = encodeFrame(l);
  putU32(f, 74, 3);  // ClearDepth needs 4
  reseal(f);
  EXPECT_NE(errorOf(f).find("command 0 (ClearDepth) at byte 78: field depth is truncated"), std::string::npos)
      << errorOf(f);
  putU32(f, 74, 5);  // one byte too many: eats the next command's first byte
  reseal(f);
  EXPECT_NE(errorOf(f).find("payloadSize = 5 but the fields of ClearDepth use 4 bytes"), std::string::npos)
      << errorOf(f);
}

TEST(Serialize, ABoolOtherThanZeroOrOneIsAnError) {
  CommandList l;
  l.draw(0, 3);
  auto f = encodeFrame(l);
  f[72 + 6 + 1] = 2;  // Draw.indexed
  reseal(f);
  EXPECT_NE(errorOf(f).find("command 0 (Draw) at byte 79: field indexed = 2 is not a bool"), std::string::npos)
      << errorOf(f);
}

TEST(Serialize, ABlobRangeOutsideTheBlobIsAnError) {
  CommandList l;
  l.setUniforms(0, std::vector<float>{1, 2, 3, 4});
  auto f = encodeFrame(l);
  putU64(f, 72 + 6 + 8, 1);  // data.offset = 1: [1, +16) of a 16-byte blob
  reseal(f);
  EXPECT_NE(errorOf(f).find("field data = [1, +16) lies outside the blob (16 bytes)"), std::string::npos) << errorOf(f);
  putU64(f, 72 + 6 + 8, ~uint64_t(0));  // offset + size would wrap around
  reseal(f);
  EXPECT_NE(errorOf(f).find("lies outside the blob"), std::string::npos) << errorOf(f);
}

TEST(Serialize, AHugeStringLengthIsRejectedBeforeAnyAllocation) {
  CommandList l;
  l.marker("hi");
  auto f = encodeFrame(l);
  putU32(f, 72 + 6, 0xffffffffu);
  reseal(f);
  EXPECT_NE(errorOf(f).find("field text has length 4294967295, more than the limit 4096"), std::string::npos)
      << errorOf(f);
  putU32(f, 72 + 6, 4000);  // within the limit but beyond the payload
  reseal(f);
  EXPECT_NE(errorOf(f).find("only 2 bytes are left"), std::string::npos) << errorOf(f);
}

TEST(Serialize, HugeCountsAndSizesInTheHeaderAreRejectedWithoutAllocating) {
  const auto good = encodeFrame(everyKind());
  for (uint64_t count : {uint64_t(1) << 60, ~uint64_t(0), uint64_t(good.size())}) {
    auto f = good;
    putU64(f, 16, count);
    EXPECT_NE(errorOf(f).find("header at byte 16: field commandCount"), std::string::npos) << errorOf(f);
  }
  for (uint64_t blob : {uint64_t(1) << 62, ~uint64_t(0)}) {
    auto f = good;
    putU64(f, 24, blob);
    EXPECT_NE(errorOf(f).find("header at byte 24: field blobSize"), std::string::npos) << errorOf(f);
  }
  auto f = good;
  putU32(f, 72 + 2, 0xfffffff0u);  // first payload size
  reseal(f);
  EXPECT_NE(errorOf(f).find("field payloadSize = 4294967280 exceeds"), std::string::npos) << errorOf(f);
}

TEST(Serialize, FewerOrMoreCommandsThanAnnouncedAreAnError) {
  CommandList l;
  l.clearDepth(1.0f);
  l.clearDepth(0.5f);
  auto f = encodeFrame(l);
  putU64(f, 16, 1);
  EXPECT_NE(errorOf(f).find("command section at byte 82: 10 bytes follow the last of the 1 commands"),
            std::string::npos)
      << errorOf(f);
  putU64(f, 16, 3);
  EXPECT_NE(errorOf(f).find("command 2 at byte 92: the command section ends after 2 of the 3 commands"),
            std::string::npos)
      << errorOf(f);
}

TEST(Serialize, HeaderErrorsNameTheField) {
  const auto good = encodeFrame(everyKind());
  auto f = good;
  f[0] = 'X';
  EXPECT_NE(errorOf(f).find("header at byte 0: field magic"), std::string::npos) << errorOf(f);
  f = good;
  putU32(f, 8, 3);
  EXPECT_NE(errorOf(f).find("header at byte 8: field version = 3 is not supported (expected 1 to 2)"), std::string::npos)
      << errorOf(f);
  f = good;
  putU32(f, 12, 80);
  EXPECT_NE(errorOf(f).find("header at byte 12: field headerSize = 80"), std::string::npos);
  f = good;
  putU64(f, 32, 7);
  EXPECT_NE(errorOf(f).find("header at byte 32: field nextId = 7 does not follow the highest created id 5"),
            std::string::npos)
      << errorOf(f);
  f = good;
  putU64(f, 32, uint64_t(1) << 32);
  EXPECT_NE(errorOf(f).find("field nextId = 4294967296 is out of range"), std::string::npos) << errorOf(f);
  EXPECT_NE(errorOf(std::span(good).first(3)).find("too short for the magic"), std::string::npos);
  EXPECT_NE(errorOf(std::span(good).first(10)).find("header at byte 8: field version is truncated"), std::string::npos);
}

TEST(Serialize, EncodingRejectsWhatTheDecoderWouldReject) {
  CommandList longName;
  longName.marker(std::string(kFrameMaxStringBytes + 1, 'x'));
  EXPECT_THROW((void)encodeFrame(longName), Error);

  CommandList badRange;
  badRange.appendRaw(SetUniforms{0, 1, BlobRange{0, 16}});  // no blob at all
  EXPECT_THROW((void)encodeFrame(badRange), Error);

  CommandList badEnum;
  badEnum.setDepthState({true, true, CompareFunc(42)});
  try {
    (void)encodeFrame(badEnum);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("command 0 (SetDepthState)"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("field func = 42 is out of range (0..7)"), std::string::npos) << e.what();
  }
}

class FrameFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() / ("tessera_serialize_" + std::to_string(::getpid()) + "_" +
                                                     ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::filesystem::path dir_;
};

TEST(Serialize, TheFileNextIdFollowsTheCreatedIdsEvenForAListCutShort) {
  // A prefix of a frame (CommandList::truncate keeps nextId()) must still encode and decode.
  CommandList l;
  l.createProgram("p");
  l.setNextId(5);
  const CommandList back = decodeFrame(encodeFrame(l), "prefix");
  EXPECT_EQ(back.nextId(), 2u);
  EXPECT_EQ(encodeFrame(back), encodeFrame(l));
}

TEST_F(FrameFiles, WriteThenReadGivesTheSameFrameAndLeavesNoTemporaryFile) {
  const CommandList l = everyKind();
  const std::string path = (dir_ / "f.tframe").string();
  writeFrame(l, path);
  EXPECT_EQ(encodeFrame(readFrame(path)), encodeFrame(l));
  size_t files = 0;
  for (const auto& e : std::filesystem::directory_iterator(dir_)) {
    ++files;
    EXPECT_EQ(e.path().filename(), "f.tframe");
  }
  EXPECT_EQ(files, 1u);
}

TEST_F(FrameFiles, WritingOverAnExistingFileReplacesItWhole) {
  const std::string path = (dir_ / "f.tframe").string();
  writeFrame(everyKind(), path);
  CommandList small;
  small.clearDepth(1.0f);
  writeFrame(small, path);
  EXPECT_EQ(std::filesystem::file_size(path), encodeFrame(small).size());
  EXPECT_EQ(readFrame(path).commands().size(), 1u);
}

TEST_F(FrameFiles, WritingIntoAMissingDirectoryThrowsNamingThePathAndCreatesNothing) {
  const std::string path = (dir_ / "missing" / "f.tframe").string();
  try {
    writeFrame(everyKind(), path);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
  EXPECT_TRUE(std::filesystem::is_empty(dir_));
}

TEST_F(FrameFiles, AFailedEncodeLeavesTheOldFileUntouched) {
  const std::string path = (dir_ / "f.tframe").string();
  writeFrame(everyKind(), path);
  const auto before = std::filesystem::file_size(path);
  CommandList bad;
  bad.marker(std::string(kFrameMaxStringBytes + 1, 'x'));
  EXPECT_THROW(writeFrame(bad, path), Error);
  EXPECT_EQ(std::filesystem::file_size(path), before);
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir_), std::filesystem::directory_iterator()), 1);
}

TEST_F(FrameFiles, ReadingAMissingOrCorruptFileNamesIt) {
  const std::string missing = (dir_ / "nope.tframe").string();
  try {
    (void)readFrame(missing);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(missing), std::string::npos) << e.what();
  }
  const std::string path = (dir_ / "f.tframe").string();
  writeFrame(everyKind(), path);
  std::filesystem::resize_file(path, std::filesystem::file_size(path) - 1);
  try {
    (void)readFrame(path);
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()).rfind(path + ": header at byte 40: field checksum", 0), 0u) << e.what();
  }
}

}  // namespace
}  // namespace tessera
