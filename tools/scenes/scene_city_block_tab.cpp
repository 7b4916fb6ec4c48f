// city_block_tab: city_block's 256 buildings and ground batched with texture arrays (Trapp & Döllner
// 2015) through the batching library itself: Algorithm 1 puts the 256 facade textures (64x64, REPEAT)
// into one 256-layer array and the road into a second, and Algorithm 2 draws ground and buildings in
// ONE draw call with texarray_batch (TAM material layout). The same geometry as city_block, made
// non-indexed, without back-face culling (tab_record.h draws no culling state), so it is a scene of its
// own rather than an image of city_block.
#include "batching/batcher.h"
#include "batching/tab_record.h"
#include "raster/texture.h"
#include "tools/scenes/city_model.h"
#include "tools/scenes/scene_common.h"

namespace tessera::scenes {

void buildCityBlockTab(CommandList& cl, int w, int h) {
  const CityModel city = makeCity(16, w, h, 2005);  // city_block's grid and seed
  batching::TabScene s;
  auto addTexture = [&](const RgbaImage& img) {
    batching::TabTexture t;
    t.width = img.width, t.height = img.height;
    t.levels = buildMipChainRGBA8(img.width, img.height, img.rgba);
    s.textures.push_back(std::move(t));
  };
  addTexture(city.road);
  for (const RgbaImage& img : city.facades) addTexture(img);
  auto addMesh = [&](uint32_t firstIndex, uint32_t count, uint32_t texture) {
    batching::TabMesh m;
    m.modelMesh = uint32_t(s.meshes.size());
    m.firstVertex = uint32_t(s.vertices.size());
    m.vertexCount = count;
    m.textures = {texture};
    for (uint32_t k = 0; k < count; ++k) {
      const Vertex& v = city.mesh.vertices[city.mesh.indices[firstIndex + k]];
      s.vertices.push_back({v.pos.x, v.pos.y, v.pos.z, v.attr.x, v.attr.y, 0.0f});
    }
    s.meshes.push_back(std::move(m));
  };
  addMesh(0, city.groundIndexCount, 0);
  for (size_t b = 0; b < city.buildings.size(); ++b) addMesh(city.buildings[b].first, city.buildings[b].second, uint32_t(1 + b));
  batching::runAlgorithm1(s, batching::TabParams{});
  batching::TabView view;
  view.mvp = city.viewProj;
  view.width = uint32_t(w), view.height = uint32_t(h);
  view.clear = {0.55f, 0.7f, 0.9f, 1};
  cl = batching::recordTabFrame(s, batching::Variant::Batched, view);
}

}  // namespace tessera::scenes
