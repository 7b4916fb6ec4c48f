// validateTabScene (tab_file.h): the rules of docs/tab-format.md, "What the reader checks", that concern
// the decoded scene. Each rule is one the batcher follows, so every scene it builds passes, and each
// protects a consumer (the recorders, `tab info`) that indexes without further checks.
#include <fmt/format.h>

#include <cmath>
#include <string>

#include "base/error.h"
#include "batching/tab_file.h"
#include "raster/command_list.h"
#include "raster/limits.h"

namespace tessera::batching {

namespace {

std::string at(const std::string& record, uint64_t i) { return record + "[" + std::to_string(i) + "]"; }
std::string num(double v) { return fmt::format("{}", v); }
std::string n(uint64_t v) { return std::to_string(v); }

const char* wrapName(WrapMode w) {
  switch (w) {
    case WrapMode::Repeat:
      return "repeat";
    case WrapMode::ClampToEdge:
      return "clamp";
    case WrapMode::MirroredRepeat:
      return "mirrored-repeat";
  }
  return "?";
}
std::string keyText(const ArrayKey& k) {
  return n(k.width) + " x " + n(k.height) + (k.format == TexelFormat::RGBA8 ? " RGBA8 " : " ? ") + wrapName(k.wrapS) +
         "/" + wrapName(k.wrapT);
}
ArrayKey keyOf(const TabTexture& t) { return ArrayKey{t.width, t.height, t.format, t.wrapS, t.wrapT}; }

class Validator {
 public:
  Validator(const TabScene& s, const std::string& path) : s_(s), path_(path) {}

  void run() {
    params();
    counts();
    textures();
    arrays();
    meshes();  // before batches: the geometry batches are checked against the meshes
    batches();
    vertices();
  }

 private:
  [[noreturn]] void fail(const std::string& field, const std::string& why) const {
    throw Error(path_ + ": " + field + ": " + why);
  }

  void params() const {
    const TabParams& p = s_.params;
    if (p.bMax <= 3) fail("params.b_max", n(p.bMax) + " is not above 3 (a geometry batch holds at least a triangle)");
    if (p.dMax < 1 || p.dMax > uint32_t(kMaxArrayLayers))
      fail("params.d_max", n(p.dMax) + " is outside [1, " + n(kMaxArrayLayers) + "] (GL_MAX_ARRAY_TEXTURE_LAYERS)");
    if (p.aMax < 1 || p.aMax > kMaxTabArrays)
      fail("params.a_max", n(p.aMax) + " is outside [1, " + n(kMaxTabArrays) + "] (texarray_batch's array units)");
    for (float b : s_.bounds)
      if (!std::isfinite(b)) fail("bounds", num(b) + " is not finite");
    for (int k = 0; k < 3; ++k)
      if (!(s_.bounds[size_t(k)] <= s_.bounds[size_t(k) + 3]))
        fail("bounds", "min " + num(s_.bounds[size_t(k)]) + " > max " + num(s_.bounds[size_t(k) + 3]) + " on axis " +
                           n(uint64_t(k)));
  }

  // Every count is a u32 in the file (and vertex ranges are u32).
  void counts() const {
    auto fits = [&](const std::string& f, uint64_t c) {
      if (c > UINT32_MAX) fail(f, n(c) + " entries do not fit the format's 32-bit count");
    };
    fits("textures", s_.textures.size()), fits("arrays", s_.arrays.size()), fits("batches", s_.batches.size());
    fits("meshes", s_.meshes.size()), fits("vertices", s_.vertices.size()), fits("source", s_.source.size());
  }

