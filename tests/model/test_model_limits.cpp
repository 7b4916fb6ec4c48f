// loadModel's budgets (base/resource_limits.h, docs/limits.md): instances, triangles, vertices and the
// decoded bytes of all textures, each an Error naming the file, the need, the limit and the option that
// raises it. Texture bytes come from the image headers, read once at load: nothing is decoded.
#include <gtest/gtest.h>

#include <cstring>
#include <string>

#include "model/model.h"
#include "model_test_util.h"

namespace tessera::model {
namespace {

using testing::errorOf;
using testing::ScratchDir;

// Two nodes with the one-triangle mesh, under a third; `images` is the glTF images array (JSON text)
// and material 0 uses image 0 when there is one.
std::string writeModel(const ScratchDir& dir, const std::string& images = "") {
  std::string bin;
  testing::appendBytes(bin, std::vector<float>{0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 1});
  const std::string textured = images.empty()
                                   ? ""
                                   : R"(,"images":)" + images + R"(,"textures":[{"source":0}],)" +
                                         R"("materials":[{"pbrMetallicRoughness":{"baseColorTexture":{"index":0}}}])";
  const std::string gltf =
      R"({"asset":{"version":"2.0"},"buffers":[{"byteLength":60,"uri":"data:application/octet-stream;base64,)" +
      testing::base64(bin) +
      R"("}],"bufferViews":[{"buffer":0,"byteLength":36},{"buffer":0,"byteOffset":36,"byteLength":24}],)"
      R"("accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3"},)"
      R"({"bufferView":1,"componentType":5126,"count":3,"type":"VEC2"}],)"
      R"("meshes":[{"primitives":[{"attributes":{"POSITION":0,"TEXCOORD_0":1})" +
      std::string(images.empty() ? "" : R"(,"material":0)") +
      R"(}]}],"nodes":[{"children":[1,2]},{"mesh":0},{"mesh":0}],"scenes":[{"nodes":[0]}])" + textured + "}";
  const std::string path = dir / "model.gltf";
  testing::writeFile(path, gltf);
  return path;
}

TEST(ModelLimits, TheInstanceBudgetCountsEveryNodeReached) {
  ScratchDir dir;
  const std::string path = writeModel(dir);
  ResourceLimits l;
  l.modelInstances = 2;  // the group node and its two children are 3
  EXPECT_CONTAINS(errorOf([&] { loadModel(path, l); }),
                  path + ": needs 3 node instances, over the limit of 2 by 1 (raise it with --model-budget-instances)");
  l.modelInstances = 3;
  EXPECT_EQ(loadModel(path, l).meshes.size(), 2u);
}

TEST(ModelLimits, TheTriangleAndVertexBudgetsCountEveryInstance) {
  ScratchDir dir;
  const std::string path = writeModel(dir);
  ResourceLimits l;
  l.modelTriangles = 1;  // two instances of one triangle
  EXPECT_CONTAINS(errorOf([&] { loadModel(path, l); }),
                  path + ": needs 2 triangles, over the limit of 1 by 1 (raise it with --model-budget-triangles)");
  l = {};
  l.modelVertices = 5;  // two instances of three vertices
  EXPECT_CONTAINS(errorOf([&] { loadModel(path, l); }),
                  path + ": needs 6 vertices, over the limit of 5 by 1 (raise it with --model-budget-vertices)");
}

TEST(ModelLimits, TheTextureBudgetCountsFourBytesPerTexelOfEveryHeader) {
  ScratchDir dir;
  testing::writeChecker(dir / "a.png", 4, 2);  // 32 bytes as RGBA8
  testing::writeChecker(dir / "b.png", 2, 2);  // 16 bytes
  const std::string path = writeModel(dir, R"([{"uri":"a.png"},{"uri":"b.png"}])");
  ResourceLimits l;
  l.modelTextureBytes = 47;
  EXPECT_CONTAINS(errorOf([&] { loadModel(path, l); }),
                  path +
                      ": needs 48 B of decoded RGBA8 textures, over the limit of 47 B by 1 B (raise it with "
                      "--model-budget-textures); the largest is texture 0 'a.png' (4x2)");
  l.modelTextureBytes = 48;
  const Model m = loadModel(path, l);
  EXPECT_EQ(m.textures[0].header.width, 4u);  // kept for probeTexture()
  EXPECT_EQ(probeTexture(m, 0).height, 2u);
}

// A PNG of a signature, an IHDR chunk saying w x h RGBA8, a few bytes of IDAT and IEND: a header that
// reads, and data that would never decode.
std::string pngHeaderOnly(uint32_t w, uint32_t h) {
  auto crc32 = [](const std::string& s) {
    uint32_t c = 0xffffffffu;
    for (unsigned char b : s) {
      c ^= b;
      for (int k = 0; k < 8; ++k) c = (c >> 1) ^ (0xedb88320u & (0u - (c & 1u)));
    }
    return c ^ 0xffffffffu;
  };
  auto be32 = [](uint32_t v) { return std::string{char(v >> 24), char(v >> 16), char(v >> 8), char(v)}; };
  auto chunk = [&](const std::string& type, const std::string& data) {
    return be32(uint32_t(data.size())) + type + data + be32(crc32(type + data));
  };
  return std::string("\x89PNG\r\n\x1a\n", 8) + chunk("IHDR", be32(w) + be32(h) + std::string("\x08\x06\0\0\0", 5)) +
         chunk("IDAT", std::string("\x78\x9c\x03\x00", 4)) + chunk("IEND", "");
}

TEST(ModelLimits, ATextureWhoseHeaderClaims60000By60000IsRefusedAtLoadWithoutDecoding) {
  ScratchDir dir;
  testing::writeFile(dir / "huge.png", pngHeaderOnly(60000, 60000));
  const std::string path = writeModel(dir, R"([{"uri":"huge.png"}])");
  // 60000 * 60000 * 4 = 14,400,000,000 bytes = 13.4 GiB.
  EXPECT_CONTAINS(errorOf([&] { loadModel(path); }),
                  path +
                      ": needs 13.4 GiB of decoded RGBA8 textures, over the limit of 8.0 GiB by 5.4 GiB (raise it "
                      "with --model-budget-textures); the largest is texture 0 'huge.png' (60000x60000)");
}

TEST(ModelLimits, AnUnreadableHeaderCountsNothingAndFailsWhenTheTextureIsLoaded) {
  ScratchDir dir;
  testing::writeFile(dir / "broken.png", "\x89PNG\r\n\x1a\n not a png");
  const std::string path = writeModel(dir, R"([{"uri":"broken.png"}])");
  ResourceLimits l;
  l.modelTextureBytes = 0;
  const Model m = loadModel(path, l);
  EXPECT_EQ(m.textures[0].header.width, 0u);
  EXPECT_CONTAINS(errorOf([&] { loadTexture(m, 0); }), "broken.png");
}

TEST(ModelLimits, AnImageThatGrewAfterTheModelWasLoadedIsNotDecodedBeyondItsHeader) {
  ScratchDir dir;
  testing::writeChecker(dir / "t.png", 2, 2);
  const std::string path = writeModel(dir, R"([{"uri":"t.png"}])");
  const Model m = loadModel(path);
  testing::writeChecker(dir / "t.png", 8, 4);
  EXPECT_CONTAINS(errorOf([&] { loadTexture(m, 0); }),
                  "t.png): the image is 8x4, its header said 2x2 when the model was loaded");
}

}  // namespace
}  // namespace tessera::model
