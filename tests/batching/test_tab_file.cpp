// The .tab file (batching/tab_file.h, docs/tab-format.md): round trip, determinism, the documented
// layout and sizes, truncation, corruption, every cross-reference rule, failed writes, and a small
// fuzz loop. Scenes are built by hand here, independently of the batcher.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <random>

#include "base/error.h"
#include "base/sha256.h"
#include "batching/tab_file.h"
#include "tests/batching/scratch_dir.h"

namespace tessera::batching {
namespace {

namespace fs = std::filesystem;

using testing::TempDir;

std::vector<uint8_t> slurp(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  return std::vector<uint8_t>(std::istreambuf_iterator<char>(f), {});
}
void spit(const std::string& path, const std::vector<uint8_t>& bytes) {
  std::ofstream f(path, std::ios::binary | std::ios::trunc);
  f.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
}

// A w x h RGBA8 texture with its full chain; texel bytes depend on (seed, level, offset).
TabTexture texture(const std::string& name, uint32_t w, uint32_t h, uint8_t seed, WrapMode s = WrapMode::Repeat,
                   WrapMode t = WrapMode::Repeat) {
  TabTexture x;
  x.name = name, x.width = w, x.height = h, x.wrapS = s, x.wrapT = t;
  for (uint32_t lw = w, lh = h, l = 0;; lw = std::max(1u, lw / 2), lh = std::max(1u, lh / 2), ++l) {
    std::vector<uint8_t> level(size_t(lw) * lh * 4);
    for (size_t i = 0; i < level.size(); ++i) level[i] = uint8_t(seed * 31 + l * 7 + i);
    x.levels.push_back(std::move(level));
    if (lw == 1 && lh == 1) break;
  }
  return x;
}

void addTriangles(TabScene& s, TabMesh& m, uint32_t triangles, float index) {
  m.firstVertex = uint32_t(s.vertices.size());
  m.vertexCount = triangles * 3;
  for (uint32_t v = 0; v < m.vertexCount; ++v) {
    const float k = float(s.vertices.size());
    s.vertices.push_back(Vertex{k, 2.0f * k - 5.0f, 0.25f * k, 0.5f * float(v % 3), 0.125f * k, index});
  }
}

// Two output batches: the first binds arrays 0 (4x4 repeat, textures 0 and 1) and 2 (2x1 clamp/repeat,
// texture 2) and draws mesh 0 (texture 0) and mesh 1 (two units: textures 1 and 2) in one geometry batch;
// the second binds array 1 (4x4 repeat, texture 3) for mesh 2, with a MASK material. Then an untextured
// mesh and a BLEND mesh.
TabScene handMadeScene() {
  TabScene s;
  s.params = TabParams{12, 2, 2};
  s.source = "hand.glb";
  s.textures = {texture("a.png", 4, 4, 1), texture("b.png", 4, 4, 2),
                texture("c.png", 2, 1, 3, WrapMode::ClampToEdge, WrapMode::Repeat), texture("d.png", 4, 4, 4)};
  const ArrayKey k44{4, 4, TexelFormat::RGBA8, WrapMode::Repeat, WrapMode::Repeat};
  s.arrays = {TextureArray{k44, {0, 1}}, TextureArray{k44, {3}},
              TextureArray{ArrayKey{2, 1, TexelFormat::RGBA8, WrapMode::ClampToEdge, WrapMode::Repeat}, {2}}};
  OutputBatch b0;
  b0.arrays = {0, 2};
  b0.tam = {TamEntry{0, 0, {1, 1, 1, 1}, 0.0f, true}, TamEntry{0, 1, {1, 0.5f, 1, 1}, 0.0f, true},
            TamEntry{1, 0, {1, 1, 1, 1}, 0.0f, true}};
  OutputBatch b1;
  b1.arrays = {1};
  b1.tam = {TamEntry{0, 0, {0.5f, 0.25f, 1, 0.75f}, 0.5f, true}};

  TabMesh m0{"m0", MeshKind::Batched, 0, 0, 0, {0}, {1, 1, 1, 1}, AlphaMode::Opaque, 0.5f, 0, 0};
  addTriangles(s, m0, 1, 0.0f);
  TabMesh m1{"m1", MeshKind::Batched, 1, 0, 0, {1, 2}, {1, 0.5f, 1, 1}, AlphaMode::Opaque, 0.5f, 0, 1};
  addTriangles(s, m1, 2, 1.0f);
  TabMesh m2{"m2", MeshKind::Batched, 3, 0, 0, {3}, {0.5f, 0.25f, 1, 0.75f}, AlphaMode::Mask, 0.5f, 1, 0};
  addTriangles(s, m2, 1, 0.0f);
  TabMesh m3{"roof", MeshKind::Untextured, 2, 0, 0, {}, {0.8f, 0.1f, 0.1f, 1}, AlphaMode::Opaque, 0.5f, 0, 0};
  addTriangles(s, m3, 1, 0.0f);
  TabMesh m4{"glass", MeshKind::Blend, 4, 0, 0, {0}, {1, 1, 1, 0.5f}, AlphaMode::Blend, 0.5f, 0, 0};
  addTriangles(s, m4, 1, 0.0f);
  s.meshes = {m0, m1, m2, m3, m4};
  b0.geometry = {GeometryBatch{0, 9, 0, 2}};
  b1.geometry = {GeometryBatch{9, 3, 2, 1}};
  s.batches = {b0, b1};
  s.bounds = {1e30f, 1e30f, 1e30f, -1e30f, -1e30f, -1e30f};
  for (const Vertex& v : s.vertices) {
    const float p[3] = {v.x, v.y, v.z};
    for (int k = 0; k < 3; ++k)
      s.bounds[k] = std::min(s.bounds[k], p[k]), s.bounds[k + 3] = std::max(s.bounds[k + 3], p[k]);
  }
  return s;
}

void expectSameScene(const TabScene& a, const TabScene& b) {
  EXPECT_EQ(a.params, b.params);
  EXPECT_EQ(a.source, b.source);
  EXPECT_EQ(a.bounds, b.bounds);
  ASSERT_EQ(a.textures.size(), b.textures.size());
  for (size_t i = 0; i < a.textures.size(); ++i) {
    const TabTexture &x = a.textures[i], &y = b.textures[i];
    EXPECT_EQ(x.name, y.name);
    EXPECT_EQ(x.width, y.width);
    EXPECT_EQ(x.height, y.height);
    EXPECT_EQ(x.format, y.format);
    EXPECT_EQ(x.wrapS, y.wrapS);
    EXPECT_EQ(x.wrapT, y.wrapT);
    EXPECT_EQ(x.levels, y.levels) << "texture " << i;
  }
  ASSERT_EQ(a.arrays.size(), b.arrays.size());
  for (size_t i = 0; i < a.arrays.size(); ++i) {
    EXPECT_EQ(a.arrays[i].key, b.arrays[i].key);
    EXPECT_EQ(a.arrays[i].layers, b.arrays[i].layers);
  }
  ASSERT_EQ(a.batches.size(), b.batches.size());
  for (size_t i = 0; i < a.batches.size(); ++i) {
    const OutputBatch &x = a.batches[i], &y = b.batches[i];
    EXPECT_EQ(x.arrays, y.arrays);
    ASSERT_EQ(x.tam.size(), y.tam.size());
    for (size_t k = 0; k < x.tam.size(); ++k) {
      EXPECT_EQ(x.tam[k].array, y.tam[k].array);
      EXPECT_EQ(x.tam[k].layer, y.tam[k].layer);
      EXPECT_EQ(x.tam[k].factor, y.tam[k].factor);
      EXPECT_EQ(x.tam[k].alphaCutoff, y.tam[k].alphaCutoff);
      EXPECT_EQ(x.tam[k].opaque, y.tam[k].opaque);
    }
    ASSERT_EQ(x.geometry.size(), y.geometry.size());
    for (size_t k = 0; k < x.geometry.size(); ++k) {
      EXPECT_EQ(x.geometry[k].firstVertex, y.geometry[k].firstVertex);
      EXPECT_EQ(x.geometry[k].vertexCount, y.geometry[k].vertexCount);
      EXPECT_EQ(x.geometry[k].firstMesh, y.geometry[k].firstMesh);
      EXPECT_EQ(x.geometry[k].meshCount, y.geometry[k].meshCount);
    }
  }
  ASSERT_EQ(a.meshes.size(), b.meshes.size());
  for (size_t i = 0; i < a.meshes.size(); ++i) {
    const TabMesh &x = a.meshes[i], &y = b.meshes[i];
    EXPECT_EQ(x.name, y.name);
    EXPECT_EQ(x.kind, y.kind);
    EXPECT_EQ(x.modelMesh, y.modelMesh);
    EXPECT_EQ(x.firstVertex, y.firstVertex);
    EXPECT_EQ(x.vertexCount, y.vertexCount);
    EXPECT_EQ(x.textures, y.textures);
    EXPECT_EQ(x.factor, y.factor);
    EXPECT_EQ(x.alphaMode, y.alphaMode);
    EXPECT_EQ(x.alphaCutoff, y.alphaCutoff);
    EXPECT_EQ(x.outputBatch, y.outputBatch);
    EXPECT_EQ(x.tamIndex, y.tamIndex);
  }
  ASSERT_EQ(a.vertices.size(), b.vertices.size());
  // memcmp's pointers must not be null even for 0 bytes (an empty vector's data() may be).
  if (!a.vertices.empty()) {
    EXPECT_EQ(0, std::memcmp(a.vertices.data(), b.vertices.data(), a.vertices.size() * sizeof(Vertex)));
  }
}

// The section table as docs/tab-format.md lays it out: entry k at 32 + 56 k: kind, reserved, offset, size.
struct SectionSpan {
  uint64_t offset, size;
};
SectionSpan sectionAt(const std::vector<uint8_t>& f, uint32_t k) {
  SectionSpan s;
  std::memcpy(&s.offset, f.data() + 32 + 56 * k + 8, 8);
  std::memcpy(&s.size, f.data() + 32 + 56 * k + 16, 8);
  return s;
}

// Recomputes every section checksum and the header checksum, so that an edited section reaches the
// decoder and the validator instead of stopping at a checksum. Does nothing to a file whose header
// does not describe sections inside it.
void fixChecksums(std::vector<uint8_t>& f) {
  if (f.size() < kTabHeaderSize) return;
  const uint64_t size = f.size();
  std::memcpy(f.data() + 24, &size, 8);
  for (uint32_t k = 0; k < kTabSectionCount; ++k) {
    const SectionSpan s = sectionAt(f, k);
    if (s.offset > f.size() || s.size > f.size() - s.offset) return;
    const auto sha = sha256(std::span<const uint8_t>(f.data() + s.offset, s.size));
    std::memcpy(f.data() + 32 + 56 * k + 24, sha.data(), 32);
  }
  const auto sha = sha256(std::span<const uint8_t>(f.data(), kTabHeaderSize - 32));
  std::memcpy(f.data() + kTabHeaderSize - 32, sha.data(), 32);
}

// Reads `bytes` as a file and returns the Error's message ("" if it was accepted).
std::string readError(const TempDir& dir, const std::vector<uint8_t>& bytes) {
  const std::string path = dir / "scene.tab";
  spit(path, bytes);
  try {
    (void)readTabFile(path);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

std::string rejection(const TempDir& dir, const TabScene& s) { return readError(dir, encodeTabFile(s)); }

TEST(TabFile, ARoundTripGivesTheSameScene) {
  TempDir dir;
  const TabScene s = handMadeScene();
  writeTabFile(s, dir / "scene.tab");
  const TabScene r = readTabFile(dir / "scene.tab");
  expectSameScene(s, r);
  EXPECT_EQ(dir.entries(), 1u);  // no temporary left beside it
}

TEST(TabFile, AnEmptySceneRoundTrips) {
  TempDir dir;
  TabScene s;
  writeTabFile(s, dir / "empty.tab");
  expectSameScene(s, readTabFile(dir / "empty.tab"));
}

TEST(TabFile, SameSceneGivesTheSameBytes) {
  TempDir dir;
  writeTabFile(handMadeScene(), dir / "a.tab");
  writeTabFile(handMadeScene(), dir / "b.tab");
  const std::vector<uint8_t> a = slurp(dir / "a.tab");
  EXPECT_EQ(a, slurp(dir / "b.tab"));
  EXPECT_EQ(a, encodeTabFile(handMadeScene()));
}

// The sizes docs/tab-format.md gives for each record, added up by hand for the scene above.
TEST(TabFile, EachSectionHasTheDocumentedSize) {
  const std::vector<uint8_t> f = encodeTabFile(handMadeScene());
  ASSERT_GE(f.size(), kTabHeaderSize);
  EXPECT_EQ(0, std::memcmp(f.data(), "TESSTAB\x1a", 8));
  EXPECT_EQ(kTabHeaderSize, 456u);
  // meta: b_max, d_max, a_max; source "hand.glb"; 6 bounds.
  const uint64_t meta = 12 + (4 + 8) + 24;
  // textures: count; per texture: name, width, height, format, wrap s, wrap t, levels.
  const uint64_t textures = 4 + 4 * (4 + 5 + 4 + 4 + 4) + 0;  // names "a.png".. are 5 bytes
  // texels: 4x4 chains are 64 + 16 + 4 bytes, the 2x1 chain 8 + 4.
  const uint64_t texels = 3 * (64 + 16 + 4) + (8 + 4);
  // arrays: count; per array: width, height, format, wrap s, wrap t, layer count, layers.
  const uint64_t arrays = 4 + 3 * (4 + 4 + 3 + 4) + 4 * (2 + 1 + 1);
  // batches: count; per batch: array list, TAM count + 29 bytes per entry, geometry count + 16 per batch.
  const uint64_t batches = 4 + (4 + 8 + 4 + 3 * 29 + 4 + 16) + (4 + 4 + 4 + 29 + 4 + 16);
  // meshes: count; per mesh: name, kind, model mesh, first vertex, vertex count, texture list, factor,
  // alpha mode, cutoff, output batch, TAM index (46 bytes besides the name and the texture list).
  const uint64_t meshes = 4 + (4 + 2) + (4 + 2) + (4 + 2) + (4 + 4) + (4 + 5) + 5 * 46 + 4 * (1 + 2 + 1 + 0 + 1);
  // vertices: count, 18 vertices of 24 bytes.
  const uint64_t vertices = 4 + 18 * 24;
  const uint64_t expected[kTabSectionCount] = {meta, textures, texels, arrays, batches, meshes, vertices};
  uint64_t offset = kTabHeaderSize;
  for (uint32_t k = 0; k < kTabSectionCount; ++k) {
    uint32_t kind;
    std::memcpy(&kind, f.data() + 32 + 56 * k, 4);
    EXPECT_EQ(kind, k + 1);
    EXPECT_EQ(sectionAt(f, k).offset, offset) << "section " << k;
    EXPECT_EQ(sectionAt(f, k).size, expected[k]) << "section " << k;
    offset += expected[k];
  }
  EXPECT_EQ(f.size(), offset);
  uint64_t fileSize;
  std::memcpy(&fileSize, f.data() + 24, 8);
  EXPECT_EQ(fileSize, f.size());
}

TEST(TabFile, TruncatedFileIsAClearError) {
  TempDir dir;
  const std::vector<uint8_t> f = encodeTabFile(handMadeScene());
  std::vector<uint64_t> cuts = {0, 1, 7, 8, 100, kTabHeaderSize - 1, kTabHeaderSize, f.size() - 1};
  for (uint32_t k = 0; k < kTabSectionCount; ++k) {
    const SectionSpan s = sectionAt(f, k);
    cuts.push_back(s.offset), cuts.push_back(s.offset + 1), cuts.push_back(s.offset + s.size - 1);
  }
  for (uint64_t cut : cuts) {
    const std::string e = readError(dir, std::vector<uint8_t>(f.begin(), f.begin() + std::ptrdiff_t(cut)));
    EXPECT_NE(e.find(dir / "scene.tab"), std::string::npos) << "cut at " << cut << ": " << e;
    EXPECT_NE(e.find("truncated"), std::string::npos) << "cut at " << cut << ": " << e;
  }
  // Trailing bytes are refused as well.
  std::vector<uint8_t> longer = f;
  longer.push_back(0);
  EXPECT_NE(readError(dir, longer).find("trailing bytes"), std::string::npos);
}

TEST(TabFile, FlippedByteIsAChecksumErrorNamingTheSection) {
  TempDir dir;
  const std::vector<uint8_t> f = encodeTabFile(handMadeScene());
  const char* names[] = {"meta", "textures", "texels", "arrays", "batches", "meshes", "vertices"};
  for (uint32_t k = 0; k < kTabSectionCount; ++k) {
    const SectionSpan s = sectionAt(f, k);
    for (uint64_t at : {s.offset, s.offset + s.size / 2, s.offset + s.size - 1}) {
      std::vector<uint8_t> g = f;
      g[at] ^= 0x10;
      const std::string e = readError(dir, g);
      EXPECT_NE(e.find(dir / "scene.tab"), std::string::npos) << e;
      EXPECT_NE(e.find(std::string(names[k]) + " section: checksum mismatch"), std::string::npos) << at << ": " << e;
    }
  }
  // In the header past the magic and the version: the header's own checksum.
  for (uint64_t at : {uint64_t(12), uint64_t(30), uint64_t(100), uint64_t(kTabHeaderSize) - 1}) {
    std::vector<uint8_t> g = f;
    g[at] ^= 0x01;
    EXPECT_NE(readError(dir, g).find("header checksum mismatch"), std::string::npos) << at;
  }
  std::vector<uint8_t> g = f;
  g[3] ^= 0x01;
  EXPECT_NE(readError(dir, g).find("bad magic"), std::string::npos);
  g = f;
  g[8] = 2;
  EXPECT_NE(readError(dir, g).find("header.version: 2"), std::string::npos);
}

TEST(TabFile, ALayerNamingAMissingTextureIsRejected) {
  TempDir dir;
  TabScene s = handMadeScene();
  s.arrays[0].layers[1] = 99;
  EXPECT_EQ(rejection(dir, s), dir / "scene.tab" + ": arrays[0].layers[1]: texture 99 does not exist (4 textures)");
  // The writer refuses it as well, and writes nothing.
  EXPECT_THROW(writeTabFile(s, dir / "out.tab"), Error);
  EXPECT_FALSE(fs::exists(dir / "out.tab"));
}

TEST(TabFile, ALayerWhoseTextureDoesNotMatchTheArrayKeyIsRejected) {
  TempDir dir;
  TabScene s = handMadeScene();
  s.arrays[1].layers[0] = 2;  // the 2x1 clamp texture in a 4x4 repeat array
  EXPECT_EQ(rejection(dir, s), dir / "scene.tab" +
                                   ": arrays[1].layers[0]: texture 2 is 2 x 1 RGBA8 clamp/repeat, but the array holds "
                                   "4 x 4 RGBA8 repeat/repeat");
}

TEST(TabFile, AnArrayOverDMaxIsRejected) {
  TempDir dir;
  TabScene s = handMadeScene();
  s.params.dMax = 1;
  EXPECT_EQ(rejection(dir, s), dir / "scene.tab" + ": arrays[0].layers: 2 layers, over params.d_max = 1");
  s.params.dMax = 2049;
  EXPECT_EQ(rejection(dir, s),
            dir / "scene.tab" + ": params.d_max: 2049 is outside [1, 2048] (GL_MAX_ARRAY_TEXTURE_LAYERS)");
}

TEST(TabFile, ATamEntryOutsideItsBatchArraysIsRejected) {
  TempDir dir;
  TabScene s = handMadeScene();
  s.batches[0].tam[2].array = 2;
  EXPECT_EQ(rejection(dir, s), dir / "scene.tab" + ": batches[0].tam[2].array: 2 is not below the batch's 2 arrays");
  s = handMadeScene();
  s.batches[0].tam[1].layer = 7;
  EXPECT_EQ(rejection(dir, s), dir / "scene.tab" + ": batches[0].tam[1].layer: 7 is not below the array's 2 layers");
}

// One edit per rule of docs/tab-format.md, "What the reader checks", with the field the error names.
TEST(TabFile, EachBrokenRuleIsRejectedNamingItsField) {
  TempDir dir;
  static constexpr float nan = std::numeric_limits<float>::quiet_NaN();
  const std::vector<std::pair<std::function<void(TabScene&)>, std::string>> cases = {
      {[](TabScene& s) { s.params.bMax = 3; }, "params.b_max: 3 is not above 3"},
      {[](TabScene& s) { s.params.aMax = 0; }, "params.a_max: 0 is outside [1, 8]"},
      {[](TabScene& s) { s.params.aMax = 9; }, "params.a_max: 9 is outside [1, 8]"},
      {[](TabScene& s) { s.params.aMax = 1; }, "batches[0].arrays: 2 arrays, over params.a_max = 1"},
      {[](TabScene& s) { s.bounds[4] = nan; }, "bounds: nan is not finite"},
      {[](TabScene& s) { s.bounds[3] = 0.5f; }, "vertices[1]: (1, -3, 0.25) is outside the scene's bounds"},
      {[](TabScene& s) { s.textures[1].levels.pop_back(); },
       "textures[1].levels: 2, but a full mip chain of 4 x 4 has 3 levels"},
      {[](TabScene& s) { s.textures[1].levels[1].pop_back(); }, "texels section"},
      {[](TabScene& s) { s.textures[2].width = 0; }, "textures[2].size: 0 x 1 is outside [1, 16384] per axis"},
      {[](TabScene& s) { s.textures[2].wrapT = WrapMode(3); }, "textures[2].wrap_t: 3 is not a value in [0, 2]"},
      {[](TabScene& s) { s.arrays[2].layers.clear(); }, "arrays[2].layers: none"},
      {[](TabScene& s) { s.batches[1].arrays[0] = 3; }, "batches[1].arrays[0]: array 3 does not exist (3 arrays)"},
      {[](TabScene& s) { s.batches[1].tam[0].factor[2] = nan; }, "batches[1].tam[0].factor: nan is not finite"},
      {[](TabScene& s) { s.batches[0].tam[1].layer = 0; },
       "meshes[1].tam_index: unit 0's entry batches[0].tam[1] holds texture 0, but the mesh uses texture 1"},
      {[](TabScene& s) { s.meshes[1].tamIndex = 2; },
       "meshes[1].tam_index: 2 + 2 units runs past batch 0's 3 TAM entries"},
      {[](TabScene& s) { s.meshes[2].tamIndex = 1u << 24; }, "meshes[2].tam_index: 16777216 is not below 2^24"},
      {[](TabScene& s) { s.meshes[2].outputBatch = 5; }, "meshes[2].output_batch: 5 does not exist (2 output batches)"},
      {[](TabScene& s) { s.meshes[3].firstVertex = 13; }, "meshes[3].first_vertex: 13, expected 12"},
      {[](TabScene& s) { s.meshes[4].vertexCount = 6; }, "meshes[4].vertex_count: vertices [15, +6) run past the 18"},
      {[](TabScene& s) { s.meshes[4].vertexCount = 2; }, "meshes[4].vertex_count: 2 is not a multiple of 3"},
      {[](TabScene& s) {
         s.meshes[3].kind = MeshKind::Blend, s.meshes[3].textures = {0};
         s.meshes[4].kind = MeshKind::Untextured, s.meshes[4].textures = {};
       },
       "meshes[4].kind: 1 after a mesh of kind 2"},
      {[](TabScene& s) { s.meshes[4].textures = {4}; }, "meshes[4].textures[0]: texture 4 does not exist"},
      {[](TabScene& s) { s.meshes[4].textures = {}; }, "meshes[4].textures: none on a BLEND mesh"},
      {[](TabScene& s) { s.meshes[0].alphaMode = AlphaMode::Blend; }, "meshes[0].alpha_mode: BLEND on a batched mesh"},
      {[](TabScene& s) { s.meshes[1].kind = MeshKind::Untextured; },
       "meshes[1].textures: 2 textures on an untextured mesh"},
      {[](TabScene& s) { s.batches[0].geometry[0].vertexCount = 8; },
       "batches[0].geometry[0].vertex_count: 8, but its meshes hold 9"},
      {[](TabScene& s) { s.batches[0].geometry[0].firstVertex = 1; },
       "batches[0].geometry[0].first_vertex: 1, but its first mesh starts at 0"},
      {[](TabScene& s) { s.batches[1].geometry[0].firstMesh = 1; }, "batches[1].geometry[0].first_mesh: 1, expected 2"},
      {[](TabScene& s) { s.batches[1].geometry[0].meshCount = 2; },
       "batches[1].geometry[0].mesh_count: meshes [2, +2) run past the 3 batched meshes"},
      {[](TabScene& s) { s.batches[1].geometry.clear(); },
       "batches: the geometry batches hold 2 meshes, but 3 are batched"},
      {[](TabScene& s) { s.params.bMax = 8; },
       "batches[0].geometry[0].vertex_count: 9 vertices in 2 meshes, over params.b_max = 8"},
      {[](TabScene& s) { s.meshes[2].outputBatch = 0; },
       "batches[1].geometry[0].first_mesh: mesh 2 belongs to output batch 0, not 1"},
      {[](TabScene& s) { s.vertices[4].index = 1.5f; }, "vertices[4].index: 1.5 is not an integer in [0, 2^24)"},
      {[](TabScene& s) { s.vertices[4].index = 0.0f; }, "vertices[4].index: 0, but mesh 1 has i_TAM 1"},
      {[](TabScene& s) { s.vertices[16].index = 1.0f; },
       "vertices[16].index: 1, but mesh 4 has i_TAM 0 (unbatched meshes carry 0)"},
      {[](TabScene& s) { s.vertices[5].s = std::numeric_limits<float>::infinity(); }, "vertices[5]: inf is not finite"},
      {[](TabScene& s) { s.vertices.push_back(s.vertices.back()); }, "meshes: cover 18 of the 19 vertices"},
  };
  for (const auto& [edit, expected] : cases) {
    TabScene s = handMadeScene();
    edit(s);
    const std::string e = rejection(dir, s);
    EXPECT_EQ(e.rfind(dir / "scene.tab: ", 0), 0u) << e;
    EXPECT_NE(e.find(expected), std::string::npos) << "expected \"" << expected << "\", got \"" << e << "\"";
  }
}

TEST(TabFile, AWriteThatFailsLeavesNoFileBehind) {
  TempDir dir;
  // A missing directory.
  EXPECT_THROW(writeTabFile(handMadeScene(), dir / "missing/scene.tab"), Error);
  EXPECT_EQ(dir.entries(), 0u);
  // A directory in the way of the final name: the rename fails after every byte was written.
  fs::create_directory(dir / "scene.tab");
  try {
    writeTabFile(handMadeScene(), dir / "scene.tab");
    ADD_FAILURE() << "wrote over a directory";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(dir / "scene.tab"), std::string::npos) << e.what();
  }
  EXPECT_EQ(dir.entries(), 1u);  // the directory alone, no temporary
  EXPECT_TRUE(fs::is_directory(dir / "scene.tab"));
  // An invalid scene over an existing file: the old file stays as it was.
  fs::remove(dir / "scene.tab");
  writeTabFile(handMadeScene(), dir / "scene.tab");
  const std::vector<uint8_t> before = slurp(dir / "scene.tab");
  TabScene bad = handMadeScene();
  bad.params.aMax = 0;
  EXPECT_THROW(writeTabFile(bad, dir / "scene.tab"), Error);
  EXPECT_EQ(slurp(dir / "scene.tab"), before);
  EXPECT_EQ(dir.entries(), 1u);
}

TEST(TabFile, AMissingFileOrADirectoryIsAClearError) {
  TempDir dir;
  EXPECT_THROW(readTabFile(dir / "none.tab"), Error);
  try {
    (void)readTabFile(dir.dir.string());
    ADD_FAILURE() << "read a directory";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("not a regular file"), std::string::npos) << e.what();
  }
}

TEST(TabFile, TexelsOverTheTextureBudgetAreRefusedBeforeBeingRead) {
  TempDir dir;
  writeTabFile(handMadeScene(), dir / "scene.tab");
  ResourceLimits limits;
  limits.modelTextureBytes = 100;  // the scene holds 3 x 84 + 12 = 264 texel bytes
  try {
    (void)readTabFile(dir / "scene.tab", limits);
    ADD_FAILURE() << "accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("needs 264 B of texels"), std::string::npos) << e.what();
  }
}

// Random byte flips, truncations and flips with repaired checksums (which reach the decoder and the
// validator): every input is either accepted or refused with an Error, never anything else.
TEST(TabFile, RandomCorruptionsOnlyEverThrowError) {
  TempDir dir;
  const std::vector<uint8_t> f = encodeTabFile(handMadeScene());
  std::mt19937 rng(12345);
  int accepted = 0, refused = 0;
  for (int i = 0; i < 900; ++i) {
    std::vector<uint8_t> g = f;
    const int mode = i % 3;
    if (mode == 0) {
      g.resize(rng() % (f.size() + 1));
    } else {
      const int flips = 1 + int(rng() % 4);
      for (int k = 0; k < flips; ++k) {
        // Mostly in the small sections, where a flip changes a count, an index or an enum.
        const size_t at = rng() % 2 ? rng() % g.size() : kTabHeaderSize + rng() % (g.size() - kTabHeaderSize);
        g[at] ^= uint8_t(1u << (rng() % 8));
      }
      if (mode == 2) fixChecksums(g);
    }
    spit(dir / "scene.tab", g);
    try {
      (void)readTabFile(dir / "scene.tab");
      ++accepted;
    } catch (const Error& e) {
      ++refused;
      ASSERT_NE(std::string(e.what()).find(dir / "scene.tab"), std::string::npos) << e.what();
    }
  }
  EXPECT_GT(refused, 600);
  EXPECT_EQ(accepted + refused, 900);
}

}  // namespace
}  // namespace tessera::batching
