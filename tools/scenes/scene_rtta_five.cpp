// rtta_five, rtta_five_atlas, rtta_five_transparent, rtta_five_ghosted, rtta_five_ghosted_ao: render-to-texture-atlas through
// the rtta library itself (Trapp & Döllner 2010) on the built-in five-object brake assembly
// (model/five_objects.h, the paper's Fig. 1), seen from its default camera: Algorithm 1 (culling,
// projection, packing, transforms), the record buffer, one capture pass by screen-space vertex
// displacement (atlas_capture: colour, window depth, depth), and the composites of Fig. 3 with
// atlas_sprite: depth sprites (A), transparent back to front (B), ghosted with the pad highlighted (C),
// and ghosted with occlusion and edges on the caliper by atlas_sprite_ao (D). rtta_five_ao_post is D's
// post-process alone on exact inputs: the oracle's capture uploaded, every object drawn by
// atlas_sprite_ao, so GL must compute the program's floats (docs/rtta.md, "ghosted-ao", step 2).
// rtta_five_atlas ends on the capture target, so its atlas colour and depth layers are the presented
// images. The atlas is twice the default side, so every object lands in layer 0: softpipe misroutes
// fragments of layers >= 1 whose depth test fails into layer 0 (docs/softpipe-edge-flips.md §1), and
// these scenes are cross-checked on softpipe too.
#include "batching/input_batches.h"
#include "raster/cpu_backend.h"
#include "raster/image_io.h"
#include "model/five_objects.h"
#include "model/object_groups.h"
#include "mta/camera.h"
#include "rtta/rtta_record.h"
#include "tools/scenes/rtta_five.h"
#include "tools/scenes/scene_common.h"

namespace tessera::scenes {

namespace {

const rtta::RttaScene& fiveScene() {
  static const rtta::RttaScene s = [] {
    const model::Model m = model::fiveObjectModel();
    const auto groups = model::groupObjects(m, model::ObjectGrouping::Node);
    std::vector<uint32_t> objectOf(m.meshes.size());
    std::vector<std::string> names;
    for (uint32_t g = 0; g < groups.size(); ++g) {
      names.push_back(groups[g].name);
      for (uint32_t mesh : groups[g].meshes) objectOf[mesh] = g;
    }
    return rtta::makeRttaScene(batching::prepareInput(m), objectOf, names);
  }();
  return s;
}

}  // namespace

rtta::RttaFrame recordFive(int w, int h, rtta::Composite composite, bool captureOnly,
                           const rtta::AtlasImages* atlasInput, const std::vector<uint32_t>* important) {
  mta::Camera c;
  c.eye = model::kFiveObjectEye;
  c.target = model::kFiveObjectTarget;
  c.up = model::kFiveObjectUp;
  c.tanHalfFovX = model::kFiveObjectTanHalfFovY * double(w) / double(h);  // the model's vertical field
  c.nearPlane = model::kFiveObjectNear;
  c.farPlane = model::kFiveObjectFar;
  rtta::RttaView v;
  v.mvp = mta::viewProjection(c, uint32_t(w), uint32_t(h));
  v.eye = c.eye;
  v.width = uint32_t(w), v.height = uint32_t(h);
  rtta::RttaOptions o;
  o.mode = rtta::Mode::Rtta;
  o.composite = composite;
  o.params.border = 2;
  o.atlasWidth = 2 * rtta::defaultAtlasSide(w, o.params.border);
  o.atlasHeight = 2 * rtta::defaultAtlasSide(h, o.params.border);
  // 3C: the pad, as the paper's Fig. 3C highlights the brake pad; 3D: the caliper, whose creases show
  // the occlusion and the edges.
  o.important = important ? *important : std::vector<uint32_t>{composite == rtta::Composite::GhostedAo ? 2u : 1u};
  o.captureOnly = captureOnly;
  o.atlasInput = atlasInput;
  return rtta::recordRttaFrame(fiveScene(), v, o);
}

namespace {
void buildFive(CommandList& cl, int w, int h, rtta::Composite composite, bool captureOnly) {
  cl = recordFive(w, h, composite, captureOnly, nullptr).list;
}

}  // namespace

void buildRttaFive(CommandList& cl, int w, int h) { buildFive(cl, w, h, rtta::Composite::Depth, false); }
void buildRttaFiveAtlas(CommandList& cl, int w, int h) { buildFive(cl, w, h, rtta::Composite::Depth, true); }
void buildRttaFiveTransparent(CommandList& cl, int w, int h) { buildFive(cl, w, h, rtta::Composite::Transparent, false); }
void buildRttaFiveGhosted(CommandList& cl, int w, int h) { buildFive(cl, w, h, rtta::Composite::Ghosted, false); }
void buildRttaFiveGhostedAo(CommandList& cl, int w, int h) { buildFive(cl, w, h, rtta::Composite::GhostedAo, false); }

void buildRttaFiveAoPost(CommandList& cl, int w, int h) {
  // The oracle's own capture, rendered here and uploaded: every texel atlas_sprite_ao reads is exact.
  const rtta::RttaFrame capture = recordFive(w, h, rtta::Composite::GhostedAo, true, nullptr);
  CpuBackend b;
  b.execute(capture.list, "rtta_five_ao_post capture");
  rtta::AtlasImages atlas;
  for (const PresentedImage& p : b.presented()) {
    const TextureData& t = *b.texture(p.texture);
    std::vector<uint8_t> rows = imagePixels(t, p.level, p.layer);  // top row first
    const size_t rowBytes = size_t(t.desc.width) * texelBytes(t.desc.format);
    std::vector<uint8_t> up(rows.size());
    for (size_t r = 0; r < t.desc.height; ++r)
      std::copy_n(rows.begin() + std::ptrdiff_t((t.desc.height - 1 - r) * rowBytes), rowBytes,
                  up.begin() + std::ptrdiff_t(r * rowBytes));
    (p.texture == capture.captureColor ? atlas.color : atlas.depth).push_back(std::move(up));
  }
  const std::vector<uint32_t> all{0, 1, 2, 3, 4};
  cl = recordFive(w, h, rtta::Composite::GhostedAo, false, &atlas, &all).list;
}

}  // namespace tessera::scenes
