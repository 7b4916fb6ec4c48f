#include "mta/build.h"

#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <set>

#include "mta/atlas_image.h"
#include "mta/critical.h"
#include "mta/paging_file.h"
#include "mta/build_plan.h"
#include "mta/output_budget.h"
#include "mta/output_size.h"
#include "mta/tree_build.h"
#include "base/resource_limits.h"
#include "raster/command_list.h"

namespace tessera::mta {

uint64_t residentBytes() {
  std::ifstream f("/proc/self/status");
  std::string line;
  while (std::getline(f, line))
    if (line.rfind("VmRSS:", 0) == 0) return uint64_t(std::strtoull(line.c_str() + 6, nullptr, 10)) * 1024;
  return 0;
}

namespace {

using Clock = std::chrono::steady_clock;

// Bytes of the RGBA8 mip chain makeMipImage builds for a w x h image (MipImage::bytes() once decoded).
uint64_t mipChainBytes(uint32_t w, uint32_t h) {
  TextureDesc d;
  d.kind = TextureKind::Tex2D;
  d.format = Format::RGBA8;
  d.width = w, d.height = h, d.layers = 1, d.levels = fullMipCount(w, h);
  uint64_t b = 0;
  for (uint32_t l = 0; l < d.levels; ++l) b += levelBytes(d, l);
  return b;
}

// Decoded images with their mip chains, least recently used evicted beyond the budget. Evicts before it
// decodes (sizes come from the headers), so the decoded images never exceed the budget, not even while
// a batch is loaded, as long as one batch's own images fit (checked before the first batch).
struct ImageCache {
  const Scene& scene;
  uint64_t budget;
  std::map<uint32_t, std::pair<std::shared_ptr<const MipImage>, uint64_t>> items;
  uint64_t bytes = 0, tick = 0, decoded = 0;

  // Makes every image of `need` resident (decoding the missing ones in parallel) and evicts others.
  void require(const std::vector<uint32_t>& need) {
    std::vector<uint32_t> missing;
    uint64_t incoming = 0;
    ++tick;
    for (uint32_t i : need) {
      auto it = items.find(i);
      if (it == items.end())
        missing.push_back(i), incoming += mipChainBytes(scene.images[i].width, scene.images[i].height);
      else
        it->second.second = tick;
    }
    while (bytes + incoming > budget) {  // evict the least recently used image not needed now (ties: lowest index)
      auto victim = items.end();
      for (auto it = items.begin(); it != items.end(); ++it)
        if (it->second.second != tick && (victim == items.end() || it->second.second < victim->second.second)) victim = it;
      if (victim == items.end()) break;
      bytes -= victim->second.first->bytes();
      items.erase(victim);
    }
    std::vector<std::shared_ptr<const MipImage>> loaded(missing.size());
    tbb::parallel_for(size_t(0), missing.size(), [&](size_t k) {
      const uint32_t i = missing[k];
      const model::Image img = scene.loadImage(i);
      const SceneImage& si = scene.images[i];
      if (img.width != si.width || img.height != si.height)
        throw Error("mta: image " + std::to_string(i) + " '" + si.name + "' decodes to " + std::to_string(img.width) + "x" +
                    std::to_string(img.height) + " but its header said " + std::to_string(si.width) + "x" + std::to_string(si.height));
      loaded[k] = std::make_shared<const MipImage>(makeMipImage(img));
    });
    for (size_t k = 0; k < missing.size(); ++k) {
      bytes += loaded[k]->bytes();
      items[missing[k]] = {loaded[k], tick};
    }
    decoded += missing.size();
  }
  const MipImage& get(uint32_t i) const { return *items.at(i).first; }
};

// Original images: each in blocks of its own of at most about `target` bytes, as row ranges.
struct OriginalPacker {
  PagingFileWriter& w;
  MtaMeta& meta;
  OriginalBlockLayout layout;
  std::vector<uint8_t> cur;
  std::vector<size_t> pending;  // pieces waiting for the current block's index
  uint32_t firstImage = 0;

