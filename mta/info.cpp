#include "mta/info.h"

#include <algorithm>

#include "base/error.h"

namespace tessera::mta {

nlohmann::json describe(const PagingFile& f, bool verifyBlocks) {
  const MtaMeta& m = f.meta();
  nlohmann::json j;
  j["format_version"] = kFormatVersion;
  j["block_encoding"] = blockEncodingName(m.encoding);  // "raw" or "s3tc" (header byte 72)
  j["file_bytes"] = f.fileSize();
  j["layers"] = m.layerCount;
  j["build_parameters"] = {{"d_min", m.params.dMin},
                           {"d_min_divisor", m.params.dMinDivisor},
                           {"tau", m.params.tau},
                           {"atlas_size", m.params.atlasSize},
                           {"border", m.params.border},
                           {"fov_degrees", m.params.fovDegrees},
                           {"tan_half_fov", m.params.tanHalfFov},
                           {"screen_width", m.params.screenWidth},
                           {"critical_threshold", m.params.criticalThreshold}};
  const BuildStats& s = m.stats;
  j["d_min_requested"] = s.dMinRequested;
  j["d_min_used"] = s.dMinUsed;
  j["scene_diagonal"] = s.sceneDiagonal;
  j["triangles_in"] = s.trianglesIn;
  j["triangles"] = s.trianglesOut;
  j["critical_triangles"] = {{"at_requested_d_min", s.criticalAtRequested},
                             {"at_used_d_min", s.criticalAfterRaise},
                             {"triangles_added_by_splitting", s.trianglesAdded},
                             {"max_split_depth", s.maxSplitDepth}};
  uint64_t storedImages = 0;
  for (const ImageRecord& r : m.images) storedImages += r.pieceCount > 0;
  j["images"] = {{"total", m.images.size()}, {"stored", storedImages}};
  j["textures"] = m.textures.size();
  nlohmann::json trees = nlohmann::json::array();
  for (const Tree& t : m.trees) {
    std::vector<uint64_t> perLevel;
    uint64_t leaves = 0;
    double covSum = 0.0, covMin = 1.0;
    if (t.nodes.empty()) throw Error("mta info: internal error: a tree without nodes");  // the validator refuses it
    for (const Node& n : t.nodes) {
      if (n.level > kMaxNodeLevel) throw Error("mta info: internal error: a node deeper than the format allows");
      if (perLevel.size() <= n.level) perLevel.resize(n.level + 1, 0);
      ++perLevel[n.level];
      if (n.leaf()) ++leaves, covSum += n.coverage, covMin = std::min(covMin, double(n.coverage));
    }
    trees.push_back({{"kind", t.alpha ? "rgba" : "rgb"},
                     {"depth", t.depth()},
                     {"nodes", t.nodes.size()},
                     {"leaves", leaves},
                     {"nodes_per_level", perLevel},
                     {"triangles", t.geometry.triangleCount()},
                     {"leaf_atlas_coverage_mean", leaves ? covSum / double(leaves) : 0.0},
                     {"leaf_atlas_coverage_min", leaves ? covMin : 0.0},
                     {"root_min_distance", t.nodes[0].minDistance}});
  }
  j["trees"] = trees;
  uint64_t n[3] = {}, bytes[3] = {};
  for (const BlockInfo& b : m.blocks) {
    if (b.kind != BlockKind::Atlas && b.kind != BlockKind::Original)
      throw Error("mta info: internal error: a block of unknown kind");
    ++n[int(b.kind)], bytes[int(b.kind)] += b.size;
  }
  j["blocks"] = {{"atlas", {{"count", n[1]}, {"bytes", bytes[1]}}}, {"original", {{"count", n[2]}, {"bytes", bytes[2]}}}};
  if (verifyBlocks) {
    for (uint32_t i = 0; i < m.blocks.size(); ++i) f.readBlock(i);
    j["blocks_verified"] = m.blocks.size();
  }
  return j;
}

}  // namespace tessera::mta
