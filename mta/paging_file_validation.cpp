#include "mta/paging_file_validation.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

#include "base/error.h"

namespace tessera::mta {

namespace {

std::string at(const std::string& record, uint64_t i) { return record + "[" + std::to_string(i) + "]"; }
std::string num(double v) { return fmt::format("{}", v); }
uint64_t align16(uint64_t x) { return (x + 15) & ~uint64_t(15); }
bool finite(const glm::vec2& v) { return std::isfinite(v.x) && std::isfinite(v.y); }
bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
std::string box(const std::array<float, 6>& b) {
  return fmt::format("[{}, {}, {}] .. [{}, {}, {}]", b[0], b[1], b[2], b[3], b[4], b[5]);
}

class Validator {
 public:
  Validator(const MtaMeta& m, const std::string& path, uint64_t metaOffset, const ResourceLimits& limits)
      : m_(m), path_(path), metaOffset_(metaOffset), limits_(limits) {}

  void run() {
    parameters();
    stats();
    textures();
    images();
    trees();
    blockDirectory();
    pieces();
    imageUse();
  }

 private:
  [[noreturn]] void fail(const std::string& field, const std::string& why) const {
    throw Error(path_ + ": " + field + ": " + why);
  }

  void parameters() const {
    try {
      m_.params.validate("parameters.", true);
    } catch (const Error& e) {
      throw Error(path_ + ": " + e.what());
    }
  }

  void stats() const {
    const BuildStats& s = m_.stats;
    if (!(s.dMinRequested > 0.0 && std::isfinite(s.dMinRequested)))
      fail("stats.d_min_requested", num(s.dMinRequested) + " is not a finite number > 0");
    // The build only ever raises d_min (critical.h).
    if (!(s.dMinUsed >= s.dMinRequested && std::isfinite(s.dMinUsed)))
      fail("stats.d_min_used",
           num(s.dMinUsed) + " is not a finite number >= d_min_requested (" + num(s.dMinRequested) + ")");
    if (!(s.sceneDiagonal >= 0.0 && std::isfinite(s.sceneDiagonal)))
      fail("stats.scene_diagonal", num(s.sceneDiagonal) + " is not a finite number >= 0");
    if (s.criticalAtRequested > s.trianglesIn)
      fail("stats.critical_at_requested",
           std::to_string(s.criticalAtRequested) + " of " + std::to_string(s.trianglesIn) + " input triangles");
    if (s.criticalAfterRaise > s.trianglesIn)
      fail("stats.critical_after_raise",
           std::to_string(s.criticalAfterRaise) + " of " + std::to_string(s.trianglesIn) + " input triangles");
    const std::optional<uint64_t> out = checkedAdd(s.trianglesIn, s.trianglesAdded);
    if (!out || *out != s.trianglesOut)
      fail("stats.triangles_out", std::to_string(s.trianglesOut) + " is not triangles_in (" +
                                      std::to_string(s.trianglesIn) + ") + triangles_added (" +
                                      std::to_string(s.trianglesAdded) + ")");
    uint64_t total = 0;
    for (const Tree& t : m_.trees) total += t.geometry.triangleCount();  // each bounded by the metadata size
    if (total != s.trianglesOut)
      fail("stats.triangles_out",
           std::to_string(s.trianglesOut) + ", but the trees hold " + std::to_string(total) + " triangles");
  }

  void textures() const {
    for (size_t i = 0; i < m_.textures.size(); ++i)
      if (m_.textures[i].image >= m_.images.size())
        fail(at("textures", i) + ".image", std::to_string(m_.textures[i].image) + " is out of range (" +
                                               std::to_string(m_.images.size()) + " images)");
  }

