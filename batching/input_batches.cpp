#include "batching/input_batches.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <mutex>
#include <tuple>

#include "base/error.h"
#include "raster/texture.h"

namespace tessera::batching {

namespace {

WrapMode toWrap(model::Wrap w) {
  switch (w) {
    case model::Wrap::Repeat: return WrapMode::Repeat;
    case model::Wrap::ClampToEdge: return WrapMode::ClampToEdge;
    case model::Wrap::MirroredRepeat: return WrapMode::MirroredRepeat;
  }
  return WrapMode::Repeat;
}

AlphaMode toAlpha(model::AlphaMode a) {
  switch (a) {
    case model::AlphaMode::Opaque: return AlphaMode::Opaque;
    case model::AlphaMode::Mask: return AlphaMode::Mask;
    case model::AlphaMode::Blend: return AlphaMode::Blend;
  }
  return AlphaMode::Opaque;
}

struct Candidate {
  uint32_t mesh = 0;
  MeshKind kind = MeshKind::Untextured;
  int32_t image = -1;  // model texture index, -1 untextured
  WrapMode wrapS = WrapMode::Repeat, wrapT = WrapMode::Repeat;
  uint32_t width = 0, height = 0;  // from the image header
};

}  // namespace

TabScene prepareInput(const model::Model& model, const InputOptions& options) {
  TabScene scene;
  scene.source = std::filesystem::path(model.source).filename().string();
  std::vector<Candidate> cands;
  cands.reserve(model.meshes.size());
  for (uint32_t i = 0; i < model.meshes.size(); ++i) {
    const model::Mesh& m = model.meshes[i];
    const model::Material& mat = model.materials[m.material];
    if (m.indices.size() < 3) continue;  // no triangle: nothing to draw or batch
    Candidate c;
    c.mesh = i;
    const bool textured = mat.baseColorTexture >= 0 && !m.texcoords.empty();
    if (textured) {
      c.image = mat.baseColorTexture;
      c.wrapS = toWrap(mat.wrapS);
      c.wrapT = toWrap(mat.wrapT);
      const model::TextureInfo info = model::probeTexture(model, size_t(c.image));
      c.width = info.width;
      c.height = info.height;
    }
    // An untextured mesh is drawn flat whatever its alpha mode; a textured BLEND mesh is never batched.
    c.kind = !textured ? MeshKind::Untextured : mat.alphaMode == model::AlphaMode::Blend ? MeshKind::Blend : MeshKind::Batched;
    cands.push_back(c);
  }
  // Batched meshes in the documented key order; the stable sort keeps model order for equal keys.
  auto key = [](const Candidate& c) {
    return std::make_tuple(uint8_t(TexelFormat::RGBA8), c.width, c.height, uint8_t(c.wrapS), uint8_t(c.wrapT), c.image, c.mesh);
  };
  std::vector<Candidate> ordered;
  for (MeshKind k : {MeshKind::Batched, MeshKind::Untextured, MeshKind::Blend})
    for (const Candidate& c : cands)
      if (c.kind == k) ordered.push_back(c);
  std::stable_sort(ordered.begin(), ordered.end(), [&](const Candidate& a, const Candidate& b) {
    if (a.kind != b.kind) return a.kind < b.kind;
    return a.kind == MeshKind::Batched ? key(a) < key(b) : false;
  });

  // Textures in order of first use; one per (image, wrapS, wrapT).
  std::map<std::tuple<int32_t, uint8_t, uint8_t>, uint32_t> texIndex;
  std::vector<int32_t> texImage;
  uint64_t vertexCount = 0;
  for (const Candidate& c : ordered) {
    const model::Mesh& m = model.meshes[c.mesh];
    const model::Material& mat = model.materials[m.material];
    TabMesh tm;
    tm.name = m.name;
    tm.kind = c.kind;
    tm.modelMesh = c.mesh;
    tm.factor = mat.baseColorFactor;
    tm.alphaMode = toAlpha(mat.alphaMode);
    tm.alphaCutoff = mat.alphaCutoff;
    if (c.image >= 0) {
      auto [it, fresh] = texIndex.emplace(std::make_tuple(c.image, uint8_t(c.wrapS), uint8_t(c.wrapT)), uint32_t(scene.textures.size()));
      if (fresh) {
        TabTexture t;
        const model::TextureRef& ref = model.textures[size_t(c.image)];
        t.name = ref.uri.empty() ? ref.name : ref.uri;
        t.width = c.width;
        t.height = c.height;
        t.wrapS = c.wrapS;
        t.wrapT = c.wrapT;
        scene.textures.push_back(std::move(t));
        texImage.push_back(c.image);
      }
      tm.textures.push_back(it->second);
    }
    tm.firstVertex = uint32_t(vertexCount);
    vertexCount += m.indices.size() / 3 * 3;
    if (vertexCount > uint64_t(UINT32_MAX))
      throw Error(model.source + ": more than 2^32 - 1 vertices after un-indexing (mesh " + std::to_string(c.mesh) + ")");
    tm.vertexCount = uint32_t(vertexCount - tm.firstVertex);
    scene.meshes.push_back(std::move(tm));
  }

  scene.vertices.resize(size_t(vertexCount));
  model::Bounds bounds;
  for (const TabMesh& tm : scene.meshes) {
    const model::Mesh& m = model.meshes[tm.modelMesh];
    Vertex* out = scene.vertices.data() + tm.firstVertex;
    const bool uv = tm.kind != MeshKind::Untextured;
    for (uint32_t k = 0; k < tm.vertexCount; ++k) {
      const uint32_t idx = m.indices[k];
      const glm::vec3& p = m.positions[idx];
      const glm::vec2 st = uv ? m.texcoords[idx] : glm::vec2(0.0f);
      out[k] = Vertex{p.x, p.y, p.z, st.x, st.y, 0.0f};
      bounds.add(p);
    }
  }
  if (!bounds.empty())
    scene.bounds = {bounds.min.x, bounds.min.y, bounds.min.z, bounds.max.x, bounds.max.y, bounds.max.z};

  // Decode every texture once, in parallel; each task writes only its own entry.
  std::mutex progressMutex;
  size_t done = 0;
  tbb::parallel_for(size_t(0), scene.textures.size(), [&](size_t i) {
    const model::Image img = model::loadTexture(model, size_t(texImage[i]));
    TabTexture& t = scene.textures[i];
    if (img.width != t.width || img.height != t.height)
      throw Error(model.source + ": texture " + std::to_string(texImage[i]) + " (" + t.name + "): decoded size " +
                  std::to_string(img.width) + "x" + std::to_string(img.height) + " differs from its header's " +
                  std::to_string(t.width) + "x" + std::to_string(t.height));
    t.levels = buildMipChainRGBA8(img.width, img.height, img.rgba);
    if (options.progress) {
      const std::lock_guard<std::mutex> lock(progressMutex);
      options.progress(++done, scene.textures.size());
    }
  });
  return scene;
}

}  // namespace tessera::batching
