// The public entry points of visibility.h: oracle render, cast + judgement, JSON.
#include "verify/visibility.h"

#include <cmath>
#include <cstring>
#include <variant>

#include "raster/cpu_backend.h"
#include "raster/validate.h"
#include "verify/embree_trace.h"
#include "verify/json_number.h"
#include "verify/visibility_check.h"
#include "verify/visibility_rewrite.h"
#include "verify/visibility_scene.h"

namespace tessera::verify {

namespace {

std::vector<uint32_t> readUintPlane(const TextureData& tex, uint32_t level, uint32_t layer, int32_t w, int32_t h) {
  std::vector<uint32_t> out(size_t(w) * size_t(h));
  for (int32_t y = 0; y < h; ++y)
    for (int32_t x = 0; x < w; ++x)
      std::memcpy(&out[size_t(y) * size_t(w) + size_t(x)], tex.texel(level, layer, uint32_t(x), uint32_t(y)), 4);
  return out;
}

// Cast and judge a list that has been validated already.
VisibilityResult castAndJudge(const CommandList& list, const IdImages& oracle, const VisibilityOptions& options) {
  const VisibilityScene scene = buildVisibilityScene(list);
  const EmbreeImage cast = traceScene(scene, options.isas, options.threads);
  return classifyVisibility(scene, cast, oracle, options);
}

}  // namespace

IdImages renderOracleIds(const CommandList& list, int threads, const ResourceLimits& limits) {
  CpuBackend backend(RenderOptions{threads, false, limits});
  backend.execute(list, "visibility");
  IdImages ids;
  const TextureData* planes[2] = {nullptr, nullptr};
  PresentedImage where[2];
  for (const PresentedImage& p : backend.presented()) {
    if (p.attachment >= 2) continue;
    planes[p.attachment] = backend.texture(p.texture);
    where[p.attachment] = p;
  }
  for (int a = 0; a < 2; ++a)
    if (!planes[a] || planes[a]->desc.format != Format::R32UI)
      throw Error("visibility: attachment " + std::to_string(a) + " of the presented target is not an R32UI image");
  ids.width = int32_t(levelWidth(planes[0]->desc, where[0].level));
  ids.height = int32_t(levelHeight(planes[0]->desc, where[0].level));
  ids.object = readUintPlane(*planes[0], where[0].level, where[0].layer, ids.width, ids.height);
  ids.primitive = readUintPlane(*planes[1], where[1].level, where[1].layer, ids.width, ids.height);
  // The depth attachment of the final target (presented() lists colour attachments only).
  const RenderTarget* last = nullptr;
  for (const Command& c : list.commands())
    if (const auto* t = std::get_if<SetRenderTarget>(&c)) last = &t->target;
  if (last && last->depth != kNone) {
    const TextureData* d = backend.texture(last->depth);
    const uint32_t layer = last->layer == kLayered ? 0 : last->layer;
    const std::vector<uint32_t> bits = readUintPlane(*d, last->level, layer, ids.width, ids.height);
    ids.depth.resize(bits.size());
    std::memcpy(ids.depth.data(), bits.data(), bits.size() * sizeof(float));
  }
  return ids;
}

VisibilityResult compareVisibility(const CommandList& list, const IdImages& oracle, const VisibilityOptions& options) {
  validateOrThrow(list, "visibility", options.limits);
  return castAndJudge(list, oracle, options);
}

VisibilityResult castVisibility(const CommandList& list, const VisibilityOptions& options) {
  // A frame not drawn with object_id is checked through its object_id rewrite (same geometry and
  // state; visibility_rewrite.h), which validates the list first.
  if (needsObjectIdRewrite(list)) {
    const CommandList rewritten = rewriteToObjectIds(list, "visibility", options.limits);
    const IdImages oracle = renderOracleIds(rewritten, options.threads, options.limits);
    VisibilityResult r = castAndJudge(rewritten, oracle, options);
    r.rewrittenToObjectId = true;
    return r;
  }
  // CpuBackend::execute validates the list (and throws naming the command) before rendering.
  const IdImages oracle = renderOracleIds(list, options.threads, options.limits);
  return castAndJudge(list, oracle, options);
}

nlohmann::json visibilityToJson(const VisibilityResult& r, bool includeTiming) {
  nlohmann::json j;
  j["scope"] = "draws to the presented render target (object_id, depth LESS/LEQUAL), one ray per pixel centre";
  j["width"] = r.width;
  j["height"] = r.height;
  j["rewritten_to_object_id"] = r.rewrittenToObjectId;
  if (r.rewrittenToObjectId) j["object_id_rule"] = "object id = the draw's index in the frame (Draw commands from 0)";
  j["draws"] = r.draws;
  j["triangles"] = r.triangles;
  j["primitives_clipped"] = r.primitivesClipped;
  j["pixels"] = r.pixels;
  j["matching"] = r.matching;
  j["exact_match_percent"] = r.exactMatchPercent;
  j["mismatches"] = r.mismatches;
  j["background_mismatches"] = r.backgroundMismatches;
  j["explained_edge"] = r.explainedEdge;
  j["explained_depth_tie"] = r.explainedDepthTie;
  j["explained_reference"] = r.explainedReference;
  j["unexplained"] = r.unexplained;
  j["edge_epsilon_px"] = r.edgeEpsilon;
  j["max_edge_distance_used_px"] = r.maxEdgeDistanceUsed;
  j["max_depth_tie_used"] = r.maxDepthTieUsed;
  j["depth"] = {
      {"checked", r.depthChecked}, {"max_abs_diff", r.depthMaxAbsDiff}, {"out_of_tolerance", r.depthOutOfTolerance}};
  nlohmann::json list = nlohmann::json::array();
  for (const UnexplainedPixel& u : r.firstUnexplained) {
    list.push_back(
        {{"x", u.x},
         {"y", u.y},
         {"file_y", r.height - 1 - u.y},
         {"oracle",
          {{"object", u.oracleObject}, {"primitive", u.oraclePrimitive}, {"depth", jsonNumber(u.oracleDepth)}}},
         {"embree",
          {{"object", u.embreeObject}, {"primitive", u.embreePrimitive}, {"depth", jsonNumber(u.embreeDepth)}}},
         {"edge_distance_px", jsonNumber(u.edgeDistance)},
         {"reason", u.reason}});
  }
  j["first_unexplained"] = list;
  j["embree"] = {{"version", r.embreeVersion}, {"isa", r.embreeIsa}};
  if (includeTiming) j["timing_ms"] = {{"build", r.buildMs}, {"cast", r.castMs}};
  return j;
}

}  // namespace tessera::verify