  void flush() {
    if (cur.empty()) return;
    const uint32_t b = w.addBlock(BlockKind::Original, 0, 0, firstImage, cur);
    for (size_t p : pending) meta.pieces[p].block = b;
    pending.clear();
    cur.clear();
  }
  void add(uint32_t image, const MipImage& img) {
    ImageRecord& r = meta.images[image];
    const size_t rowBytes = size_t(r.width) * r.channels;
    r.firstPiece = uint32_t(meta.pieces.size());
    if (meta.encoding == BlockEncoding::S3tc) {
      // One piece in a block of its own: the chain encoded from the stored channels of level 0 (a 3-channel
      // image's alpha is 255, as the raw runtime reads it), so the chain is the raw file's chain, encoded.
      std::vector<uint8_t> texels(size_t(r.width) * r.height * r.channels);
      const uint8_t* src = img.levels[0].data();
      for (size_t t = 0; t < size_t(r.width) * r.height; ++t)
        for (uint32_t c = 0; c < r.channels; ++c) texels[t * r.channels + c] = src[t * 4 + c];
      meta.pieces.push_back(PieceRecord{image, 0, 0, r.height, 0});
      meta.pieces.back().block =
          w.addBlock(BlockKind::Original, 0, 0, image, encodeS3tcChain(r.width, r.height, r.channels, texels));
      r.pieceCount = 1;
      return;
    }
    for (uint32_t row = 0; row < r.height;) {
      // The layout is the size estimate's own (output_size.h), so the estimate stays exact.
      const OriginalBlockLayout::Piece p = layout.next(r.height - row, rowBytes, row == 0);
      if (p.closedBlockBytes) flush();
      if (cur.empty()) firstImage = image;
      const uint32_t rows = p.rows;
      pending.push_back(meta.pieces.size());
      meta.pieces.push_back(PieceRecord{image, 0, row, rows, cur.size()});
      const uint8_t* src = img.levels[0].data() + size_t(row) * r.width * 4;
      for (size_t t = 0; t < size_t(rows) * r.width; ++t)
        for (uint32_t c = 0; c < r.channels; ++c) cur.push_back(src[t * 4 + c]);
      row += rows;
    }
    r.pieceCount = uint32_t(meta.pieces.size()) - r.firstPiece;
  }
};

// Leaf-local atlas texel position of vertex k of triangle t (layer-0 entry e).
std::pair<double, double> localTexel(const Scene& s, const Tree& tree, const AtlasEntry& e, uint32_t t, int k) {
  const glm::vec2* uvs = &tree.geometry.layers[0].uv[t * 3];
  const auto shift = repeatShift(uvs, s.textures[e.texture].wrapS, s.textures[e.texture].wrapT);
  const double u = float(double(uvs[k].x) - shift.first), v = float(double(uvs[k].y) - shift.second);
  return entryTexel(e, u, v);
}

// Layer 0: the map from atlas texel centres to the entry's source rectangle (tree.h AtlasEntry), the
// inverse of entryTexel.
AffineMap entryMap(const AtlasEntry& e) {
  AffineMap m;
  if (!e.rotated) {
    m.ux = e.source.width() / e.w;
    m.vy = e.source.height() / e.h;
    m.u0 = e.source.u0 - e.x * m.ux;
    m.v0 = e.source.v0 - e.y * m.vy;
    return m;
  }
  // u grows with y from u0 at the area's bottom row; v falls with x from v1 at its left column.
  m.uy = e.source.width() / e.h;
  m.vx = -(e.source.height() / e.w);
  m.u0 = e.source.u0 - e.y * m.uy;
  m.v0 = e.source.v1 - e.x * m.vx;
  return m;
}

// Renders layer `layer` of leaf `node`.
void renderLeaf(const Scene& s, const Tree& tree, uint32_t node, uint32_t layer, const ImageCache& cache, uint32_t A,
                std::vector<uint8_t>& out) {
  const Node& n = tree.nodes[node];
  const uint32_t C = tree.channels();
  out = blankAtlas(A, C, layer);
  for (const AtlasEntry& e : n.entries) {
    if (layer == 0) {
      const SceneTexture& tex = s.textures[e.texture];
      fillArea(out.data(), A, C, e.x, e.y, e.w, e.h, entryMap(e), cache.get(tex.image), tex.wrapS, tex.wrapT);
      continue;
    }
    // §5.1.3: the first triangle of this texture with a layer texture and a non-degenerate atlas triangle.
    const SceneLayer& L = tree.geometry.layers[layer];
    for (uint32_t t = n.firstTriangle; t < n.firstTriangle + n.triangleCount; ++t) {
      if (tree.geometry.layers[0].texture[t] != e.texture || L.texture[t] < 0) continue;
      const auto p0 = localTexel(s, tree, e, t, 0), p1 = localTexel(s, tree, e, t, 1), p2 = localTexel(s, tree, e, t, 2);
      const double ax = p1.first - p0.first, ay = p1.second - p0.second, bx = p2.first - p0.first, by = p2.second - p0.second;
      const double det = ax * by - bx * ay;
      if (!(std::fabs(det) > 1e-9)) continue;
      const glm::vec2* uv = &L.uv[t * 3];
      const double du1 = double(uv[1].x) - uv[0].x, dv1 = double(uv[1].y) - uv[0].y;
      const double du2 = double(uv[2].x) - uv[0].x, dv2 = double(uv[2].y) - uv[0].y;
      // (x, y) - p0 = a·(ax, ay) + b·(bx, by); uv = uv0 + a·d1 + b·d2.
      AffineMap m;
      m.ux = (du1 * by - du2 * ay) / det, m.uy = (du2 * ax - du1 * bx) / det;
      m.vx = (dv1 * by - dv2 * ay) / det, m.vy = (dv2 * ax - dv1 * bx) / det;
      m.u0 = uv[0].x - m.ux * p0.first - m.uy * p0.second;
      m.v0 = uv[0].y - m.vx * p0.first - m.vy * p0.second;
      const SceneTexture& tex = s.textures[L.texture[t]];
      fillArea(out.data(), A, C, e.x, e.y, e.w, e.h, m, cache.get(tex.image), tex.wrapS, tex.wrapT);
      break;
    }
  }
}

// "45 s", "12 min 05 s", "3 h 20 min": the time left in progress lines.
std::string formatDuration(double seconds) {
  const uint64_t s = uint64_t(std::max(0.0, seconds) + 0.5);
  char buf[48];
  if (s < 60)
    std::snprintf(buf, sizeof buf, "%llu s", (unsigned long long)s);
  else if (s < 3600)
    std::snprintf(buf, sizeof buf, "%llu min %02llu s", (unsigned long long)(s / 60), (unsigned long long)(s % 60));
  else
    std::snprintf(buf, sizeof buf, "%llu h %02llu min", (unsigned long long)(s / 3600), (unsigned long long)(s / 60 % 60));
  return buf;
}

}  // namespace

BuildReport buildMta(const Scene& scene, const BuildParams& params, const std::string& outPath, const OutputGuard& guard) {
  const auto t0 = Clock::now();
  params.validate();
  scene.validate();
  if (guard.fitBytes && params.dMin > 0.0)
    throw Error("mta build: --fit chooses d_min itself; do not pass --d-min as well (--d-min-divisor sets the finest "
                "d_min --fit may choose)");
  std::optional<tbb::global_control> threads;
  if (params.threads) threads.emplace(tbb::global_control::max_allowed_parallelism, params.threads);
  BuildReport rep;
  const ImageCache* cacheForMessages = nullptr;
  auto checkMemory = [&](const char* where) {
    const uint64_t rss = residentBytes();
    rep.peakResidentBytes = std::max(rep.peakResidentBytes, rss);
    if (params.memoryLimit && rss > params.memoryLimit) {
      std::string cache;
      if (cacheForMessages)
        cache = ", decoded images " + std::to_string(cacheForMessages->bytes >> 20) + " MiB of a budget of " +
                std::to_string(cacheForMessages->budget >> 20) + " MiB";
      throw Error("mta: resident memory " + std::to_string(rss >> 20) + " MiB exceeds --memory-limit " +
                  std::to_string(params.memoryLimit >> 20) + " MiB " + where + cache +
                  " (the scene's geometry, the tree and the open batch must fit; raise the limit)");
    }
  };
  // Everything is decided before the output exists: the plan, its exact size, and (--fit) the d_min.
  BuildPlan plan;
  if (guard.fitBytes) {
    DMinFit fit = fitDMin(scene, params, guard.fitBytes);
    if (!fit.found)
      throw Error("mta build: --fit " + formatBytes(guard.fitBytes) + ": no d_min fits: the smallest tree tried, at d_min " +
                  formatDMin(fit.dMin) + ", takes " + formatBytes(fit.estimate.totalBytes) + " (" +
                  groupThousands(fit.estimate.nodes) + " nodes; geometry and tables " +
                  formatBytes(fit.estimate.metadataBytes) + ", original images " + formatBytes(fit.estimate.originalBytes) +
                  "): pass a larger --fit");
    plan = std::move(fit.plan);
    rep.fitDMin = fit.dMin, rep.fitPlans = fit.plans, rep.fitFinerDMin = fit.finerDMin, rep.fitFinerBytes = fit.finerBytes;
    checkMemory("after choosing d_min for --fit");
  } else {
    plan = planBuild(scene, params, checkMemory);
  }
  rep.estimate = estimateOutput(plan);
  if (params.progress)
    std::fprintf(stderr, "mta: planned %s nodes (%s leaves): the file will take %s (%s bytes)%s\n",
                 groupThousands(rep.estimate.nodes).c_str(), groupThousands(rep.estimate.leaves).c_str(),
                 formatBytes(rep.estimate.totalBytes).c_str(), groupThousands(rep.estimate.totalBytes).c_str(),
                 rep.fitPlans ? (", d_min " + formatDMin(rep.fitDMin) + " chosen by --fit from " +
                                 std::to_string(rep.fitPlans) + " plans").c_str()
                              : "");
  refuseIfTooBig(scene, params, plan, rep.estimate, guard);
  rep.planSeconds = std::chrono::duration<double>(Clock::now() - t0).count();
  MtaMeta& meta = plan.meta;
  if (params.progress)
    std::fprintf(stderr, "mta: %llu triangles, d_min %.6g (requested %.6g), %llu critical triangles split into %llu more\n",
                 (unsigned long long)meta.stats.trianglesOut, meta.stats.dMinUsed, meta.stats.dMinRequested,
                 (unsigned long long)meta.stats.criticalAfterRaise, (unsigned long long)meta.stats.trianglesAdded);
  const uint32_t A = params.atlasSize, layers = meta.layerCount;
  const uint64_t leafCount = plan.leaves;

  // Memory for the atlas phase, bounded by construction: what is resident now (geometry, tree, the
  // caller's model) + the working set below + the image cache, whose budget is what the limit leaves
  // (at most limit / 8, clamped to 64 MiB .. 1 GiB as before), with a quarter of the rest kept as slack
  // for the allocator. The VmRSS checks stay as a safety net.
  constexpr size_t kBatch = 8;  // leaves per batch; fixed: the bytes never depend on it, only memory and speed do
  const uint64_t atlasBytes4 = uint64_t(A) * A * 4;
  uint32_t maxDepth = 0;
  uint64_t largestImage = 0, largestBatch = 0;  // RGBA8 bytes of one decoded image; mip-chain bytes of one batch
  for (const Tree& tree : meta.trees) {
    maxDepth = std::max(maxDepth, tree.depth());
    std::vector<uint32_t> leaves;
    for (uint32_t i = 0; i < tree.nodes.size(); ++i)
      if (tree.nodes[i].leaf()) leaves.push_back(i);
    for (size_t b0 = 0; b0 < leaves.size(); b0 += kBatch) {
      std::set<uint32_t> imgs;
      for (size_t k = b0; k < std::min(leaves.size(), b0 + kBatch); ++k)
        for (uint32_t j = 0; j < tree.nodes[leaves[k]].imageCount; ++j) imgs.insert(tree.leafImages[tree.nodes[leaves[k]].imageFirst + j]);
      uint64_t b = 0;
      for (uint32_t i : imgs) {
        b += mipChainBytes(scene.images[i].width, scene.images[i].height);
        largestImage = std::max(largestImage, uint64_t(scene.images[i].width) * scene.images[i].height * 4);
      }
      largestBatch = std::max(largestBatch, b);
    }
  }
  const uint64_t threadCount = tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism);
  // Rendered batch + open inner atlases (one per level, per layer) + the originals block + per decoding
  // thread the decoded image, its mip chain under construction and the decoder's own buffer.
  const uint64_t working = (kBatch + maxDepth) * layers * atlasBytes4 + atlasBytes4 + threadCount * 4 * largestImage;
  const uint64_t inUse = residentBytes();
  uint64_t cacheBudget = 1ull << 30;
  if (params.memoryLimit) {
    const uint64_t headroom = params.memoryLimit > inUse + working ? (params.memoryLimit - inUse - working) / 4 * 3 : 0;
    cacheBudget = std::min(std::clamp<uint64_t>(params.memoryLimit / 8, 64ull << 20, 1ull << 30), headroom);
    if (largestBatch > cacheBudget) {
      if (largestBatch > headroom)
        throw Error("mta: --memory-limit " + std::to_string(params.memoryLimit >> 20) + " MiB is too small: " +
                    std::to_string(inUse >> 20) + " MiB are in use after building the tree structure, the atlas working set needs " +
                    std::to_string(working >> 20) + " MiB and the images of one batch of " + std::to_string(kBatch) + " leaves " +
                    std::to_string(largestBatch >> 20) + " MiB decoded (with a quarter of the rest as slack); raise the limit");
      cacheBudget = largestBatch;
    }
  }
  if (params.progress)
    std::fprintf(stderr, "mta: %llu MiB in use, image cache budget %llu MiB, atlas working set %llu MiB, largest batch %llu MiB\n",
                 (unsigned long long)(inUse >> 20), (unsigned long long)(cacheBudget >> 20), (unsigned long long)(working >> 20),
                 (unsigned long long)(largestBatch >> 20));

