// loadModel()'s dispatch, and lazy texture access through OpenImageIO (raster/image_module.h).
#include "model/model.h"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <glm/common.hpp>

#include "base/error.h"
#include "model/loaders.h"
#include "model/scene_manifest.h"
#include "raster/image_module.h"

namespace tessera::model {

namespace fs = std::filesystem;

// glm::min / glm::max are (y < x) ? y : x and (x < y) ? y : x per component, as std::min / std::max.
void Bounds::add(const glm::vec3& p) {
  min = glm::min(min, p);
  max = glm::max(max, p);
}

size_t Model::triangleCount() const {
  size_t n = 0;
  for (const Mesh& m : meshes) n += m.triangleCount();
  return n;
}

namespace detail {

std::string uriDecode(std::string_view uri) {
  if (uri.starts_with("file://")) uri.remove_prefix(7);
  std::string out;
  out.reserve(uri.size());
  auto hex = [](char c) -> int {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return -1;
  };
  for (size_t i = 0; i < uri.size(); ++i) {
    if (uri[i] == '%' && i + 2 < uri.size() && hex(uri[i + 1]) >= 0 && hex(uri[i + 2]) >= 0) {
      out += char(hex(uri[i + 1]) * 16 + hex(uri[i + 2]));
      i += 2;
    } else {
      out += uri[i];
    }
  }
  return out;
}

std::string resolveBeside(const std::string& modelPath, const std::string& relative) {
  std::string r = relative;
  std::replace(r.begin(), r.end(), '\\', '/');  // Windows exporters
  const fs::path p(r);
  if (p.is_absolute()) return p.lexically_normal().string();
  return (fs::path(modelPath).parent_path() / p).lexically_normal().string();
}

void requireTextureFile(const std::string& modelPath, const std::string& what, const std::string& uri,
                        const std::string& resolved) {
  std::error_code ec;
  if (fs::is_regular_file(resolved, ec)) return;
  throw Error(modelPath + ": " + what + ": texture file '" + resolved + "' (written as '" + uri + "') does not exist");
}

namespace {

const char* budgetWhat(ModelBudget b) {
  switch (b) {
    case ModelBudget::Instances:
      return "node instances";
    case ModelBudget::Triangles:
      return "triangles";
    case ModelBudget::Vertices:
      return "vertices";
    default:
      return "of decoded RGBA8 textures";
  }
}

}  // namespace

void requireWithinBudget(const std::string& where, ModelBudget budget, uint64_t need, const ResourceLimits& limits) {
  // The options are wired by the commands that load models (docs/limits.md).
  static constexpr std::string_view kOption[] = {"--model-budget-instances", "--model-budget-triangles",
                                                 "--model-budget-vertices", "--model-budget-textures"};
  const uint64_t limit = budget == ModelBudget::Instances   ? limits.modelInstances
                         : budget == ModelBudget::Triangles ? limits.modelTriangles
                         : budget == ModelBudget::Vertices  ? limits.modelVertices
                                                            : limits.modelTextureBytes;
  if (need <= limit) return;
  throw Error(overLimitMessage(where, budgetWhat(budget), need == UINT64_MAX ? std::nullopt : std::optional(need),
                               limit, kOption[int(budget)], budget == ModelBudget::TextureBytes));
}

}  // namespace detail

namespace {

TextureInfo readHeader(const Model& model, size_t index);

// Reads every texture's header once and checks the decoded RGBA8 bytes of all of them against the budget
// before anything is decoded. Headers are cheap (railway.glb: 28 in a few ms, docs/model-import.md) and
// the consumers of a model read them all anyway (mta::sceneFromModel), so they are kept in TextureRef.
// A header that cannot be read counts zero bytes: loadTexture() will refuse that image with the reason.
void readHeadersWithinBudget(Model& m, const ResourceLimits& limits) {
  uint64_t total = 0, largestBytes = 0;
  size_t largest = 0;
  for (size_t i = 0; i < m.textures.size(); ++i) {
    try {
      m.textures[i].header = readHeader(m, i);
    } catch (const Error&) {
      continue;
    }
    const TextureInfo& h = m.textures[i].header;
    const uint64_t bytes = detail::saturatingMul(uint64_t(h.width) * h.height, 4);
    total = detail::saturatingAdd(total, bytes);
    if (bytes > largestBytes) largestBytes = bytes, largest = i;
  }
  if (total <= limits.modelTextureBytes) return;
  const TextureRef& t = m.textures[largest];
  try {
    detail::requireWithinBudget(m.source, detail::ModelBudget::TextureBytes, total, limits);
  } catch (const Error& e) {
    throw Error(std::string(e.what()) + "; the largest is texture " + std::to_string(largest) + " '" + t.name + "' (" +
                std::to_string(t.header.width) + "x" + std::to_string(t.header.height) + ")");
  }
}

}  // namespace

namespace detail {

Model loadModelFile(const std::string& path, const ResourceLimits& limits) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) throw Error(path + ": no such model file");
  char magic[4] = {};
  {
    std::ifstream f(path, std::ios::binary);
    if (!f) throw Error(path + ": cannot open for reading");
    f.read(magic, 4);
  }
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  Model m;
  const bool ac3d = std::memcmp(magic, "AC3D", 4) == 0;
  if (std::memcmp(magic, "glTF", 4) == 0 || (!ac3d && (ext == ".gltf" || ext == ".glb")))
    m = detail::loadGltf(path, limits);
  else if (ac3d || ext == ".ac" || ext == ".acc" || ext == ".ac3d")
    m = detail::loadAc3d(path, limits);
  else if (ext == ".obj")
    m = detail::loadObj(path, limits);
  else
    m = detail::loadAssimp(path, limits);
  m.source = path;
  return m;
}

}  // namespace detail