  // Each image's own fields and the pieces it lists; how pieces fill blocks is checked in pieces().
  void images() const {
    uint64_t listed = 0;
    for (size_t i = 0; i < m_.images.size(); ++i) {
      const ImageRecord& r = m_.images[i];
      const std::string f = at("images", i);
      if (r.channels != 3 && r.channels != 4) fail(f + ".channels", std::to_string(r.channels) + " is not 3 or 4");
      if (r.width < 1 || r.width > kMaxImageSize)
        fail(f + ".width", std::to_string(r.width) + " is outside [1, " + std::to_string(kMaxImageSize) + "]");
      if (r.height < 1 || r.height > kMaxImageSize)
        fail(f + ".height", std::to_string(r.height) + " is outside [1, " + std::to_string(kMaxImageSize) + "]");
      if (uint64_t(r.firstPiece) + r.pieceCount > m_.pieces.size())
        fail(f + ".piece_count", "pieces [" + std::to_string(r.firstPiece) + ", +" + std::to_string(r.pieceCount) +
                                     ") run past the " + std::to_string(m_.pieces.size()) + " pieces");
      uint64_t row = 0;
      for (uint32_t k = 0; k < r.pieceCount; ++k) {
        const size_t j = size_t(r.firstPiece) + k;
        const PieceRecord& p = m_.pieces[j];
        const std::string pf = at("pieces", j);
        if (p.image != i) fail(pf + ".image", std::to_string(p.image) + ", but " + f + " lists the piece");
        if (p.row0 != row)
          fail(pf + ".row0",
               std::to_string(p.row0) + ", expected " + std::to_string(row) + " (an image's pieces continue its rows)");
        if (p.rows == 0 || row + p.rows > r.height)
          fail(pf + ".rows", std::to_string(p.rows) + ": rows [" + std::to_string(row) + ", " +
                                 std::to_string(row + p.rows) + ") are not a non-empty range inside the image's " +
                                 std::to_string(r.height) + " rows");
        row += p.rows;
      }
      if (r.pieceCount != 0 && row != r.height)
        fail(f + ".piece_count",
             "its pieces cover " + std::to_string(row) + " of " + std::to_string(r.height) + " rows");
      listed += r.pieceCount;
    }
    // With every listed piece naming its image, this makes each piece belong to exactly one image.
    if (listed != m_.pieces.size())
      fail("pieces", std::to_string(m_.pieces.size()) + " pieces, but the images list " + std::to_string(listed));
  }

  void trees() {
    if (m_.trees.empty()) fail("trees", "none (a file holds the RGB tree, the RGBA tree or both)");
    imageUsers_.assign(m_.images.size(), 0);
    uint64_t triangles = 0;
    for (size_t ti = 0; ti < m_.trees.size(); ++ti) {
      const Tree& t = m_.trees[ti];
      const std::string tf = at("trees", ti);
      if (t.alpha > 1) fail(tf + ".alpha", std::to_string(t.alpha) + " is not 0 (RGB) or 1 (RGBA)");
      if (ti > 0 && t.alpha <= m_.trees[ti - 1].alpha)
        fail(tf + ".alpha", std::to_string(t.alpha) + " after a tree with alpha " +
                                std::to_string(m_.trees[ti - 1].alpha) +
                                " (the RGB tree comes first, each kind at most once)");
      triangles += t.geometry.triangleCount();
      if (triangles > kMaxTriangles)
        fail(tf + ".positions", std::to_string(triangles) + " triangles in all, over the format's limit of " +
                                    std::to_string(kMaxTriangles) + " (3 per triangle must fit 32-bit vertex indices)");
      geometry(t, tf);
      nodes(t, tf);
    }
  }

