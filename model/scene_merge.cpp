// Merging the models of a scene (scene_manifest.h): each entry's model is read by loadModelFile(),
// transformed by the entry's matrix and appended. Shared things stay shared: a texture is the same when
// it is the same image of the same file (same source, path, byte range), a material when every field
// is the same after its texture was renumbered, so a city split into one file per building gives the
// texture and material lists of the one-file city (in order of first use).
#include <cstring>
#include <filesystem>
#include <map>
#include <tuple>

#include "base/error.h"
#include "model/loaders.h"
#include "model/scene_manifest.h"

namespace tessera::model::detail {

namespace {

// Every field of a material, floats by their bits (a NaN factor then equals itself).
std::string materialKey(const Material& m) {
  std::string k = m.name;
  k.push_back('\0');
  const auto put = [&](const void* p, size_t n) { k.append(static_cast<const char*>(p), n); };
  put(&m.baseColorTexture, sizeof m.baseColorTexture);
  put(m.baseColorFactor.data(), sizeof(float) * 4);
  put(&m.alphaMode, 1), put(&m.alphaCutoff, sizeof(float)), put(&m.doubleSided, 1), put(&m.wrapS, 1), put(&m.wrapT, 1);
  put(&m.occlusionTexture, sizeof m.occlusionTexture), put(&m.occlusionStrength, sizeof(float));
  put(&m.occlusionWrapS, 1), put(&m.occlusionWrapT, 1);
  return k;
}

class SceneBuilder {
 public:
  SceneBuilder(const Scene& scene, const ResourceLimits& limits) : scene_(scene), limits_(limits) {
    out_.loader = "scene:" + scene.kind;
  }

  Model run() {
    for (const SceneEntry& e : scene_.entries) {
      Model m;
      try {
        m = loadModelFile(e.file, limits_);
      } catch (const Error& err) {
        throw Error(scene_.path + ": " + e.where + ": " + err.what());
      }
      append(e, std::move(m));
      requireWithinBudget(scene_.path, ModelBudget::Triangles, triangles_, limits_);
      requireWithinBudget(scene_.path, ModelBudget::Vertices, vertices_, limits_);
    }
    out_.notes.insert(out_.notes.begin(), std::to_string(scene_.entries.size()) + " model files merged");
    return std::move(out_);
  }

 private:
  int32_t texture(const TextureRef& t) {
    if (t.source == TextureRef::Source::Memory) {  // embedded: nothing says two are the same image
      out_.textures.push_back(t);
      return int32_t(out_.textures.size() - 1);
    }
    const auto key = std::make_tuple(int(t.source), t.path, t.offset, t.size);
    const auto [it, added] = textures_.emplace(key, int32_t(out_.textures.size()));
    if (added) out_.textures.push_back(t);
    return it->second;
  }

  uint32_t material(Material m, const std::vector<int32_t>& textureMap) {
    if (m.baseColorTexture >= 0) m.baseColorTexture = textureMap.at(size_t(m.baseColorTexture));
    if (m.occlusionTexture >= 0) m.occlusionTexture = textureMap.at(size_t(m.occlusionTexture));
    const auto [it, added] = materials_.emplace(materialKey(m), uint32_t(out_.materials.size()));
    if (added) out_.materials.push_back(std::move(m));
    return it->second;
  }

  void append(const SceneEntry& e, Model m) {
    std::vector<int32_t> textureMap;
    for (const TextureRef& t : m.textures) textureMap.push_back(texture(t));
    std::vector<uint32_t> materialMap;
    for (const Material& mat : m.materials) materialMap.push_back(material(mat, textureMap));

    // Objects: node indices move past the earlier models' so that two models' nodes stay distinct. The
    // entry's name names a model of one object, and prefixes the objects of a model of several.
    const uint32_t objectBase = uint32_t(out_.objects.size());
    int32_t maxNode = -1;
    for (SceneObject o : m.objects) {
      maxNode = std::max(maxNode, o.node);
      if (o.node >= 0) o.node += nodeBase_;
      if (!e.name.empty()) o.name = m.objects.size() == 1 ? e.name : e.name + "/" + o.name;
      out_.objects.push_back(std::move(o));
    }
    nodeBase_ += maxNode + 1;
    if (m.objects.empty() && !m.meshes.empty())  // a model without objects is one object
      out_.objects.push_back(SceneObject{.name = e.name.empty() ? m.source : e.name, .node = -1, .instance = 0});

    const bool identity = isIdentity(e.transform), flip = det3(e.transform) < 0.0;
    for (Mesh& mesh : m.meshes) {
      mesh.material = materialMap.at(mesh.material);
      mesh.object = m.objects.empty() ? uint32_t(out_.objects.size() - 1) : objectBase + mesh.object;
      if (!identity) {
        for (glm::vec3& p : mesh.positions) p = transformPoint(e.transform, p);
        for (glm::vec3& n : mesh.normals) n = transformNormal(e.transform, n);
      }
      if (flip)
        for (size_t i = 0; i + 2 < mesh.indices.size(); i += 3) std::swap(mesh.indices[i + 1], mesh.indices[i + 2]);
      triangles_ = saturatingAdd(triangles_, mesh.triangleCount());
      vertices_ = saturatingAdd(vertices_, mesh.positions.size());
      out_.meshes.push_back(std::move(mesh));
    }
    const std::string file = std::filesystem::path(e.file).filename().string();
    for (const std::string& n : m.notes) out_.notes.push_back(file + ": " + n);
  }

  const Scene& scene_;
  const ResourceLimits& limits_;
  Model out_;
  std::map<std::tuple<int, std::string, uint64_t, uint64_t>, int32_t> textures_;
  std::map<std::string, uint32_t> materials_;
  int32_t nodeBase_ = 0;
  uint64_t triangles_ = 0, vertices_ = 0;
};

}  // namespace

Model mergeScene(const Scene& scene, const ResourceLimits& limits) { return SceneBuilder(scene, limits).run(); }

}  // namespace tessera::model::detail