  void textures() const {
    for (size_t i = 0; i < s_.textures.size(); ++i) {
      const TabTexture& t = s_.textures[i];
      const std::string f = at("textures", i);
      if (t.name.size() > UINT32_MAX) fail(f + ".name", "longer than 2^32 - 1 bytes");
      if (t.width < 1 || t.width > uint32_t(kMaxTextureSize) || t.height < 1 || t.height > uint32_t(kMaxTextureSize))
        fail(f + ".size", n(t.width) + " x " + n(t.height) + " is outside [1, " + n(kMaxTextureSize) + "] per axis");
      if (t.format != TexelFormat::RGBA8) fail(f + ".format", n(uint8_t(t.format)) + " is not 0 (RGBA8)");
      if (uint8_t(t.wrapS) > 2) fail(f + ".wrap_s", n(uint8_t(t.wrapS)) + " is not 0, 1 or 2");
      if (uint8_t(t.wrapT) > 2) fail(f + ".wrap_t", n(uint8_t(t.wrapT)) + " is not 0, 1 or 2");
      const uint32_t full = fullMipCount(t.width, t.height);
      if (t.levels.size() != full)
        fail(f + ".levels", n(t.levels.size()) + ", but a full mip chain of " + n(t.width) + " x " + n(t.height) +
                                " has " + n(full) + " levels");
      const TextureDesc d{TextureKind::Tex2D, Format::RGBA8, t.width, t.height, 1, full};
      for (uint32_t l = 0; l < full; ++l)
        if (t.levels[l].size() != levelBytes(d, l))
          fail(at(f + ".levels", l), n(t.levels[l].size()) + " bytes, but level " + n(l) + " of " + n(t.width) + " x " +
                                         n(t.height) + " RGBA8 is " + n(levelBytes(d, l)));
    }
  }

  void arrays() const {
    for (size_t i = 0; i < s_.arrays.size(); ++i) {
      const TextureArray& a = s_.arrays[i];
      const std::string f = at("arrays", i);
      const ArrayKey& k = a.key;
      if (k.width < 1 || k.width > uint32_t(kMaxTextureSize) || k.height < 1 || k.height > uint32_t(kMaxTextureSize))
        fail(f + ".size", n(k.width) + " x " + n(k.height) + " is outside [1, " + n(kMaxTextureSize) + "] per axis");
      if (k.format != TexelFormat::RGBA8) fail(f + ".format", n(uint8_t(k.format)) + " is not 0 (RGBA8)");
      if (uint8_t(k.wrapS) > 2 || uint8_t(k.wrapT) > 2) fail(f + ".wrap", "a wrap mode is not 0, 1 or 2");
      if (a.layers.empty()) fail(f + ".layers", "none (an array holds at least one layer)");
      if (a.layers.size() > s_.params.dMax)
        fail(f + ".layers", n(a.layers.size()) + " layers, over params.d_max = " + n(s_.params.dMax));
      for (size_t l = 0; l < a.layers.size(); ++l) {
        const uint32_t t = a.layers[l];
        if (t >= s_.textures.size())
          fail(at(f + ".layers", l), "texture " + n(t) + " does not exist (" + n(s_.textures.size()) + " textures)");
        if (keyOf(s_.textures[t]) != k)
          fail(at(f + ".layers", l),
               "texture " + n(t) + " is " + keyText(keyOf(s_.textures[t])) + ", but the array holds " + keyText(k));
      }
    }
  }

  // Meshes are in drawing order: batched, then untextured, then BLEND; their vertex ranges follow each
  // other from 0 and cover every vertex, 3 per triangle.
  void meshes() {
    uint64_t end = 0;
    for (size_t i = 0; i < s_.meshes.size(); ++i) {
      const TabMesh& m = s_.meshes[i];
      const std::string f = at("meshes", i);
      if (m.name.size() > UINT32_MAX || m.textures.size() > UINT32_MAX)
        fail(f, "a string or list is longer than 2^32 - 1");
      if (uint8_t(m.kind) > 2) fail(f + ".kind", n(uint8_t(m.kind)) + " is not 0, 1 or 2");
      if (uint8_t(m.alphaMode) > 2) fail(f + ".alpha_mode", n(uint8_t(m.alphaMode)) + " is not 0, 1 or 2");
      if (i > 0 && m.kind < s_.meshes[i - 1].kind)
        fail(f + ".kind", n(uint8_t(m.kind)) + " after a mesh of kind " + n(uint8_t(s_.meshes[i - 1].kind)) +
                              " (batched meshes come first, then untextured, then BLEND)");
      if (m.kind == MeshKind::Batched) ++batched_;
      if (m.firstVertex != end)
        fail(f + ".first_vertex", n(m.firstVertex) + ", expected " + n(end) + " (where the previous mesh ends)");
      if (m.vertexCount % 3 != 0)
        fail(f + ".vertex_count", n(m.vertexCount) + " is not a multiple of 3 (3 vertices per triangle)");
      end += m.vertexCount;
      if (end > s_.vertices.size())
        fail(f + ".vertex_count", "vertices [" + n(m.firstVertex) + ", +" + n(m.vertexCount) + ") run past the " +
                                      n(s_.vertices.size()) + " vertices");
      for (size_t u = 0; u < m.textures.size(); ++u)
        if (m.textures[u] >= s_.textures.size())
          fail(at(f + ".textures", u),
               "texture " + n(m.textures[u]) + " does not exist (" + n(s_.textures.size()) + " textures)");
      for (float c : m.factor)
        if (!std::isfinite(c)) fail(f + ".factor", num(c) + " is not finite");
      if (!std::isfinite(m.alphaCutoff)) fail(f + ".alpha_cutoff", num(m.alphaCutoff) + " is not finite");
      if (m.kind == MeshKind::Untextured && !m.textures.empty())
        fail(f + ".textures", n(m.textures.size()) + " textures on an untextured mesh");
      if (m.kind == MeshKind::Blend && m.textures.empty())
        fail(f + ".textures", "none on a BLEND mesh (it is drawn with its texture; untextured meshes are drawn flat)");
      if (m.kind == MeshKind::Batched) batchedMesh(m, f);
    }
    if (end != s_.vertices.size()) fail("meshes", "cover " + n(end) + " of the " + n(s_.vertices.size()) + " vertices");
  }