  void geometry(const Tree& t, const std::string& tf) const {
    const Geometry& g = t.geometry;
    const uint64_t tris = g.triangleCount();
    // Decoding sized every array from the triangle count; an in-memory tree is checked all the same.
    bool sized = g.positions.size() == tris * 3 && g.source.size() == tris && g.layers.size() == m_.layerCount &&
                 t.atlasUV.size() == tris * 3 && t.atlasBlocks.size() == uint64_t(t.nodes.size()) * m_.layerCount;
    for (const SceneLayer& l : g.layers) sized = sized && l.texture.size() == tris && l.uv.size() == tris * 3;
    if (!sized) fail(tf, "its arrays do not match its triangle and node counts");
    for (size_t v = 0; v < g.positions.size(); ++v)
      if (!finite(g.positions[v])) fail(at(tf + ".positions", v), "not finite");
    for (uint32_t l = 0; l < m_.layerCount; ++l) {
      const SceneLayer& L = g.layers[l];
      const std::string lf = at(tf + ".layers", l);
      for (size_t k = 0; k < L.texture.size(); ++k)
        if (L.texture[k] < -1 || L.texture[k] >= int64_t(m_.textures.size()))
          fail(at(lf + ".texture", k), std::to_string(L.texture[k]) + " is neither -1 (none) nor a texture index (" +
                                           std::to_string(m_.textures.size()) + " textures)");
      for (size_t v = 0; v < L.uv.size(); ++v)
        if (!finite(L.uv[v])) fail(at(lf + ".uv", v), "not finite");
    }
    for (size_t v = 0; v < t.atlasUV.size(); ++v)
      if (!finite(t.atlasUV[v])) fail(at(tf + ".atlas_uv", v), "not finite");
  }

  // One node's own fields.
  void nodeFields(const Node& n, const std::string& nf, uint64_t tris) const {
    for (int k = 0; k < 6; ++k)
      if (!std::isfinite(n.bounds[size_t(k)])) fail(nf + ".bounds", box(n.bounds) + " is not finite");
    for (int k = 0; k < 3; ++k)
      if (!(n.bounds[size_t(k)] <= n.bounds[size_t(k) + 3])) fail(nf + ".bounds", box(n.bounds) + " has min > max");
    if (!(n.minDistance > 0.0f && std::isfinite(n.minDistance)))
      fail(nf + ".min_distance", num(n.minDistance) + " is not a finite number > 0");
    if (!(n.coverage >= 0.0f && n.coverage <= 1.0f)) fail(nf + ".coverage", num(n.coverage) + " is outside [0, 1]");
    if (n.level > kMaxNodeLevel)
      fail(nf + ".level",
           std::to_string(n.level) + ": deeper than the format's " + std::to_string(kMaxNodeLevel) + " levels");
    if (n.level < 32 && ((uint64_t(n.cellX) >> n.level) || (uint64_t(n.cellY) >> n.level)))
      fail(nf + ".cell", "(" + std::to_string(n.cellX) + ", " + std::to_string(n.cellY) + ") is outside the 2^" +
                             std::to_string(n.level) + " cells of its level");
    if (uint64_t(n.firstTriangle) + n.triangleCount > tris)
      fail(nf + ".triangle_count", "triangles [" + std::to_string(n.firstTriangle) + ", +" +
                                       std::to_string(n.triangleCount) + ") run past the tree's " +
                                       std::to_string(tris));
  }