// The one place where a path becomes a Model, so every command that takes a model takes a scene too.
Model loadModel(const std::string& path, const ResourceLimits& limits) {
  std::error_code ec;
  if (!fs::exists(path, ec)) throw Error(path + ": no such model file");
  Model m;
  if (fs::is_directory(path, ec))
    m = detail::mergeScene(detail::readSceneDirectory(path), limits);
  else if (detail::isScenePath(path))
    m = detail::mergeScene(detail::readSceneManifest(path), limits);
  else
    m = detail::loadModelFile(path, limits);
  m.source = path;
  // The loaders refuse geometry over the budgets before reading it; this repeats the check on the result,
  // for any loader that counts less precisely.
  uint64_t vertices = 0;
  for (const Mesh& mesh : m.meshes) vertices += mesh.positions.size();
  detail::requireWithinBudget(path, detail::ModelBudget::Triangles, m.triangleCount(), limits);
  detail::requireWithinBudget(path, detail::ModelBudget::Vertices, vertices, limits);
  readHeadersWithinBudget(m, limits);
  for (const Mesh& mesh : m.meshes)
    for (const glm::vec3& p : mesh.positions) m.bounds.add(p);
  return m;
}

namespace {

// The OIIO format to try for encoded bytes: by signature, then by MIME type, then by extension.
std::string formatHint(const TextureRef& t, const uint8_t* head, size_t n) {
  auto is = [&](const char* sig, size_t len) { return n >= len && std::memcmp(head, sig, len) == 0; };
  if (is("\x89PNG", 4)) return "png";
  if (is("\xff\xd8\xff", 3)) return "jpg";
  if (is("DDS ", 4)) return "dds";
  if (is("\x01\xda", 2)) return "sgi";
  if (is("BM", 2)) return "bmp";
  if (is("GIF8", 4)) return "gif";
  if (is("RIFF", 4)) return "webp";
  if (t.mimeType == "image/png") return "png";
  if (t.mimeType == "image/jpeg") return "jpg";
  std::string ext = fs::path(t.path.empty() ? t.uri : t.path).extension().string();
  if (!ext.empty()) return ext.substr(1);
  return "tga";  // TGA has no signature at the start
}

std::string describe(const Model& m, size_t index) {
  const TextureRef& t = m.textures[index];
  std::string s = m.source + ": texture " + std::to_string(index) + " '" + t.name + "'";
  if (t.source == TextureRef::Source::File) s += " (" + t.path + ")";
  if (t.source == TextureRef::Source::FileRange)
    s += " (bytes " + std::to_string(t.offset) + "+" + std::to_string(t.size) + " of " + t.path + ")";
  return s;
}

std::vector<uint8_t> readRange(const std::string& what, const std::string& path, uint64_t offset, uint64_t size) {
  std::ifstream f(path, std::ios::binary);
  if (!f) throw Error(what + ": cannot open " + path);
  f.seekg(std::streamoff(offset));
  std::vector<uint8_t> bytes(size);
  if (!f.read(reinterpret_cast<char*>(bytes.data()), std::streamsize(size)))
    throw Error(what + ": the file ends before the image's byte range");
  return bytes;
}

// An open OIIO reader on the texture's bytes. Memory and file ranges go through an IOMemReader when
// the format's plugin supports IOProxy; otherwise through a temporary file (removed on destruction).
void requireIndex(const Model& m, size_t index) {
  if (index >= m.textures.size())
    throw Error(m.source + ": texture " + std::to_string(index) + " does not exist (" +
                std::to_string(m.textures.size()) + " textures)");
}

class OpenTexture {
 public:
  OpenTexture(const Model& m, size_t index) : what_((requireIndex(m, index), describe(m, index))) {
    const TextureRef& t = m.textures[index];
    const imagemod::Api& api = imagemod::api();
    std::string error;
    // Alpha as stored, colour not premultiplied (the module's readers never premultiply).
    if (t.source == TextureRef::Source::File) {
      in_ = api.open(t.path, error);
      if (!in_) throw Error(what_ + ": cannot read image: " + error);
      return;
    }
    if (t.source == TextureRef::Source::FileRange) {
      owned_ = readRange(what_, t.path, t.offset, t.size);
      data_ = owned_.data(), size_ = owned_.size();
    } else {
      if (!t.bytes) throw Error(what_ + ": no bytes");
      data_ = t.bytes->data(), size_ = t.bytes->size();
    }
    const std::string ext = formatHint(t, data_, size_);
    in_ = api.openMemory(data_, size_, ext, error);
    if (!in_ && error.empty()) {  // that format's reader cannot read from memory
      static std::atomic<uint64_t> counter{0};
      temp_ = (fs::temp_directory_path() /
               ("tessera-texture-" + std::to_string(::getpid()) + "-" + std::to_string(counter++) + "." + ext))
                  .string();
      std::ofstream f(temp_, std::ios::binary);
      f.write(reinterpret_cast<const char*>(data_), std::streamsize(size_));
      f.close();
      if (!f) throw Error(what_ + ": cannot write the temporary file " + temp_);
      in_ = api.open(temp_, error);
    }
    if (!in_) throw Error(what_ + ": cannot read image (" + ext + "): " + error);
  }
  ~OpenTexture() {
    in_.reset();  // closed before its temporary file goes
    if (!temp_.empty()) std::remove(temp_.c_str());
  }
  imagemod::Reader& in() { return *in_; }
  const std::string& what() const { return what_; }

