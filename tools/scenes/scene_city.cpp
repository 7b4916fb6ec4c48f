// city_block and city_ids: the procedural city of city_model.h. city_block binds each building's
// facade texture before its draw (one texture state change per building: the workload the texture
// management techniques reduce); city_ids renders the same geometry through "object_id" into two
// R32UI targets (object id; primitive id within the draw), background 0xffffffff.
#include "tools/scenes/city_model.h"
#include "tools/scenes/scene_common.h"

namespace tessera::scenes {

namespace {
constexpr int kGrid = 16;  // 256 buildings, 256 facade textures
constexpr uint64_t kSeed = 2005;
}  // namespace

void buildCityBlock(CommandList& cl, int w, int h) {
  const CityModel city = makeCity(kGrid, w, h, kSeed);
  beginFrame(cl, w, h, true, {0.55f, 0.7f, 0.9f, 1});
  bindMesh(cl, city.mesh);
  cl.useProgram(cl.createProgram("textured"));
  setMatrix(cl, 0, city.viewProj);
  setTexturedDefaults(cl);
  DepthState ds;
  ds.test = true;
  cl.setDepthState(ds);
  RasterState rs;
  rs.cull = CullMode::Back;
  cl.setRasterState(rs);
  SamplerState s;
  s.minFilter = Filter::LinearMipmapLinear;
  cl.bindSampler(0, cl.createSampler(s));
  cl.bindTexture(0, uploadTexture(cl, city.road, true));
  cl.drawIndexed(0, city.groundIndexCount);
  std::vector<ResourceId> textures;
  for (const RgbaImage& img : city.facades) textures.push_back(uploadTexture(cl, img, true));
  for (size_t b = 0; b < city.buildings.size(); ++b) {
    cl.bindTexture(0, textures[b]);
    cl.drawIndexed(city.buildings[b].first, city.buildings[b].second);
  }
}

void buildCityIds(CommandList& cl, int w, int h) {
  const CityModel city = makeCity(kGrid, w, h, kSeed);
  RenderTarget t;
  t.color[0] = createTarget(cl, Format::R32UI, w, h);
  t.color[1] = createTarget(cl, Format::R32UI, w, h);
  t.depth = createTarget(cl, Format::D32F, w, h);
  cl.setRenderTarget(t);
  cl.setViewport({0, 0, w, h});
  cl.clearColorUint(0, {0xffffffffu, 0, 0, 0});
  cl.clearColorUint(1, {0xffffffffu, 0, 0, 0});
  cl.clearDepth(1.0f);
  const uint32_t n = bindMesh(cl, city.mesh);
  cl.useProgram(cl.createProgram("object_id"));
  setMatrix(cl, 0, city.viewProj);
  DepthState ds;
  ds.test = true;
  cl.setDepthState(ds);
  RasterState rs;
  rs.cull = CullMode::Back;
  cl.setRasterState(rs);
  cl.drawIndexed(0, n);
}

}  // namespace tessera::scenes