  PagingFileWriter writer(outPath);
  OriginalPacker packer{writer, meta, OriginalBlockLayout(originalBlockTarget(A)), {}, {}, 0};
  ImageCache cache{scene, cacheBudget, {}, 0, 0, 0};
  cacheForMessages = &cache;
  std::vector<uint8_t> stored(scene.images.size(), 0);
  uint64_t leavesDone = 0;
  const auto tWrite = Clock::now();
  auto lastProgress = tWrite;
  for (size_t ti = 0; ti < meta.trees.size(); ++ti) {
    Tree& tree = meta.trees[ti];
    const uint32_t C = tree.channels();
    // Partial inner atlases (per node, per layer) and how many children are still missing.
    std::map<uint32_t, std::pair<std::vector<std::vector<uint8_t>>, int>> open;
    std::function<void(uint32_t, std::vector<std::vector<uint8_t>>&)> complete = [&](uint32_t node,
                                                                                       std::vector<std::vector<uint8_t>>& atlas) {
      for (uint32_t l = 0; l < layers; ++l)
        tree.atlasBlocks[node * layers + l] = writer.addBlock(
            BlockKind::Atlas, uint8_t(ti), uint8_t(l), node,
            meta.encoding == BlockEncoding::S3tc ? encodeS3tcChain(A, A, C, atlas[l]) : atlas[l]);
      const int32_t parent = tree.nodes[node].parent;
      if (parent < 0) return;
      auto it = open.find(uint32_t(parent));
      if (it == open.end()) {
        int kids = 0;
        for (int32_t c : tree.nodes[parent].children) kids += c >= 0;
        it = open.emplace(uint32_t(parent), std::make_pair(std::vector<std::vector<uint8_t>>(layers), kids)).first;
        for (uint32_t l = 0; l < layers; ++l) it->second.first[l] = blankAtlas(A, C, l);
      }
      int q = 0;
      while (tree.nodes[parent].children[q] != int32_t(node)) ++q;
      for (uint32_t l = 0; l < layers; ++l) downsampleIntoQuadrant(atlas[l].data(), it->second.first[l].data(), A, C, q);
      if (--it->second.second == 0) {
        auto done = std::move(it->second.first);
        open.erase(it);
        complete(uint32_t(parent), done);
      }
    };
    std::vector<uint32_t> leaves;
    for (uint32_t i = 0; i < tree.nodes.size(); ++i)
      if (tree.nodes[i].leaf()) leaves.push_back(i);
    for (size_t b0 = 0; b0 < leaves.size(); b0 += kBatch) {
      const size_t b1 = std::min(leaves.size(), b0 + kBatch);
      std::vector<uint32_t> need, fresh;
      for (size_t k = b0; k < b1; ++k) {
        const Node& n = tree.nodes[leaves[k]];
        for (uint32_t j = 0; j < n.imageCount; ++j) {
          const uint32_t img = tree.leafImages[n.imageFirst + j];
          need.push_back(img);
          if (!stored[img]) stored[img] = 1, fresh.push_back(img);
        }
      }
      std::sort(need.begin(), need.end());
      need.erase(std::unique(need.begin(), need.end()), need.end());
      cache.require(need);
      checkMemory("after decoding a batch's images");
      std::vector<std::vector<std::vector<uint8_t>>> atlases(b1 - b0, std::vector<std::vector<uint8_t>>(layers));
      tbb::parallel_for(size_t(0), (b1 - b0) * layers, [&](size_t k) {
        renderLeaf(scene, tree, leaves[b0 + k / layers], uint32_t(k % layers), cache, A, atlases[k / layers][k % layers]);
      });
      for (uint32_t img : fresh) packer.add(img, cache.get(img));
      for (size_t k = b0; k < b1; ++k) complete(leaves[k], atlases[k - b0]);
      leavesDone += b1 - b0;
      checkMemory("while writing atlases");
      if (params.progress && Clock::now() - lastProgress > std::chrono::seconds(2)) {
        lastProgress = Clock::now();
        // The total is the plan's exact size, so bytes give the fraction done; the time left assumes the
        // rate so far (atlases dominate and cost about the same per byte).
        const double written = double(writer.bytesWritten()), total = double(rep.estimate.totalBytes);
        const double elapsed = std::chrono::duration<double>(Clock::now() - tWrite).count();
        std::fprintf(stderr, "mta: %5.1f%%  leaves %s/%s, images decoded %llu, file %s of %s, %s left\n",
                     100.0 * written / total, groupThousands(leavesDone).c_str(), groupThousands(leafCount).c_str(),
                     (unsigned long long)cache.decoded, formatBytes(writer.bytesWritten()).c_str(),
                     formatBytes(rep.estimate.totalBytes).c_str(),
                     formatDuration(written > 0.0 ? elapsed * (total - written) / written : 0.0).c_str());
      }
    }
    for (auto& t : tree.nodes) t.entries.clear(), t.entries.shrink_to_fit();
  }
  packer.flush();
  writer.finish(meta);
  rep.imagesDecoded = cache.decoded;
  rep.fileBytes = std::filesystem::file_size(outPath);
  rep.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  checkMemory("at the end");
  if (params.progress)
    std::fprintf(stderr, "mta: wrote %s: %.1f MiB (estimated %.1f MiB) in %.1f s (peak resident %.0f MiB)\n", outPath.c_str(),
                 rep.fileBytes / 1048576.0, rep.estimate.totalBytes / 1048576.0, rep.seconds, rep.peakResidentBytes / 1048576.0);
  return rep;
}

}  // namespace tessera::mta