  // A batched mesh's place in its output batch; its TAM entries are checked in batches().
  void batchedMesh(const TabMesh& m, const std::string& f) const {
    if (m.textures.empty()) fail(f + ".textures", "none on a batched mesh");
    if (m.alphaMode == AlphaMode::Blend)
      fail(f + ".alpha_mode", "BLEND on a batched mesh (BLEND meshes stay unbatched)");
    if (m.outputBatch >= s_.batches.size())
      fail(f + ".output_batch", n(m.outputBatch) + " does not exist (" + n(s_.batches.size()) + " output batches)");
    if (m.tamIndex >= kMaxTamIndex)
      fail(f + ".tam_index", n(m.tamIndex) + " is not below 2^24 (exact in a float texcoord)");
    const uint64_t tam = s_.batches[m.outputBatch].tam.size();
    if (uint64_t(m.tamIndex) + m.textures.size() > tam)
      fail(f + ".tam_index", n(m.tamIndex) + " + " + n(m.textures.size()) + " units runs past batch " +
                                 n(m.outputBatch) + "'s " + n(tam) + " TAM entries");
  }

  void batches() const {
    uint64_t nextMesh = 0;  // geometry batches take the batched meshes in order, each exactly once
    for (size_t b = 0; b < s_.batches.size(); ++b) {
      const OutputBatch& ob = s_.batches[b];
      const std::string f = at("batches", b);
      if (ob.arrays.size() > s_.params.aMax)
        fail(f + ".arrays", n(ob.arrays.size()) + " arrays, over params.a_max = " + n(s_.params.aMax));
      for (size_t k = 0; k < ob.arrays.size(); ++k)
        if (ob.arrays[k] >= s_.arrays.size())
          fail(at(f + ".arrays", k),
               "array " + n(ob.arrays[k]) + " does not exist (" + n(s_.arrays.size()) + " arrays)");
      if (ob.tam.size() > kMaxTamIndex)
        fail(f + ".tam", n(ob.tam.size()) + " entries, over 2^24 (i_TAM must be exact in a float)");
      for (size_t k = 0; k < ob.tam.size(); ++k) {
        const TamEntry& e = ob.tam[k];
        const std::string tf = at(f + ".tam", k);
        if (e.array >= ob.arrays.size())
          fail(tf + ".array", n(e.array) + " is not below the batch's " + n(ob.arrays.size()) + " arrays");
        const size_t layers = s_.arrays[ob.arrays[e.array]].layers.size();
        if (e.layer >= layers) fail(tf + ".layer", n(e.layer) + " is not below the array's " + n(layers) + " layers");
        for (float c : e.factor)
          if (!std::isfinite(c)) fail(tf + ".factor", num(c) + " is not finite");
        if (!std::isfinite(e.alphaCutoff)) fail(tf + ".alpha_cutoff", num(e.alphaCutoff) + " is not finite");
      }
      if (ob.geometry.size() > UINT32_MAX) fail(f + ".geometry", "more than 2^32 - 1 geometry batches");
      for (size_t k = 0; k < ob.geometry.size(); ++k) geometry(ob.geometry[k], b, at(f + ".geometry", k), nextMesh);
    }
    if (nextMesh != batched_)
      fail("batches", "the geometry batches hold " + n(nextMesh) + " meshes, but " + n(batched_) + " are batched");
    // Each batched mesh's entries name layers holding its textures, unit by unit.
    for (size_t i = 0; i < batched_; ++i) {
      const TabMesh& m = s_.meshes[i];
      const OutputBatch& ob = s_.batches[m.outputBatch];
      for (size_t u = 0; u < m.textures.size(); ++u) {
        const TamEntry& e = ob.tam[m.tamIndex + u];
        const uint32_t t = s_.arrays[ob.arrays[e.array]].layers[e.layer];
        if (t != m.textures[u])
          fail(at("meshes", i) + ".tam_index", "unit " + n(u) + "'s entry batches[" + n(m.outputBatch) + "].tam[" +
                                                   n(m.tamIndex + u) + "] holds texture " + n(t) +
                                                   ", but the mesh uses texture " + n(m.textures[u]));
      }
    }
  }