  // The node table: a tree in depth-first pre-order (children in quadrant order), walked without
  // recursion; every node reached exactly once; ranges nest; leaves list their images.
  void nodes(const Tree& t, const std::string& tf) {
    const size_t count = t.nodes.size();
    const uint64_t tris = t.geometry.triangleCount();
    if (count == 0) fail(tf + ".nodes", "none (a tree has at least its root)");
    const Node& root = t.nodes[0];
    const std::string rf = tf + ".nodes[0]";
    if (root.parent != -1) fail(rf + ".parent", std::to_string(root.parent) + " (the root has none: -1)");
    if (root.level != 0 || root.cellX != 0 || root.cellY != 0) fail(rf + ".level", "the root is level 0, cell (0, 0)");
    if (root.firstTriangle != 0 || root.triangleCount != tris)
      fail(rf + ".triangle_count", "the root covers [" + std::to_string(root.firstTriangle) + ", +" +
                                       std::to_string(root.triangleCount) + "), not every triangle [0, " +
                                       std::to_string(tris) + ")");
    std::vector<uint32_t> stack{0};
    size_t visited = 0;
    uint64_t imageCursor = 0, refs = 0;
    std::vector<uint32_t> used;
    while (!stack.empty()) {
      const uint32_t i = stack.back();
      stack.pop_back();
      const Node& n = t.nodes[i];
      const std::string nf = at(tf + ".nodes", i);
      if (i != visited)
        fail(nf, "is reached at position " + std::to_string(visited) +
                     " of the depth-first walk from the root; nodes are stored in that order");
      ++visited;
      nodeFields(n, nf, tris);
      for (int q = 0; q < 4; ++q) {
        const int32_t c = n.children[size_t(q)];
        if (c != -1 && (c <= int64_t(i) || uint64_t(c) >= count))
          fail(nf + ".children[" + std::to_string(q) + "]",
               std::to_string(c) + " is neither -1 (no child) nor the index of a later node (" + std::to_string(i + 1) +
                   ".." + std::to_string(count - 1) + ")");
      }
      if (n.leaf()) {
        leaf(t, n, nf, imageCursor, refs, used);
        continue;
      }
      if (n.imageFirst != 0 || n.imageCount != 0)
        fail(nf + ".image_count", "an inner node lists no images (first 0, count 0)");
      uint64_t next = n.firstTriangle;
      for (int q = 0; q < 4; ++q) {
        const int32_t c = n.children[size_t(q)];
        if (c < 0) continue;
        const Node& ch = t.nodes[size_t(c)];
        const std::string cf = at(tf + ".nodes", uint64_t(c));
        const std::string why = ", but " + nf + " lists it as child " + std::to_string(q);
        if (ch.parent != int32_t(i)) fail(cf + ".parent", std::to_string(ch.parent) + why);
        if (ch.level != n.level + 1)
          fail(cf + ".level", std::to_string(ch.level) + why + " (level " + std::to_string(n.level) + ")");
        if (ch.cellX != n.cellX * 2 + uint32_t(q & 1) || ch.cellY != n.cellY * 2 + uint32_t(q >> 1))
          fail(cf + ".cell", "(" + std::to_string(ch.cellX) + ", " + std::to_string(ch.cellY) + ") is not quadrant " +
                                 std::to_string(q) + " of its parent's cell");
        if (ch.firstTriangle != next || ch.triangleCount == 0)
          fail(cf + ".first_triangle", "triangles [" + std::to_string(ch.firstTriangle) + ", +" +
                                           std::to_string(ch.triangleCount) + ") do not continue at " +
                                           std::to_string(next) +
                                           " (children's ranges follow each other in quadrant order)");
        next += ch.triangleCount;
      }
      if (next != uint64_t(n.firstTriangle) + n.triangleCount)
        fail(nf + ".triangle_count", "its children's triangles end at " + std::to_string(next) + ", its own range at " +
                                         std::to_string(uint64_t(n.firstTriangle) + n.triangleCount));
      for (int q = 3; q >= 0; --q)
        if (n.children[size_t(q)] >= 0) stack.push_back(uint32_t(n.children[size_t(q)]));
    }
    if (visited != count) fail(at(tf + ".nodes", visited), "is not reachable from the root");
    if (imageCursor != t.leafImages.size())
      fail(tf + ".leaf_images",
           std::to_string(t.leafImages.size()) + " entries, but the leaves list " + std::to_string(imageCursor));
    if (refs > limits_.mtaLeafBlockRefs)
      throw Error(overLimitMessage(path_ + ": " + tf + ".leaf_images",
                                   "original-texture block references (per leaf and image piece)", refs,
                                   limits_.mtaLeafBlockRefs, "", false));
    // Children have larger indices, so this pass may look at them: each was checked on its own above.
    for (size_t i = 0; i < count; ++i) {
      const Node& n = t.nodes[i];
      for (int32_t c : n.children) {
        if (c < 0) continue;
        const Node& ch = t.nodes[size_t(c)];
        const std::string nf = at(tf + ".nodes", i);
        for (int k = 0; k < 3; ++k)
          if (!(n.bounds[size_t(k)] <= ch.bounds[size_t(k)] && ch.bounds[size_t(k) + 3] <= n.bounds[size_t(k) + 3]))
            fail(nf + ".bounds",
                 box(n.bounds) + " does not contain child " + std::to_string(c) + "'s " + box(ch.bounds));
        // The build sets an inner node's minDistance to 2 · max(children) or more (mta-build.md step 3).
        if (!(double(n.minDistance) >= 2.0 * double(ch.minDistance)))
          fail(nf + ".min_distance",
               num(n.minDistance) + " is less than twice child " + std::to_string(c) + "'s " + num(ch.minDistance));
      }
    }
  }