 private:
  std::string what_;
  std::vector<uint8_t> owned_;
  const uint8_t* data_ = nullptr;
  size_t size_ = 0;
  std::string temp_;
  std::unique_ptr<imagemod::Reader> in_;
};

}  // namespace

Image loadTexture(const Model& model, size_t index) {
  requireIndex(model, index);
  if (model.textures[index].rawRGBA) {
    const TextureRef& t = model.textures[index];
    Image img{{t.rawWidth, t.rawHeight, {}}, 4, false};
    if (!t.bytes || t.bytes->size() != size_t(t.rawWidth) * t.rawHeight * 4)
      throw Error(describe(model, index) + ": raw texel data has the wrong size");
    img.rgba = *t.bytes;
    for (size_t i = 3; i < img.rgba.size(); i += 4) img.usesAlpha = img.usesAlpha || img.rgba[i] != 255;
    return img;
  }
  OpenTexture ot(model, index);
  const imagemod::Header spec = ot.in().header();
  const int nc = spec.channels;
  if (spec.width <= 0 || spec.height <= 0 || nc <= 0 || spec.width > 65536 || spec.height > 65536)
    throw Error(ot.what() + ": unsupported image size " + std::to_string(spec.width) + "x" +
                std::to_string(spec.height) + "x" + std::to_string(nc));
  // The texture budget was checked against the header loadModel() read; an image that has grown since
  // (a file replaced on disk) is not decoded beyond it.
  const TextureInfo& h = model.textures[index].header;
  if (h.width > 0 && (uint32_t(spec.width) != h.width || uint32_t(spec.height) != h.height))
    throw Error(ot.what() + ": the image is " + std::to_string(spec.width) + "x" + std::to_string(spec.height) +
                ", its header said " + std::to_string(h.width) + "x" + std::to_string(h.height) +
                " when the model was loaded");
  Image img;
  img.width = uint32_t(spec.width), img.height = uint32_t(spec.height), img.fileChannels = nc;
  const size_t texels = size_t(img.width) * img.height;
  std::vector<uint8_t> raw(texels * size_t(nc));
  if (const std::string e = ot.in().read(imagemod::Type::U8, raw.data()); !e.empty())
    throw Error(ot.what() + ": cannot decode image: " + e);
  img.rgba.resize(texels * 4);
  const int alpha = spec.alphaChannel >= 0 ? spec.alphaChannel : (nc == 2 ? 1 : nc >= 4 ? 3 : -1);
  for (size_t i = 0; i < texels; ++i) {
    const uint8_t* s = &raw[i * size_t(nc)];
    uint8_t* d = &img.rgba[i * 4];
    if (nc <= 2) {
      d[0] = d[1] = d[2] = s[0];
    } else {
      d[0] = s[0], d[1] = s[1], d[2] = s[2];
    }
    d[3] = alpha >= 0 ? s[alpha] : 255;
    img.usesAlpha = img.usesAlpha || d[3] != 255;
  }
  return img;
}

namespace {

TextureInfo readHeader(const Model& model, size_t index) {
  requireIndex(model, index);
  if (model.textures[index].rawRGBA) return {model.textures[index].rawWidth, model.textures[index].rawHeight, 4, "raw"};
  OpenTexture ot(model, index);
  const imagemod::Header& spec = ot.in().header();
  return {uint32_t(std::max(spec.width, 0)), uint32_t(std::max(spec.height, 0)), spec.channels, spec.formatName};
}

}  // namespace

TextureInfo probeTexture(const Model& model, size_t index) {
  requireIndex(model, index);
  if (model.textures[index].header.width > 0) return model.textures[index].header;
  return readHeader(model, index);
}

}  // namespace tessera::model
