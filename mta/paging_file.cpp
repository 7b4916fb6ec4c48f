#include "mta/paging_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <type_traits>

#include "base/sha256.h"
#include "mta/paging_file_validation.h"
#include "raster/command_list.h"

namespace tessera::mta {

namespace {

constexpr char kMagic[8] = {'T', 'E', 'S', 'S', 'M', 'T', 'A', '\x1a'};

// Positions and texcoords are stored as the bytes of their glm vectors: 3 or 2 floats, no padding.
static_assert(sizeof(glm::vec3) == 12 && sizeof(glm::vec2) == 8 && std::is_trivially_copyable_v<glm::vec3> &&
              std::is_trivially_copyable_v<glm::vec2>);

// Little-endian serialization (the only hosts are little-endian x86-64; memcpy keeps it explicit).
struct Out {
  std::vector<uint8_t> b;
  template <class T>
  void put(T v) {
    const size_t o = b.size();
    b.resize(o + sizeof(T));
    std::memcpy(b.data() + o, &v, sizeof(T));
  }
  template <class T>
  void arr(const std::vector<T>& v) {
    put<uint64_t>(v.size());
    const size_t o = b.size();
    b.resize(o + v.size() * sizeof(T));
    if (!v.empty()) std::memcpy(b.data() + o, v.data(), v.size() * sizeof(T));
  }
  void str(const std::string& s) {
    put<uint32_t>(uint32_t(s.size()));
    b.insert(b.end(), s.begin(), s.end());
  }
};

struct In {
  const std::vector<uint8_t>& b;
  size_t pos = 0;
  const std::string& path;
  [[noreturn]] void fail(const std::string& field, const std::string& why) const {
    throw Error(path + ": metadata byte " + std::to_string(pos) + ", " + field + ": " + why);
  }
  template <class T>
  T get(const char* field) {
    if (b.size() - pos < sizeof(T)) fail(field, "truncated");
    T v;
    std::memcpy(&v, b.data() + pos, sizeof(T));
    pos += sizeof(T);
    return v;
  }
  template <class T>
  std::vector<T> arr(const char* field, uint64_t expect = UINT64_MAX) {
    const uint64_t n = get<uint64_t>(field);
    if (expect != UINT64_MAX && n != expect) fail(field, "has " + std::to_string(n) + " elements, expected " + std::to_string(expect));
    if (n > (b.size() - pos) / sizeof(T)) fail(field, "length " + std::to_string(n) + " exceeds the metadata");
    std::vector<T> v(n);
    if (n) std::memcpy(v.data(), b.data() + pos, n * sizeof(T));
    pos += n * sizeof(T);
    return v;
  }
  std::string str(const char* field) {
    const uint32_t n = get<uint32_t>(field);
    if (n > b.size() - pos) fail(field, "string length exceeds the metadata");
    std::string s(reinterpret_cast<const char*>(b.data() + pos), n);
    pos += n;
    return s;
  }
};

#pragma pack(push, 1)
struct NodeDisk {
  float bounds[6];
  float minDistance, coverage;
  uint32_t level, cellX, cellY;
  int32_t children[4], parent;
  uint32_t firstTriangle, triangleCount, imageFirst, imageCount;
};
struct BlockDisk {
  uint64_t offset, size;
  uint8_t kind, tree, layer, pad;
  uint32_t node;
  uint8_t sha[32];
};
struct PieceDisk {
  uint32_t image, block, row0, rows;
  uint64_t offset;
};
#pragma pack(pop)

}  // namespace

std::vector<uint8_t> encodeMetadata(const MtaMeta& m) {
  Out o;
  const BuildParams& p = m.params;
  o.put<uint32_t>(m.layerCount), o.put<uint32_t>(p.atlasSize), o.put<uint32_t>(p.border), o.put<uint32_t>(p.screenWidth);
  o.put<double>(p.dMin), o.put<double>(p.dMinDivisor), o.put<double>(p.tau), o.put<double>(p.fovDegrees);
  o.put<double>(p.tanHalfFov), o.put<double>(p.criticalThreshold);
  const BuildStats& s = m.stats;
  o.put(s.trianglesIn), o.put(s.trianglesOut), o.put(s.criticalAtRequested), o.put(s.criticalAfterRaise), o.put(s.trianglesAdded);
  o.put(s.maxSplitDepth), o.put(s.dMinRequested), o.put(s.dMinUsed), o.put(s.sceneDiagonal);
  o.put<uint32_t>(uint32_t(m.textures.size()));
  for (const SceneTexture& t : m.textures) o.put(t.image), o.put(uint8_t(t.wrapS)), o.put(uint8_t(t.wrapT));
  o.put<uint32_t>(uint32_t(m.images.size()));
  for (const ImageRecord& r : m.images) {
    o.put(r.width), o.put(r.height), o.put(r.channels), o.put(r.firstPiece), o.put(r.pieceCount);
    o.str(r.name);
  }
  std::vector<PieceDisk> pieces;
  for (const PieceRecord& r : m.pieces) pieces.push_back(PieceDisk{r.image, r.block, r.row0, r.rows, r.offset});
  o.arr(pieces);
  std::vector<BlockDisk> blocks;
  for (const BlockInfo& b : m.blocks) {
    BlockDisk d{b.offset, b.size, uint8_t(b.kind), b.tree, b.layer, 0, b.node, {}};
    std::memcpy(d.sha, b.sha256.data(), 32);
    blocks.push_back(d);
  }
  o.arr(blocks);
  o.put<uint32_t>(uint32_t(m.trees.size()));
  for (const Tree& t : m.trees) {
    o.put(t.alpha);
    std::vector<NodeDisk> nodes;
    for (const Node& n : t.nodes) {
      NodeDisk d{};
      std::memcpy(d.bounds, n.bounds.data(), sizeof d.bounds);
      d.minDistance = n.minDistance, d.coverage = n.coverage, d.level = n.level, d.cellX = n.cellX, d.cellY = n.cellY;
      std::memcpy(d.children, n.children.data(), sizeof d.children);
      d.parent = n.parent, d.firstTriangle = n.firstTriangle, d.triangleCount = n.triangleCount;
      d.imageFirst = n.imageFirst, d.imageCount = n.imageCount;
      nodes.push_back(d);
    }
    o.arr(nodes);
    o.arr(t.geometry.positions);
    o.arr(t.geometry.source);
    for (uint32_t l = 0; l < m.layerCount; ++l) o.arr(t.geometry.layers[l].texture), o.arr(t.geometry.layers[l].uv);
    o.arr(t.atlasUV);
    o.arr(t.leafImages);
    o.arr(t.atlasBlocks);
  }
  return std::move(o.b);
}

uint64_t metadataBytes(const MtaMeta& m, uint64_t pieces, uint64_t blocks) {
  // Field by field as encodeMetadata writes them; an array is its uint64 length and its elements.
  uint64_t n = 4 * 4 + 6 * 8;        // layer_count, atlas_size, border, screen_width; six doubles
  n += 5 * 8 + 4 + 3 * 8;            // stats
  n += 4 + uint64_t(m.textures.size()) * (4 + 1 + 1);
  n += 4;
  for (const ImageRecord& r : m.images) n += 5 * 4 + 4 + r.name.size();
  n += 8 + pieces * sizeof(PieceDisk);
  n += 8 + blocks * sizeof(BlockDisk);
  n += 4;
  for (const Tree& t : m.trees) {
    n += 1 + 8 + uint64_t(t.nodes.size()) * sizeof(NodeDisk);
    n += 8 + uint64_t(t.geometry.positions.size()) * sizeof(glm::vec3);
    n += 8 + uint64_t(t.geometry.source.size()) * sizeof(uint32_t);
    for (uint32_t l = 0; l < m.layerCount; ++l)
      n += 8 + uint64_t(t.geometry.layers[l].texture.size()) * sizeof(int32_t) + 8 +
           uint64_t(t.geometry.layers[l].uv.size()) * sizeof(glm::vec2);
    n += 8 + uint64_t(t.atlasUV.size()) * sizeof(glm::vec2);
    n += 8 + uint64_t(t.leafImages.size()) * sizeof(uint32_t);
    n += 8 + uint64_t(t.atlasBlocks.size()) * sizeof(uint32_t);
  }
  return n;
}

namespace {

MtaMeta deserialize(const std::vector<uint8_t>& bytes, const std::string& path) {
  In in{bytes, 0, path};
  MtaMeta m;
  BuildParams& p = m.params;
  m.layerCount = in.get<uint32_t>("layer_count");
  p.atlasSize = in.get<uint32_t>("atlas_size"), p.border = in.get<uint32_t>("border"), p.screenWidth = in.get<uint32_t>("screen_width");
  p.dMin = in.get<double>("d_min"), p.dMinDivisor = in.get<double>("d_min_divisor"), p.tau = in.get<double>("tau");
  p.fovDegrees = in.get<double>("fov"), p.tanHalfFov = in.get<double>("tan_half_fov");
  p.criticalThreshold = in.get<double>("critical_threshold");
  // Bounds the per-layer arrays below; the parameters' ranges are checked with the rest (validateMetadata).
  if (m.layerCount < 1 || m.layerCount > kMaxLayers)
    in.fail("layer_count", std::to_string(m.layerCount) + " outside [1, " + std::to_string(kMaxLayers) + "]");
  BuildStats& s = m.stats;
  s.trianglesIn = in.get<uint64_t>("stats"), s.trianglesOut = in.get<uint64_t>("stats");
  s.criticalAtRequested = in.get<uint64_t>("stats"), s.criticalAfterRaise = in.get<uint64_t>("stats");
  s.trianglesAdded = in.get<uint64_t>("stats"), s.maxSplitDepth = in.get<uint32_t>("stats");
  s.dMinRequested = in.get<double>("stats"), s.dMinUsed = in.get<double>("stats"), s.sceneDiagonal = in.get<double>("stats");
  const uint32_t nt = in.get<uint32_t>("textures");
  if (nt > bytes.size()) in.fail("textures", "count exceeds the metadata");
  for (uint32_t i = 0; i < nt; ++i) {
    SceneTexture t;
    t.image = in.get<uint32_t>("texture.image");
    const uint8_t ws = in.get<uint8_t>("texture.wrap"), wt = in.get<uint8_t>("texture.wrap");
    if (ws > 2 || wt > 2)
      in.fail("textures[" + std::to_string(i) + "].wrap",
              "mode " + std::to_string(ws > 2 ? ws : wt) + " is not 0, 1 or 2");
    t.wrapS = model::Wrap(ws), t.wrapT = model::Wrap(wt);
    m.textures.push_back(t);
  }
  const uint32_t ni = in.get<uint32_t>("images");
  if (ni > bytes.size()) in.fail("images", "count exceeds the metadata");
  for (uint32_t i = 0; i < ni; ++i) {
    ImageRecord r;
    r.width = in.get<uint32_t>("image.width"), r.height = in.get<uint32_t>("image.height");
    r.channels = in.get<uint32_t>("image.channels"), r.firstPiece = in.get<uint32_t>("image.first_piece");
    r.pieceCount = in.get<uint32_t>("image.piece_count");
    r.name = in.str("image.name");
    m.images.push_back(r);
  }
  for (const PieceDisk& d : in.arr<PieceDisk>("pieces")) m.pieces.push_back(PieceRecord{d.image, d.block, d.row0, d.rows, d.offset});
  for (const BlockDisk& d : in.arr<BlockDisk>("blocks")) {
    if (d.pad != 0)
      throw Error(path + ": blocks[" + std::to_string(m.blocks.size()) + "].pad: " + std::to_string(d.pad) +
                  " (must be 0)");
    BlockInfo b{d.offset, d.size, BlockKind(d.kind), d.tree, d.layer, d.node, {}};
    std::memcpy(b.sha256.data(), d.sha, 32);
    m.blocks.push_back(b);
  }
  const uint32_t ntree = in.get<uint32_t>("trees");
  if (ntree > 2) in.fail("trees", std::to_string(ntree) + " trees (at most 2: RGB and RGBA)");
  for (uint32_t ti = 0; ti < ntree; ++ti) {
    Tree t;
    t.alpha = in.get<uint8_t>("tree.alpha");
    for (const NodeDisk& d : in.arr<NodeDisk>("tree.nodes")) {
      Node n;
      std::memcpy(n.bounds.data(), d.bounds, sizeof d.bounds);
      n.minDistance = d.minDistance, n.coverage = d.coverage, n.level = d.level, n.cellX = d.cellX, n.cellY = d.cellY;
      std::memcpy(n.children.data(), d.children, sizeof d.children);
      n.parent = d.parent, n.firstTriangle = d.firstTriangle, n.triangleCount = d.triangleCount;
      n.imageFirst = d.imageFirst, n.imageCount = d.imageCount;
      t.nodes.push_back(n);
    }
    t.geometry.positions = in.arr<glm::vec3>("tree.positions");
    const uint64_t tris = t.geometry.positions.size() / 3;
    if (t.geometry.positions.size() % 3) in.fail("tree.positions", "not 3 per triangle");
    t.geometry.source = in.arr<uint32_t>("tree.source", tris);
    t.geometry.alpha.assign(tris, t.alpha);
    t.geometry.layers.resize(m.layerCount);
    for (uint32_t l = 0; l < m.layerCount; ++l) {
      t.geometry.layers[l].texture = in.arr<int32_t>("tree.layer.texture", tris);
      t.geometry.layers[l].uv = in.arr<glm::vec2>("tree.layer.uv", tris * 3);
    }
    t.atlasUV = in.arr<glm::vec2>("tree.atlas_uv", tris * 3);
    t.leafImages = in.arr<uint32_t>("tree.leaf_images");
    t.atlasBlocks = in.arr<uint32_t>("tree.atlas_blocks", uint64_t(t.nodes.size()) * m.layerCount);
    m.trees.push_back(std::move(t));
  }
  if (in.pos != bytes.size()) in.fail("end", std::to_string(bytes.size() - in.pos) + " trailing bytes");
  return m;
}

}  // namespace

const char* blockKindName(BlockKind k) { return k == BlockKind::Atlas ? "atlas" : k == BlockKind::Original ? "original" : "?"; }

PagingFileWriter::PagingFileWriter(std::string path) : path_(std::move(path)), file_(path_) {
  const std::vector<uint8_t> zero(kHeaderSize, 0);
  file_.writeAt(0, zero);
}

PagingFileWriter::~PagingFileWriter() = default;

uint32_t PagingFileWriter::addBlock(BlockKind kind, uint8_t tree, uint8_t layer, uint32_t node, std::span<const uint8_t> bytes) {
  end_ = (end_ + 15) & ~uint64_t(15);
  BlockInfo b{end_, bytes.size(), kind, tree, layer, node, sha256(bytes)};
  file_.writeAt(end_, bytes);
  end_ += bytes.size();
  blocks_.push_back(b);
  return uint32_t(blocks_.size() - 1);
}

void PagingFileWriter::finish(MtaMeta& meta) {
  meta.blocks = blocks_;
  const std::vector<uint8_t> body = encodeMetadata(meta);
  const uint64_t metaOffset = (end_ + 15) & ~uint64_t(15);
  file_.writeAt(metaOffset, body);
  uint8_t h[kHeaderSize] = {};
  std::memcpy(h, kMagic, 8);
  const uint32_t version = kFormatVersion, hs = kHeaderSize, encoding = uint32_t(meta.encoding);
  const uint64_t fileSize = metaOffset + body.size(), metaSize = body.size();
  std::memcpy(h + 8, &version, 4), std::memcpy(h + 12, &hs, 4);
  std::memcpy(h + 16, &fileSize, 8), std::memcpy(h + 24, &metaOffset, 8), std::memcpy(h + 32, &metaSize, 8);
  const auto ms = sha256(body);
  std::memcpy(h + 40, ms.data(), 32);
  std::memcpy(h + 72, &encoding, 4);
  const auto hsha = sha256(std::span<const uint8_t>(h, 96));
  std::memcpy(h + 96, hsha.data(), 32);
  file_.writeAt(0, std::span<const uint8_t>(h, kHeaderSize));
  file_.commit();
}

PagingFile::PagingFile(std::string path, const ResourceLimits& limits) : path_(std::move(path)) {
  fd_ = ::open(path_.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd_ < 0) throw Error(path_ + ": cannot open: " + std::strerror(errno));
  // A constructor that throws runs no destructor: without this, every refused file leaked its descriptor
  // (a fuzz run ran out of them after some 20,000 inputs).
  try {
    load(limits);
  } catch (...) {
    ::close(fd_);
    fd_ = -1;
    throw;
  }
}

void PagingFile::load(const ResourceLimits& limits) {
  struct stat st{};
  if (::fstat(fd_, &st) != 0) throw Error(path_ + ": cannot stat: " + std::strerror(errno));
  if (S_ISDIR(st.st_mode)) throw Error(path_ + ": is a directory, not an atlas tree file");
  fileSize_ = uint64_t(st.st_size);
  uint8_t h[kHeaderSize];
  if (fileSize_ < kHeaderSize || ::pread(fd_, h, kHeaderSize, 0) != ssize_t(kHeaderSize))
    throw Error(path_ + ": truncated: " + std::to_string(fileSize_) + " bytes, shorter than the 128-byte header");
  if (std::memcmp(h, kMagic, 8) != 0) throw Error(path_ + ": not a Tessera atlas tree file (bad magic)");
  const auto hsha = sha256(std::span<const uint8_t>(h, 96));
  if (std::memcmp(hsha.data(), h + 96, 32) != 0) throw Error(path_ + ": header checksum mismatch (corrupted header)");
  uint32_t version, hs;
  uint64_t size, metaOffset, metaSize;
  std::memcpy(&version, h + 8, 4), std::memcpy(&hs, h + 12, 4);
  std::memcpy(&size, h + 16, 8), std::memcpy(&metaOffset, h + 24, 8), std::memcpy(&metaSize, h + 32, 8);
  if (version == 1)
    throw Error(path_ + ": format version 1: its original images share blocks, which this reader no longer accepts "
                "(version 2 gives every image blocks of its own, docs/mta-format.md); rebuild it with `tessera mta build`");
  if (version == 2)
    throw Error(path_ + ": format version 2: its header does not record the block encoding, which this reader needs "
                "(version 3 stores raw or S3TC blocks, docs/mta-format.md); rebuild it with `tessera mta build`");
  if (version != kFormatVersion)
    throw Error(path_ + ": format version " + std::to_string(version) + " (this reader knows " +
                std::to_string(kFormatVersion) + ")");
  if (hs != kHeaderSize) throw Error(path_ + ": header size " + std::to_string(hs) + " (expected 128)");
  if (size != fileSize_)
    throw Error(path_ + ": file is " + std::to_string(fileSize_) + " bytes but the header says " + std::to_string(size) +
                (fileSize_ < size ? " (truncated)" : " (trailing bytes)"));
  if (metaOffset < kHeaderSize || metaOffset > size || metaSize != size - metaOffset)
    throw Error(path_ + ": metadata range [" + std::to_string(metaOffset) + ", +" + std::to_string(metaSize) + ") is invalid");
  std::vector<uint8_t> body(metaSize);
  if (metaSize && ::pread(fd_, body.data(), metaSize, off_t(metaOffset)) != ssize_t(metaSize))
    throw Error(path_ + ": cannot read the metadata");
  const auto ms = sha256(body);
  if (std::memcmp(ms.data(), h + 40, 32) != 0) throw Error(path_ + ": metadata checksum mismatch (corrupted node table or geometry)");
  uint32_t encoding;
  std::memcpy(&encoding, h + 72, 4);
  if (encoding > uint32_t(BlockEncoding::S3tc))
    throw Error(path_ + ": header.encoding: " + std::to_string(encoding) + " is not 0 (raw) or 1 (S3TC)");
  for (int i = 76; i < 96; ++i)
    if (h[i] != 0) throw Error(path_ + ": header byte " + std::to_string(i) + ": " + std::to_string(h[i]) + " (reserved, must be 0)");
  meta_ = deserialize(body, path_);
  meta_.encoding = BlockEncoding(encoding);
  validateMetadata(meta_, path_, metaOffset, limits);
}

PagingFile::~PagingFile() {
  if (fd_ >= 0) ::close(fd_);
}

std::vector<uint8_t> PagingFile::readBlock(uint32_t index) const {
  if (index >= meta_.blocks.size())
    throw Error(path_ + ": block " + std::to_string(index) + " out of range (" + std::to_string(meta_.blocks.size()) + " blocks)");
  const BlockInfo& b = meta_.blocks[index];
  std::vector<uint8_t> bytes(b.size);
  size_t done = 0;
  while (done < b.size) {
    const ssize_t r = ::pread(fd_, bytes.data() + done, b.size - done, off_t(b.offset + done));
    if (r <= 0) throw Error(path_ + ": block " + std::to_string(index) + ": read failed");
    done += size_t(r);
  }
  if (sha256(bytes) != b.sha256)
    throw Error(path_ + ": block " + std::to_string(index) + " (" + blockKindName(b.kind) + ", node/image " +
                std::to_string(b.node) + "): checksum mismatch");
  return bytes;
}

std::vector<uint8_t> PagingFile::readImage(uint32_t image) const {
  if (image >= meta_.images.size()) throw Error(path_ + ": image " + std::to_string(image) + " out of range");
  const ImageRecord& r = meta_.images[image];
  if (meta_.encoding == BlockEncoding::S3tc) {
    // One piece, one block, its chain (validated): level 0 decoded.
    if (r.pieceCount != 1) throw Error(path_ + ": images[" + std::to_string(image) + "]: internal error: not one piece");
    return decodeS3tcLevel0(r.width, r.height, r.channels, readBlock(meta_.pieces.at(r.firstPiece).block));
  }
  std::vector<uint8_t> out(size_t(r.width) * r.height * r.channels);
  const size_t rowBytes = size_t(r.width) * r.channels;
  for (uint32_t k = 0; k < r.pieceCount; ++k) {
    const PieceRecord& p = meta_.pieces.at(size_t(r.firstPiece) + k);
    const std::vector<uint8_t> block = readBlock(p.block);
    // Guaranteed by the validator; checked again because a wrong record here would copy out of bounds.
    if (uint64_t(p.row0) + p.rows > r.height || p.offset > block.size() || p.rows * rowBytes > block.size() - p.offset)
      throw Error(path_ + ": pieces[" + std::to_string(r.firstPiece + k) +
                  "]: internal error: outside its image or block");
    std::memcpy(out.data() + p.row0 * rowBytes, block.data() + p.offset, p.rows * rowBytes);
  }
  return out;
}

std::vector<uint8_t> PagingFile::readAtlas(uint32_t tree, uint32_t node, uint32_t layer) const {
  if (tree >= meta_.trees.size() || node >= meta_.trees[tree].nodes.size() || layer >= meta_.layerCount)
    throw Error(path_ + ": atlas (tree " + std::to_string(tree) + ", node " + std::to_string(node) + ", layer " +
                std::to_string(layer) + ") out of range");
  std::vector<uint8_t> bytes = readBlock(meta_.trees[tree].atlasBlocks[size_t(node) * meta_.layerCount + layer]);
  if (meta_.encoding == BlockEncoding::Raw) return bytes;
  const uint32_t a = meta_.params.atlasSize;
  return decodeS3tcLevel0(a, a, meta_.trees[tree].channels(), bytes);
}

}  // namespace tessera::mta