  void leaf(const Tree& t, const Node& n, const std::string& nf, uint64_t& imageCursor, uint64_t& refs,
            std::vector<uint32_t>& used) {
    if (n.triangleCount == 0) fail(nf + ".triangle_count", "0 (a leaf has triangles)");
    if (n.imageFirst != imageCursor)
      fail(nf + ".image_first", std::to_string(n.imageFirst) + ", expected " + std::to_string(imageCursor) +
                                    " (the leaves' image lists follow each other in node order)");
    if (uint64_t(n.imageFirst) + n.imageCount > t.leafImages.size())
      fail(nf + ".image_count", "images [" + std::to_string(n.imageFirst) + ", +" + std::to_string(n.imageCount) +
                                    ") run past the tree's " + std::to_string(t.leafImages.size()) +
                                    " leaf image entries");
    imageCursor += n.imageCount;
    // The images its triangles sample, in every layer: what the memory manager must load before the leaf
    // is drawn with its original textures.
    const Geometry& g = t.geometry;
    used.clear();
    for (uint32_t tri = n.firstTriangle; tri < n.firstTriangle + n.triangleCount; ++tri)
      for (const SceneLayer& L : g.layers)
        if (L.texture[tri] >= 0) used.push_back(m_.textures[size_t(L.texture[tri])].image);
    std::sort(used.begin(), used.end());
    used.erase(std::unique(used.begin(), used.end()), used.end());
    const uint32_t* list = t.leafImages.data() + n.imageFirst;
    for (uint32_t k = 0; k < n.imageCount; ++k) {
      if (list[k] >= m_.images.size())
        fail(at(nf + ".images", k),
             std::to_string(list[k]) + " is out of range (" + std::to_string(m_.images.size()) + " images)");
      if (k > 0 && list[k] <= list[k - 1]) fail(at(nf + ".images", k), "the list is not sorted without repeats");
    }
    if (n.imageCount != used.size() || !std::equal(used.begin(), used.end(), list)) {
      for (uint32_t img : used)
        if (!std::binary_search(list, list + n.imageCount, img))
          fail(nf + ".image_count", "its triangles use image " + std::to_string(img) + ", which its image list lacks");
      for (uint32_t k = 0; k < n.imageCount; ++k)
        if (!std::binary_search(used.begin(), used.end(), list[k]))
          fail(at(nf + ".images", k), "image " + std::to_string(list[k]) + " is used by none of its triangles");
    }
    for (uint32_t k = 0; k < n.imageCount; ++k) {
      imageUsers_[list[k]] |= uint8_t(1u << t.alpha);
      refs = checkedAdd(refs, m_.images[list[k]].pieceCount).value_or(UINT64_MAX);
    }
    // Culling and the distance test use the box; it must hold every vertex.
    const std::array<float, 6>& b = n.bounds;
    for (size_t v = size_t(n.firstTriangle) * 3; v < (size_t(n.firstTriangle) + n.triangleCount) * 3; ++v) {
      const glm::vec3& p = g.positions[v];
      if (!(p.x >= b[0] && p.y >= b[1] && p.z >= b[2] && p.x <= b[3] && p.y <= b[4] && p.z <= b[5]))
        fail(nf + ".bounds", box(b) + " does not contain vertex " + std::to_string(v) + " (" + num(p.x) + ", " +
                                 num(p.y) + ", " + num(p.z) + ")");
    }
  }

