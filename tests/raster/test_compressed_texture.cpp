// S3TC textures in the command list (TextureDesc::compression): the oracle decodes uploads by the rule of
// raster/bc_decode.h, validation checks sizes and uses, and the .tframe file stays version 1 unless a texture
// is compressed.
#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

#include "raster/bc_decode.h"
#include "raster/cpu_backend.h"
#include "raster/provenance.h"
#include "raster/serialize.h"
#include "raster/texture.h"
#include "raster/validate.h"
#include "tools/scenes/builder.h"

namespace tessera {
namespace {

TextureDesc compressed(BcFormat f, uint32_t w, uint32_t h, uint32_t levels) {
  TextureDesc d;
  d.kind = TextureKind::Tex2D;
  d.format = Format::RGBA8;
  d.width = w, d.height = h, d.levels = levels;
  d.compression = f;
  return d;
}

// One BC1 block: color0 = 0x0821 -> (8, 4, 8), color1 = 0, four colours, codes 0, 1, 2, 3 for texels 0..3;
// decoded by hand in test_bc_decode.cpp: (8,4,8), (0,0,0), (5,3,5), (3,1,3), the rest (8,4,8).
const std::vector<uint8_t> kBc1Block = {0x21, 0x08, 0x00, 0x00, 0xE4, 0, 0, 0};

std::string joined(const std::vector<Diagnostic>& ds) {
  std::string s;
  for (const Diagnostic& d : ds) s += "command " + std::to_string(d.command) + ": " + d.message + "\n";
  return s;
}

TEST(CompressedTexture, TheOracleStoresAnUploadedBc1LevelDecodedAndUnuploadedLevelsAsOpaqueBlack) {
  CommandList l;
  // 2 x 2 with two levels: level 0 is the top-left 2 x 2 of the block (texels 0, 1 and 4, 5), level 1 stays
  // the all-zero block GL starts with, opaque black for BC1.
  const ResourceId t = l.createTexture(compressed(BcFormat::BC1, 2, 2, 2));
  l.uploadTexture(t, 0, 0, kBc1Block);
  ASSERT_EQ(joined(validate(l)), "");
  CpuBackend b(RenderOptions{1});
  b.execute(l, "bc1");
  const TextureData* tex = b.texture(t);
  ASSERT_NE(tex, nullptr);
  const std::vector<uint8_t> level0 = {8, 4, 8, 255, 0, 0, 0, 255, 8, 4, 8, 255, 8, 4, 8, 255};
  EXPECT_EQ(tex->levels[0], level0);
  EXPECT_EQ(tex->levels[1], (std::vector<uint8_t>{0, 0, 0, 255}));
}

TEST(CompressedTexture, AnUploadOfTheWrongSizeNamesTheBlockFormatAndTheExpectedBytes) {
  CommandList l;
  const ResourceId t = l.createTexture(compressed(BcFormat::BC3, 8, 4, 1));
  l.uploadTexture(t, 0, 0, std::vector<uint8_t>(8 * 4 * 4, 0));  // RGBA8 bytes instead of two BC3 blocks
  const std::string e = joined(validate(l));
  EXPECT_NE(e.find("data has 128 bytes but level 0 of texture 1 (8x4 RGBA8 as BC3 blocks) has 32"), std::string::npos)
      << e;
}

TEST(CompressedTexture, ACompressedTextureCannotBeAnArrayOrARenderTarget) {
  CommandList l;
  TextureDesc array = compressed(BcFormat::BC1, 4, 4, 1);
  array.kind = TextureKind::Tex2DArray;
  array.layers = 2;
  l.createTexture(array);
  const ResourceId t = l.createTexture(compressed(BcFormat::BC1, 4, 4, 1));
  RenderTarget rt;
  rt.color[0] = t;
  l.setRenderTarget(rt);
  const std::string e = joined(validate(l));
  EXPECT_NE(e.find("command 0: desc.compression = BC1 needs a Tex2D RGBA8 texture (has Tex2DArray RGBA8)"),
            std::string::npos)
      << e;
  EXPECT_NE(e.find("command 2: color[0]: texture 2 is BC1-compressed and cannot be rendered to"), std::string::npos)
      << e;
}

TEST(CompressedTexture, AFrameWithoutCompressedTexturesIsStillWrittenAsVersion1) {
  CommandList l;
  TextureDesc d = compressed(BcFormat::None, 1, 1, 1);
  l.uploadTexture(l.createTexture(d), 0, 0, std::vector<uint8_t>{1, 2, 3, 4});
  const std::vector<uint8_t> bytes = encodeFrame(l);
  uint32_t version;
  std::memcpy(&version, bytes.data() + 8, 4);
  EXPECT_EQ(version, 1u);
  // 72-byte header, then CreateTexture: opcode 2 + size 4 + the version-1 payload of 26 bytes.
  uint32_t payload;
  std::memcpy(&payload, bytes.data() + 72 + 2, 4);
  EXPECT_EQ(payload, 26u);
}

TEST(CompressedTexture, AFrameWithACompressedTextureIsVersion2AndRoundTripsItsCompression) {
  CommandList l;
  const ResourceId t = l.createTexture(compressed(BcFormat::BC3, 4, 4, 1));
  l.uploadTexture(t, 0, 0, std::vector<uint8_t>(16, 7));
  const std::vector<uint8_t> bytes = encodeFrame(l);
  uint32_t version, payload;
  std::memcpy(&version, bytes.data() + 8, 4);
  std::memcpy(&payload, bytes.data() + 72 + 2, 4);
  EXPECT_EQ(version, 2u);
  EXPECT_EQ(payload, 27u);  // desc.compression appended as one byte
  const CommandList back = decodeFrame(bytes, "bc3.tframe");
  const auto* c = std::get_if<CreateTexture>(&back.commands().at(0));
  ASSERT_NE(c, nullptr);
  EXPECT_EQ(c->desc.compression, BcFormat::BC3);
  EXPECT_EQ(encodeFrame(back), bytes);
}

TEST(CompressedTexture, InProvenanceModeOnlyInterpolatedTexelsWidenByOneUnitAndAreClassedBcInterpolant) {
  // A 4 x 4 target showing the 4 x 4 BC1 texture texel for texel (NEAREST at texel centres, textured's
  // defaults: factor 1, so the output is the texel): pixel (x, 0) shows texel x of the block's first row,
  // codes 0, 1, 2, 3 = (8,4,8) endpoint, black endpoint, (5,3,5) and (3,1,3) interpolants.
  CommandList cl;
  RenderTarget rt;
  rt.color[0] = scenes::createTarget(cl, Format::RGBA8, 4, 4);
  cl.setRenderTarget(rt);
  cl.setViewport({0, 0, 4, 4});
  cl.clearColor(0, {0, 0, 0, 0});
  scenes::Mesh m;
  m.quad({0, 0, 0}, {4, 0, 0}, {4, 4, 0}, {0, 4, 0}, {0, 0, 0, 0}, {1, 0, 0, 0}, {1, 1, 0, 0}, {0, 1, 0, 0});
  scenes::bindMesh(cl, m);
  cl.useProgram(cl.createProgram("textured"));
  scenes::setMatrix(cl, 0, scenes::ortho(0, 4, 0, 4, -1, 1));
  scenes::setTexturedDefaults(cl);
  const ResourceId tex = cl.createTexture(compressed(BcFormat::BC1, 4, 4, 1));
  cl.uploadTexture(tex, 0, 0, kBc1Block);
  cl.bindTexture(0, tex);
  SamplerState nearest;
  nearest.minFilter = Filter::Nearest;
  nearest.magFilter = Filter::Nearest;
  cl.bindSampler(0, cl.createSampler(nearest));
  cl.drawIndexed(0, 6);
  CpuBackend b(RenderOptions{1, true, {}, 8});
  b.execute(cl, "bc1 provenance");
  const TextureData& t = *b.texture(rt.color[0]);
  ASSERT_TRUE(t.prov);
  auto at = [](const TextureData& img, int x) { return std::vector<uint8_t>(img.texel(0, 0, x, 0), img.texel(0, 0, x, 0) + 4); };
  const uint16_t cls2 = t.prov->classes[0][2], cls0 = t.prov->classes[0][0];
  EXPECT_EQ(at(t, 2), (std::vector<uint8_t>{5, 3, 5, 255}));
  EXPECT_EQ(at(*t.prov->lo, 2), (std::vector<uint8_t>{4, 2, 4, 255}));
  EXPECT_EQ(at(*t.prov->hi, 2), (std::vector<uint8_t>{6, 4, 6, 255}));
  EXPECT_NE(cls2 & kBcInterpolant, 0);
  EXPECT_EQ(at(*t.prov->lo, 3), (std::vector<uint8_t>{2, 0, 2, 255}));
  EXPECT_EQ(at(*t.prov->hi, 3), (std::vector<uint8_t>{4, 2, 4, 255}));
  // Endpoints are exact: no interval, no class.
  EXPECT_EQ(at(*t.prov->lo, 0), at(t, 0));
  EXPECT_EQ(at(*t.prov->hi, 0), at(t, 0));
  EXPECT_EQ(cls0, 0);
}

}  // namespace
}  // namespace tessera