  void geometry(const GeometryBatch& g, size_t b, const std::string& f, uint64_t& nextMesh) const {
    if (g.meshCount == 0) fail(f + ".mesh_count", "0 (a geometry batch draws at least one mesh)");
    if (g.firstMesh != nextMesh)
      fail(f + ".first_mesh",
           n(g.firstMesh) + ", expected " + n(nextMesh) + " (where the previous geometry batch ends)");
    if (uint64_t(g.firstMesh) + g.meshCount > batched_)
      fail(f + ".mesh_count",
           "meshes [" + n(g.firstMesh) + ", +" + n(g.meshCount) + ") run past the " + n(batched_) + " batched meshes");
    uint64_t vertices = 0;
    for (uint32_t i = g.firstMesh; i < g.firstMesh + g.meshCount; ++i) {
      if (s_.meshes[i].outputBatch != b)
        fail(f + ".first_mesh",
             "mesh " + n(i) + " belongs to output batch " + n(s_.meshes[i].outputBatch) + ", not " + n(b));
      vertices += s_.meshes[i].vertexCount;
    }
    if (g.firstVertex != s_.meshes[g.firstMesh].firstVertex)
      fail(f + ".first_vertex",
           n(g.firstVertex) + ", but its first mesh starts at " + n(s_.meshes[g.firstMesh].firstVertex));
    if (g.vertexCount != vertices) fail(f + ".vertex_count", n(g.vertexCount) + ", but its meshes hold " + n(vertices));
    if (g.vertexCount > s_.params.bMax && g.meshCount > 1)
      fail(f + ".vertex_count", n(g.vertexCount) + " vertices in " + n(g.meshCount) + " meshes, over params.b_max = " +
                                    n(s_.params.bMax) + " (only a mesh alone may exceed it)");
    nextMesh += g.meshCount;
  }

  void vertices() const {
    const auto& B = s_.bounds;
    for (size_t i = 0; i < s_.meshes.size(); ++i) {
      const TabMesh& m = s_.meshes[i];
      const float index = m.kind == MeshKind::Batched ? float(m.tamIndex) : 0.0f;
      for (uint32_t v = m.firstVertex; v < m.firstVertex + m.vertexCount; ++v) {
        const Vertex& x = s_.vertices[v];
        // The field name is built only on failure: this loop runs once per vertex.
        auto f = [v](const char* field) { return fmt::format("vertices[{}]{}", v, field); };
        const float c[6] = {x.x, x.y, x.z, x.s, x.t, x.index};
        for (float y : c)
          if (!std::isfinite(y)) fail(f(""), fmt::format("{} is not finite", y));
        if (!(x.index >= 0.0f && x.index < float(kMaxTamIndex) && x.index == std::floor(x.index)))
          fail(f(".index"), fmt::format("{} is not an integer in [0, 2^24)", x.index));
        if (x.index != index)
          fail(f(".index"), fmt::format("{}, but mesh {} has i_TAM {}{}", x.index, i, index,
                                        m.kind == MeshKind::Batched ? "" : " (unbatched meshes carry 0)"));
        if (!(x.x >= B[0] && x.y >= B[1] && x.z >= B[2] && x.x <= B[3] && x.y <= B[4] && x.z <= B[5]))
          fail(f(""), fmt::format("({}, {}, {}) is outside the scene's bounds", x.x, x.y, x.z));
      }
    }
  }

  const TabScene& s_;
  const std::string& path_;
  uint64_t batched_ = 0;
};

}  // namespace

void validateTabScene(const TabScene& scene, const std::string& path) { Validator(scene, path).run(); }

}  // namespace tessera::batching