  // The directory is the sequence the writer appends: gap-free, each block at the next multiple of 16,
  // the metadata right after the last one; one atlas block per (tree, node, layer).
  void blockDirectory() const {
    const uint64_t atlasTexels = uint64_t(m_.params.atlasSize) * m_.params.atlasSize;  // <= 2^26
    uint64_t end = kHeaderSize;
    for (size_t i = 0; i < m_.blocks.size(); ++i) {
      const BlockInfo& b = m_.blocks[i];
      const std::string f = at("blocks", i);
      if (b.kind != BlockKind::Atlas && b.kind != BlockKind::Original)
        fail(f + ".kind", std::to_string(int(b.kind)) + " is not 1 (atlas) or 2 (original)");
      if (b.offset != align16(end))
        fail(f + ".offset", std::to_string(b.offset) + ", expected " + std::to_string(align16(end)) +
                                " (blocks follow each other, each at the next multiple of 16)");
      const std::optional<uint64_t> blockEnd = checkedAdd(b.offset, b.size);
      if (!blockEnd || *blockEnd > metaOffset_)
        fail(f + ".size", std::to_string(b.size) +
                              ": the block runs past the block area, which ends where the metadata starts (" +
                              std::to_string(metaOffset_) + ")");
      end = *blockEnd;
      if (b.kind == BlockKind::Original) {
        if (b.tree != 0 || b.layer != 0) fail(f + ".tree", "an original-texture block has tree 0 and layer 0");
        if (b.node >= m_.images.size())
          fail(f + ".node", "first image " + std::to_string(b.node) + " is out of range (" +
                                std::to_string(m_.images.size()) + " images)");
        continue;
      }
      if (b.tree >= m_.trees.size())
        fail(f + ".tree", std::to_string(b.tree) + " is out of range (" + std::to_string(m_.trees.size()) + " trees)");
      const Tree& t = m_.trees[b.tree];
      if (b.layer >= m_.layerCount)
        fail(f + ".layer", std::to_string(b.layer) + " is out of range (" + std::to_string(m_.layerCount) + " layers)");
      if (b.node >= t.nodes.size())
        fail(f + ".node", std::to_string(b.node) + " is out of range (tree " + std::to_string(b.tree) + " has " +
                              std::to_string(t.nodes.size()) + " nodes)");
      const uint64_t owner = t.atlasBlocks[size_t(b.node) * m_.layerCount + b.layer];
      if (owner != i)
        fail(f + ".node", "an atlas block of trees[" + std::to_string(b.tree) + "].nodes[" + std::to_string(b.node) +
                              "] layer " + std::to_string(b.layer) + ", whose atlas is blocks[" +
                              std::to_string(owner) + "]");
      if (m_.encoding == BlockEncoding::S3tc) {
        const uint64_t want = s3tcChainBytes(m_.params.atlasSize, m_.params.atlasSize, t.channels());
        if (b.size != want)
          fail(f + ".size", std::to_string(b.size) + ", expected " + std::to_string(want) + " (the " +
                                bcFormatName(storedBcFormat(t.channels())) + " mip chain of a " +
                                std::to_string(m_.params.atlasSize) + "² atlas)");
      } else if (b.size != atlasTexels * t.channels()) {
        fail(f + ".size", std::to_string(b.size) + ", expected " + std::to_string(atlasTexels * t.channels()) + " (" +
                              std::to_string(m_.params.atlasSize) + "² texels of " + std::to_string(t.channels()) +
                              " bytes)");
      }
    }
    if (align16(end) != metaOffset_)
      fail("blocks", "the block area ends at " + std::to_string(end) + ", but the metadata starts at " +
                         std::to_string(metaOffset_) + " (expected " + std::to_string(align16(end)) + ")");
    // Each tree's table names a block of the right tree, node and layer (checked here for every entry, so
    // with the ownership check above every atlas block belongs to exactly one node and layer).
    for (size_t ti = 0; ti < m_.trees.size(); ++ti) {
      const Tree& t = m_.trees[ti];
      for (size_t k = 0; k < t.atlasBlocks.size(); ++k) {
        const uint32_t bi = t.atlasBlocks[k];
        const size_t node = k / m_.layerCount, layer = k % m_.layerCount;
        const std::string f = at("trees", ti) + ".atlas_blocks[" + std::to_string(k) + "]";
        if (bi >= m_.blocks.size())
          fail(f, std::to_string(bi) + " is out of range (" + std::to_string(m_.blocks.size()) + " blocks)");
        const BlockInfo& b = m_.blocks[bi];
        if (b.kind != BlockKind::Atlas || b.tree != ti || b.node != node || b.layer != layer)
          fail(f, "blocks[" + std::to_string(bi) + "] is not the atlas of node " + std::to_string(node) + ", layer " +
                      std::to_string(layer) + " of this tree");
      }
    }
  }

