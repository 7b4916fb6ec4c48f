#include "mta/scene.h"

#include <cmath>
#include <map>
#include <tuple>

#include "base/error.h"

namespace tessera::mta {

void Scene::validate() const {
  const size_t n = geometry.triangleCount();
  auto fail = [&](const std::string& what) { throw Error("mta scene '" + name + "': " + what); };
  if (geometry.positions.size() != n * 3) fail("positions are not 3 per triangle");
  if (geometry.source.size() != n || geometry.alpha.size() != n) fail("source/alpha arrays are not one per triangle");
  if (geometry.layers.empty()) fail("no texture layer");
  for (size_t l = 0; l < geometry.layers.size(); ++l) {
    const SceneLayer& L = geometry.layers[l];
    if (L.texture.size() != n || L.uv.size() != n * 3) fail("layer " + std::to_string(l) + ": arrays do not match the triangle count");
    for (size_t t = 0; t < n; ++t) {
      if (L.texture[t] < -1 || L.texture[t] >= int64_t(textures.size()))
        fail("layer " + std::to_string(l) + " triangle " + std::to_string(t) + ": texture " + std::to_string(L.texture[t]) + " out of range");
      for (int k = 0; k < 3; ++k)
        if (!std::isfinite(L.uv[t * 3 + k].x) || !std::isfinite(L.uv[t * 3 + k].y))
          fail("layer " + std::to_string(l) + " triangle " + std::to_string(t) + ": non-finite texcoord");
    }
  }
  for (size_t i = 0; i < geometry.positions.size(); ++i) {
    const glm::vec3& p = geometry.positions[i];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) fail("triangle " + std::to_string(i / 3) + ": non-finite position");
  }
  for (size_t t = 0; t < textures.size(); ++t) {
    if (textures[t].image >= images.size()) fail("texture " + std::to_string(t) + ": image index out of range");
  }
  for (size_t i = 0; i < images.size(); ++i)
    if (images[i].width == 0 || images[i].height == 0 || images[i].width > 65536 || images[i].height > 65536)
      fail("image " + std::to_string(i) + " '" + images[i].name + "': size " + std::to_string(images[i].width) + "x" +
           std::to_string(images[i].height) + " outside [1, 65536]");
}

Scene sceneFromModel(std::shared_ptr<const model::Model> m) {
  Scene s;
  s.name = m->source;
  s.images.resize(m->textures.size());
  for (size_t i = 0; i < m->textures.size(); ++i) {
    const model::TextureInfo info = model::probeTexture(*m, i);
    s.images[i] = SceneImage{info.width, info.height, m->textures[i].name};
  }
  std::map<std::tuple<uint32_t, int, int>, int32_t> texIndex;  // (image, wrapS, wrapT) -> texture, in first-use order
  auto textureOf = [&](int32_t image, model::Wrap wrapS, model::Wrap wrapT) {
    const auto key = std::make_tuple(uint32_t(image), int(wrapS), int(wrapT));
    auto it = texIndex.find(key);
    if (it == texIndex.end()) {
      it = texIndex.emplace(key, int32_t(s.textures.size())).first;
      s.textures.push_back(SceneTexture{uint32_t(image), wrapS, wrapT});
    }
    return it->second;
  };
  // A glTF occlusionTexture is layer 1 (thesis §5.1.3), read from its own texcoord set; the layer exists
  // when any material has one, and triangles of the others have none in it (-1).
  bool occlusion = false;
  for (const model::Mesh& mesh : m->meshes)
    occlusion = occlusion || (m->materials[mesh.material].occlusionTexture >= 0 && !mesh.occlusionTexcoords.empty());
  Geometry& g = s.geometry;
  g.layers.resize(occlusion ? 2 : 1);
  for (const model::Mesh& mesh : m->meshes) {
    const model::Material& mat = m->materials[mesh.material];
    const int32_t tex =
        mat.baseColorTexture >= 0 && !mesh.texcoords.empty() ? textureOf(mat.baseColorTexture, mat.wrapS, mat.wrapT) : -1;
    const int32_t occ = occlusion && mat.occlusionTexture >= 0 && !mesh.occlusionTexcoords.empty()
                            ? textureOf(mat.occlusionTexture, mat.occlusionWrapS, mat.occlusionWrapT)
                            : -1;
    const uint8_t alpha = mat.alphaMode == model::AlphaMode::Opaque ? 0 : 1;
    for (size_t t = 0; t < mesh.triangleCount(); ++t) {
      for (int k = 0; k < 3; ++k) {
        const uint32_t idx = mesh.indices[t * 3 + k];
        g.positions.push_back(mesh.positions[idx]);
        g.layers[0].uv.push_back(tex >= 0 ? mesh.texcoords[idx] : glm::vec2{});
        if (occlusion) g.layers[1].uv.push_back(occ >= 0 ? mesh.occlusionTexcoords[idx] : glm::vec2{});
      }
      g.layers[0].texture.push_back(tex);
      if (occlusion) g.layers[1].texture.push_back(occ);
      g.source.push_back(uint32_t(g.source.size()));
      g.alpha.push_back(alpha);
    }
  }
  s.loadImage = [m](uint32_t image) { return model::loadTexture(*m, image); };
  s.describeTriangle = [m](uint32_t source) {
    uint64_t k = source;  // the triangles follow the meshes' order (above)
    for (size_t i = 0; i < m->meshes.size(); ++i) {
      if (k < m->meshes[i].triangleCount())
        return "mesh '" + m->meshes[i].name + "' (" + std::to_string(i) + ") triangle " + std::to_string(k);
      k -= m->meshes[i].triangleCount();
    }
    return "input triangle " + std::to_string(source);
  };
  s.validate();
  return s;
}

}  // namespace tessera::mta