  // Original-texture blocks, in directory order, each hold exactly one piece, in array order (format
  // version 2: every image starts blocks of its own, so reading one image never reads another's texels),
  // and an image's block ends only at the image's end or where its next row would not fit (build.cpp,
  // OriginalBlockLayout): no block holds more than 4 · A² bytes unless it is a single row, so an image has
  // no more pieces than its bytes need.
  void pieces() const {
    const uint64_t target = uint64_t(m_.params.atlasSize) * m_.params.atlasSize * 4;
    size_t nextOriginal = 0;  // first original block not yet filled
    auto advance = [&]() {
      while (nextOriginal < m_.blocks.size() && m_.blocks[nextOriginal].kind != BlockKind::Original) ++nextOriginal;
    };
    advance();
    // The block of the previous piece holds that piece alone: its size is the piece's bytes (checked when
    // the next piece is known to be elsewhere, so that a second piece in it is named as such).
    auto close = [&](size_t j) {
      const PieceRecord& p = m_.pieces[j];
      if (m_.encoding == BlockEncoding::S3tc) {
        // One piece per image (all its rows), its block the image's encoded chain (block_encoding.h).
        const ImageRecord& img = m_.images[p.image];
        if (p.row0 != 0 || p.rows != img.height)
          fail(at("pieces", j) + ".rows", "rows [" + std::to_string(p.row0) + ", +" + std::to_string(p.rows) +
                                              ") of a " + std::to_string(img.height) +
                                              "-row image: an S3TC file stores each image as one piece");
        const uint64_t want = s3tcChainBytes(img.width, img.height, img.channels);
        if (m_.blocks[p.block].size != want)
          fail(at("blocks", p.block) + ".size", std::to_string(m_.blocks[p.block].size) + ", expected " +
                                                    std::to_string(want) + " (the " +
                                                    bcFormatName(storedBcFormat(img.channels)) + " chain of " +
                                                    at("images", p.image) + ")");
        return;
      }
      const uint64_t rowBytes = uint64_t(m_.images[p.image].width) * m_.images[p.image].channels;
      const uint64_t fill = p.rows * rowBytes;  // rows <= 2^16, rowBytes <= 2^18
      const BlockInfo& b = m_.blocks[p.block];
      if (b.size != fill)
        fail(at("blocks", p.block) + ".size", std::to_string(b.size) + ", but its piece (" + at("pieces", j) + ": " +
                                                  std::to_string(p.rows) + " rows of " + std::to_string(rowBytes) +
                                                  " bytes) fills " + std::to_string(fill) + " bytes");
      if (fill > target && p.rows != 1)
        fail(at("pieces", j) + ".rows", std::to_string(p.rows) + ": its block would hold " + std::to_string(fill) +
                                            " bytes, more than " + std::to_string(target) +
                                            " (4 · A²), which only a block of a single row may");
    };
    for (size_t j = 0; j < m_.pieces.size(); ++j) {
      const PieceRecord& p = m_.pieces[j];
      const std::string pf = at("pieces", j);
      const ImageRecord& img = m_.images[p.image];  // in range: images() matched every piece to its image
      const uint64_t rowBytes = uint64_t(img.width) * img.channels;
      if (p.block >= m_.blocks.size())
        fail(pf + ".block",
             std::to_string(p.block) + " is out of range (" + std::to_string(m_.blocks.size()) + " blocks)");
      if (j > 0) {
        const PieceRecord& prev = m_.pieces[j - 1];
        if (p.block == prev.block)
          fail(pf + ".block", std::to_string(p.block) + ", which already holds " + at("pieces", j - 1) + " (image " +
                                  std::to_string(prev.image) +
                                  "): every original-texture block holds one piece, so each image starts blocks of "
                                  "its own (format version 2)");
        close(j - 1);
        // An image's block ends early only where its next row would not fit.
        const uint64_t prevSize = m_.blocks[prev.block].size;
        if (m_.encoding == BlockEncoding::Raw && prev.image == p.image && prevSize + rowBytes <= target)
          fail(at("blocks", prev.block) + ".size",
               std::to_string(prevSize) + ": the block ends although the next piece's row (" +
                   std::to_string(rowBytes) + " bytes) fits in a block's " + std::to_string(target) + " bytes");
      }
      if (p.block != nextOriginal)
        fail(pf + ".block", std::to_string(p.block) + ", expected " + std::to_string(nextOriginal) +
                                " (pieces fill the original-texture blocks in directory order)");
      ++nextOriginal;
      advance();
      const BlockInfo& b = m_.blocks[p.block];
      if (b.node != p.image)
        fail(at("blocks", p.block) + ".node",
             std::to_string(b.node) + ", but its piece (" + pf + ") belongs to image " + std::to_string(p.image));
      if (p.offset != 0) fail(pf + ".offset", std::to_string(p.offset) + ", expected 0 (a block holds one piece)");
    }
    if (!m_.pieces.empty()) close(m_.pieces.size() - 1);
    if (nextOriginal < m_.blocks.size())
      fail(at("blocks", nextOriginal), "an original-texture block that holds no pieces");
  }

  // Which trees' leaves use each image decides whether it is stored and with how many channels.
  void imageUse() const {
    for (size_t i = 0; i < m_.images.size(); ++i) {
      const ImageRecord& r = m_.images[i];
      const uint8_t users = imageUsers_[i];
      const std::string f = at("images", i);
      if (users == 0) {
        if (r.pieceCount != 0)
          fail(f + ".piece_count",
               std::to_string(r.pieceCount) + " pieces of an image no leaf uses (those are not stored)");
        continue;
      }
      if (r.pieceCount == 0) fail(f + ".piece_count", "0, but leaves use the image, so it must be stored");
      const uint32_t want = (users & 2) ? 4 : 3;
      if (r.channels != want)
        fail(f + ".channels",
             std::to_string(r.channels) + ", expected " + std::to_string(want) +
                 (want == 4 ? " (leaves of the RGBA tree use it)" : " (only leaves of the RGB tree use it)"));
    }
  }

  const MtaMeta& m_;
  const std::string& path_;
  uint64_t metaOffset_;
  const ResourceLimits& limits_;
  std::vector<uint8_t> imageUsers_;  // per image: bit alpha set when a leaf of that tree lists it
};

}  // namespace

void validateMetadata(const MtaMeta& meta, const std::string& path, uint64_t metaOffset, const ResourceLimits& limits) {
  Validator(meta, path, metaOffset, limits).run();
}

}  // namespace tessera::mta
