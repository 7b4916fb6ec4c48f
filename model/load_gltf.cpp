// glTF 2.0 (.gltf / .glb) through tinygltf (Debian's libtinygltf, linked, not compiled in here).
//
// Images are never decoded here. tinygltf is given an image callback that only stashes the bytes of
// data: URIs, and file-system callbacks that read buffers but refuse image files, so an external
// image costs one stat() at load time and a .glb's images stay where they are in the file: a
// TextureRef records (file, offset, size) and loadTexture() reads that range when asked.
// Before tinygltf sees the file, the .glb container and the JSON are checked here (gltf_checks.h), so
// a truncated or malformed file is an Error naming the file and the JSON pointer, never a crash. Then
// the node graph is walked without recursion and every accessor a reached mesh reads is range-checked,
// and the instances, triangles and vertices are counted against the model budgets (gltf_graph.h),
// before any geometry is read or allocated.
#include <tiny_gltf.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>

#include "model/gltf_accessors.h"
#include "model/gltf_checks.h"
#include "model/gltf_graph.h"
#include "model/gltf_version.h"
#include "model/loaders.h"
#include "raster/command_list.h"
#include "base/det_math.h"

namespace tessera::model::detail {

namespace {

namespace fs = std::filesystem;
using gltf::fail;
using gltf::le32;
using gltf::Reader;

std::vector<uint8_t> readWholeFile(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  if (!f) throw Error(path + ": cannot open for reading");
  f.seekg(0, std::ios::end);
  const std::streamoff n = f.tellg();
  f.seekg(0);
  std::vector<uint8_t> bytes(size_t(std::max<std::streamoff>(n, 0)));
  if (!bytes.empty() && !f.read(reinterpret_cast<char*>(bytes.data()), n)) throw Error(path + ": read failed");
  return bytes;
}

std::string canonical(const std::string& p) {
  std::error_code ec;
  fs::path c = fs::weakly_canonical(p, ec);
  return ec ? fs::path(p).lexically_normal().string() : c.string();
}

// State shared with tinygltf's callbacks.
struct LoadContext {
  std::set<std::string> bufferFiles;  // canonical paths of external buffers: the only files read
  std::map<int, std::shared_ptr<const std::vector<uint8_t>>> dataUriImages;
};

bool fileExists(const std::string& p, void*) {
  std::error_code ec;
  return fs::is_regular_file(p, ec);
}
std::string expandPath(const std::string& p, void*) { return p; }
bool readBufferFile(std::vector<unsigned char>* out, std::string* err, const std::string& p, void* user) {
  auto* ctx = static_cast<LoadContext*>(user);
  if (!ctx->bufferFiles.count(canonical(p))) {
    if (err) *err = "deferred";  // an image: read lazily by loadTexture()
    return false;
  }
  try {
    *out = readWholeFile(p);
  } catch (const Error& e) {
    if (err) *err = e.what();
    return false;
  }
  return true;
}
bool refuseWrite(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
  if (err) *err = "writing is not supported";
  return false;
}
bool stashImage(tinygltf::Image* image, const int index, std::string*, std::string*, int, int,
                const unsigned char* bytes, int size, void* user) {
  // Called for data: URIs and bufferView images; only data: URIs need their bytes kept (a bufferView
  // image is re-read from its file range).
  if (image->bufferView < 0 && bytes && size > 0)
    static_cast<LoadContext*>(user)->dataUriImages[index] =
        std::make_shared<const std::vector<uint8_t>>(bytes, bytes + size);
  return true;
}

// The texcoord set and KHR_texture_transform of one of a material's textures.
struct UvSource {
  int set = 0;
  bool transform = false;
  double offset[2] = {0, 0}, scale[2] = {1, 1}, rotation = 0;
};

double number(const std::string& path, const nlohmann::json& j, const std::string& ptr) {
  if (!j.is_number() || !std::isfinite(j.get<double>())) fail(path, ptr, "expected a finite number");
  return j.get<double>();
}

// ptr: the texture info object (".../baseColorTexture", ".../occlusionTexture").
UvSource uvSource(const std::string& path, const nlohmann::json& root, const std::string& ptr) {
  UvSource s;
  const nlohmann::json::json_pointer jp(ptr);
  if (!root.contains(jp)) return s;
  const nlohmann::json& ti = root.at(jp);
  if (ti.contains("texCoord")) s.set = int(number(path, ti["texCoord"], ptr + "/texCoord"));
  const nlohmann::json::json_pointer tp("/extensions/KHR_texture_transform");
  if (!ti.contains(tp)) return s;
  const nlohmann::json& t = ti.at(tp);
  const std::string tptr = ptr + "/extensions/KHR_texture_transform";
  s.transform = true;
  for (int k = 0; k < 2; ++k) {
    if (t.contains("offset"))
      s.offset[k] = number(path, t["offset"].is_array() && t["offset"].size() == 2 ? t["offset"][k] : nlohmann::json(),
                           tptr + "/offset");
    if (t.contains("scale"))
      s.scale[k] = number(path, t["scale"].is_array() && t["scale"].size() == 2 ? t["scale"][k] : nlohmann::json(),
                          tptr + "/scale");
  }
  if (t.contains("rotation")) s.rotation = number(path, t["rotation"], tptr + "/rotation");
  if (t.contains("texCoord")) s.set = int(number(path, t["texCoord"], tptr + "/texCoord"));
  return s;
}

Wrap wrapOf(int mode) {
  if (mode == TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE) return Wrap::ClampToEdge;
  if (mode == TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT) return Wrap::MirroredRepeat;
  return Wrap::Repeat;
}

class Builder {
 public:
  Builder(const std::string& path, const tinygltf::Model& m, const nlohmann::json& root, const ResourceLimits& limits,
          Model& out)
      : path_(path), m_(m), root_(root), limits_(limits), out_(out), reader_(path, m) {}

  void run() {
    materials();
    std::vector<int> roots;
    std::string rootsPointer = "/nodes";
    if (!m_.scenes.empty()) {
      const int s = m_.defaultScene >= 0 ? m_.defaultScene : 0;
      if (size_t(s) >= m_.scenes.size()) fail(path_, "/scene", std::to_string(s) + " is not a scene index");
      roots = m_.scenes[size_t(s)].nodes;
      rootsPointer = "/scenes/" + std::to_string(s) + "/nodes";
    } else {  // no scene: every node nobody lists as a child
      std::vector<bool> child(m_.nodes.size());
      for (const auto& n : m_.nodes)
        for (int c : n.children)
          if (c >= 0 && size_t(c) < child.size()) child[size_t(c)] = true;
      for (size_t i = 0; i < m_.nodes.size(); ++i)
        if (!child[i]) roots.push_back(int(i));
    }
    // The whole graph and every accessor a reached mesh reads are checked, and the instances,
    // triangles and vertices counted, before any geometry is read.
    const gltf::NodeGraph graph(path_, m_, limits_, std::move(roots), rootsPointer);
    graph.check([&](int mesh) { return meshCost(mesh); });
    graph.forEachInstance([&](int node, const glm::dmat4& world) { instance(node, world); });
    if (defaultMaterial_ >= 0) out_.notes.push_back("primitives without a material use a default white material");
  }

 private:
  void materials() {
    for (size_t i = 0; i < m_.materials.size(); ++i) {
      const tinygltf::Material& gm = m_.materials[i];
      Material mat;
      mat.name = gm.name;
      const auto& f = gm.pbrMetallicRoughness.baseColorFactor;
      if (f.size() == 4)
        for (int k = 0; k < 4; ++k) mat.baseColorFactor[size_t(k)] = float(f[size_t(k)]);
      mat.alphaMode = gm.alphaMode == "MASK"    ? AlphaMode::Mask
                      : gm.alphaMode == "BLEND" ? AlphaMode::Blend
                                                : AlphaMode::Opaque;
      mat.alphaCutoff = float(gm.alphaCutoff);
      mat.doubleSided = gm.doubleSided;
      const std::string mptr = "/materials/" + std::to_string(i);
      mat.baseColorTexture = textureImage(gm.pbrMetallicRoughness.baseColorTexture.index,
                                          mptr + "/pbrMetallicRoughness/baseColorTexture/index", mat.wrapS, mat.wrapT);
      mat.occlusionTexture =
          textureImage(gm.occlusionTexture.index, mptr + "/occlusionTexture/index", mat.occlusionWrapS, mat.occlusionWrapT);
      if (mat.occlusionTexture >= 0) {
        const double strength = gm.occlusionTexture.strength;
        // glTF 2.0 §5.25 (material.occlusionTextureInfo.strength): a number in [0, 1].
        if (!(strength >= 0.0 && strength <= 1.0))
          fail(path_, mptr + "/occlusionTexture/strength", "expected a number in [0, 1], got " + std::to_string(strength));
        mat.occlusionStrength = float(strength);
      }
      out_.materials.push_back(mat);
      uv_.push_back(uvSource(path_, root_, "/materials/" + std::to_string(i) + "/pbrMetallicRoughness/baseColorTexture"));
      occlusionUv_.push_back(uvSource(path_, root_, "/materials/" + std::to_string(i) + "/occlusionTexture"));
    }
  }

  // The image of texture `ti` (-1: none) and its sampler's wrap modes; ptr names the index's field.
  int32_t textureImage(int ti, const std::string& ptr, Wrap& wrapS, Wrap& wrapT) const {
    if (ti < 0) return -1;
    if (size_t(ti) >= m_.textures.size()) fail(path_, ptr, std::to_string(ti) + " is not a texture index");
    const tinygltf::Texture& t = m_.textures[size_t(ti)];
    if (t.source < 0 || size_t(t.source) >= m_.images.size())
      fail(path_, "/textures/" + std::to_string(ti) + "/source", std::to_string(t.source) + " is not an image index");
    if (t.sampler >= 0) {
      if (size_t(t.sampler) >= m_.samplers.size())
        fail(path_, "/textures/" + std::to_string(ti) + "/sampler", std::to_string(t.sampler) + " is not a sampler index");
      wrapS = wrapOf(m_.samplers[size_t(t.sampler)].wrapS);
      wrapT = wrapOf(m_.samplers[size_t(t.sampler)].wrapT);
    }
    return t.source;
  }

  uint32_t defaultMaterial() {
    if (defaultMaterial_ < 0) {
      defaultMaterial_ = int(out_.materials.size());
      out_.materials.push_back(Material{.name = "default"});
      uv_.push_back(UvSource{});
      occlusionUv_.push_back(UvSource{});
    }
    return uint32_t(defaultMaterial_);
  }

  static bool isTriangles(int mode) {
    return mode == TINYGLTF_MODE_TRIANGLES || mode == TINYGLTF_MODE_TRIANGLE_STRIP ||
           mode == TINYGLTF_MODE_TRIANGLE_FAN;
  }

  // Checks every accessor that one instance of mesh `index` will read, and what it adds to the model
  // (NodeGraph::check). Reads no element.
  gltf::MeshCost meshCost(int index) {
    gltf::MeshCost cost;
    const tinygltf::Mesh& gm = m_.meshes[size_t(index)];
    for (size_t p = 0; p < gm.primitives.size(); ++p) {
      const tinygltf::Primitive& prim = gm.primitives[p];
      const std::string ptr = "/meshes/" + std::to_string(index) + "/primitives/" + std::to_string(p);
      const int mode = prim.mode < 0 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
      const auto pos = prim.attributes.find("POSITION");
      if (!isTriangles(mode) || pos == prim.attributes.end()) continue;  // skipped with a note
      const uint32_t material = materialOf(prim, ptr);
      const uint64_t nv = reader_.check(pos->second, 3, ptr + "/attributes/POSITION");
      // The texcoord set the material's texture reads must exist: without it the texture could not be
      // mapped, and the material would silently render as its factor alone.
      checkTexcoords(prim, ptr, material, uv_[material], out_.materials[material].baseColorTexture >= 0,
                     "base colour texture", nv);
      checkTexcoords(prim, ptr, material, occlusionUv_[material], out_.materials[material].occlusionTexture >= 0,
                     "occlusion texture", nv);
      const auto nrm = prim.attributes.find("NORMAL");
      if (nrm != prim.attributes.end() && reader_.count(nrm->second, ptr + "/attributes/NORMAL") == nv)
        reader_.check(nrm->second, 3, ptr + "/attributes/NORMAL");
      const uint64_t n = prim.indices >= 0 ? reader_.check(prim.indices, gltf::Reader::kIndices, ptr + "/indices") : nv;
      const uint64_t triangles = mode == TINYGLTF_MODE_TRIANGLES ? n / 3 : n >= 3 ? n - 2 : 0;
      cost.triangles = saturatingAdd(cost.triangles, triangles);
      cost.vertices = saturatingAdd(cost.vertices, nv);
    }
    return cost;
  }

  void checkTexcoords(const tinygltf::Primitive& prim, const std::string& ptr, uint32_t material, const UvSource& uv,
                      bool used, const char* what, uint64_t nv) {
    const std::string set = "TEXCOORD_" + std::to_string(uv.set);
    const auto tc = prim.attributes.find(set);
    if (tc == prim.attributes.end() && used)
      fail(path_, ptr + "/attributes",
           "material " + std::to_string(material) + "'s " + what + " reads texCoord " + std::to_string(uv.set) + " (" +
               set + "), which this primitive does not have");
    if (tc != prim.attributes.end() && reader_.check(tc->second, 2, ptr + "/attributes/" + set) != nv)
      fail(path_, ptr + "/attributes/" + set, "count differs from POSITION's");
  }

  // The texcoords of set uv.set after its KHR_texture_transform; empty when the primitive lacks the set.
  std::vector<glm::vec2> texcoords(const tinygltf::Primitive& prim, const std::string& ptr, const UvSource& uv, size_t nv) {
    std::vector<glm::vec2> out;
    const auto tc = prim.attributes.find("TEXCOORD_" + std::to_string(uv.set));
    if (tc == prim.attributes.end()) return out;
    const std::string tptr = ptr + "/attributes/TEXCOORD_" + std::to_string(uv.set);
    if (reader_.count(tc->second, tptr) != nv) fail(path_, tptr, "count differs from POSITION's");
    const std::vector<float> t = reader_.floats(tc->second, 2, tptr);
    out.resize(nv);
    // KHR_texture_transform: uv' = offset + R * (scale * uv) with u' = cos u + sin v, v' = -sin u + cos v: the
    // reading under which the extension's own example (offset [0, 1], rotation pi/2, scale 0.5) selects the
    // lower-left quadrant, as the reference viewers and the TextureTransformTest sample model do.
    const double c = uv.transform ? detCos(uv.rotation) : 1.0, s = uv.transform ? detSin(uv.rotation) : 0.0;
    for (size_t i = 0; i < nv; ++i) {
      if (!uv.transform) {
        out[i] = {t[i * 2], t[i * 2 + 1]};
        continue;
      }
      const double u = double(t[i * 2]) * uv.scale[0], v = double(t[i * 2 + 1]) * uv.scale[1];
      out[i] = {float(c * u + s * v + uv.offset[0]), float(-s * u + c * v + uv.offset[1])};
    }
    return out;
  }

  uint32_t materialOf(const tinygltf::Primitive& prim, const std::string& ptr) {
    if (prim.material < 0) return defaultMaterial();
    if (size_t(prim.material) >= m_.materials.size())
      fail(path_, ptr + "/material", std::to_string(prim.material) + " is not a material index");
    return uint32_t(prim.material);
  }

  void instance(int index, const glm::dmat4& world) {
    const tinygltf::Node& n = m_.nodes[size_t(index)];
    if (n.mesh < 0) return;
    const tinygltf::Mesh& gm = m_.meshes[size_t(n.mesh)];  // checked by NodeGraph::check
    objects_.begin(n.name.empty() ? "node" + std::to_string(index) : n.name, index);
    for (size_t p = 0; p < gm.primitives.size(); ++p)
      primitive(gm.primitives[p], "/meshes/" + std::to_string(n.mesh) + "/primitives/" + std::to_string(p),
                (gm.name.empty() ? "mesh" + std::to_string(n.mesh) : gm.name) + "/" + std::to_string(p), world);
  }

  void primitive(const tinygltf::Primitive& prim, const std::string& ptr, const std::string& name,
                 const glm::dmat4& world) {
    const int mode = prim.mode < 0 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
    if (!isTriangles(mode)) {
      ++skippedNonTriangles_;
      if (skippedNonTriangles_ == 1)
        out_.notes.push_back(ptr + ": points / lines primitives are not triangles; skipped");
      return;
    }
    const auto pos = prim.attributes.find("POSITION");
    if (pos == prim.attributes.end()) {
      out_.notes.push_back(ptr + ": no POSITION attribute; skipped");
      return;
    }
    Mesh mesh;
    mesh.name = name;
    mesh.material = materialOf(prim, ptr);
    const std::vector<float> p = reader_.floats(pos->second, 3, ptr + "/attributes/POSITION");
    const size_t nv = p.size() / 3;
    const bool identity = isIdentity(world);
    mesh.positions.resize(nv);
    for (size_t i = 0; i < nv; ++i) {
      const glm::vec3 v{p[i * 3], p[i * 3 + 1], p[i * 3 + 2]};
      mesh.positions[i] = identity ? v : transformPoint(world, v);
    }
    mesh.texcoords = texcoords(prim, ptr, uv_[mesh.material], nv);
    if (out_.materials[mesh.material].occlusionTexture >= 0)
      mesh.occlusionTexcoords = texcoords(prim, ptr, occlusionUv_[mesh.material], nv);
    const auto nrm = prim.attributes.find("NORMAL");
    if (nrm != prim.attributes.end() && reader_.count(nrm->second, ptr + "/attributes/NORMAL") == nv) {
      const std::vector<float> n = reader_.floats(nrm->second, 3, ptr + "/attributes/NORMAL");
      mesh.normals.resize(nv);
      for (size_t i = 0; i < nv; ++i) {
        const glm::vec3 v{n[i * 3], n[i * 3 + 1], n[i * 3 + 2]};
        mesh.normals[i] = identity ? v : transformNormal(world, v);
      }
    }
    std::vector<uint32_t> idx;
    if (prim.indices >= 0) {
      idx = reader_.indices(prim.indices, ptr + "/indices");
      for (uint32_t i : idx)
        if (i >= nv)
          fail(path_, ptr + "/indices", "index " + std::to_string(i) + " >= vertex count " + std::to_string(nv));
    } else {
      idx.resize(nv);
      for (size_t i = 0; i < nv; ++i) idx[i] = uint32_t(i);
    }
    const bool flip = det3(world) < 0.0;
    auto tri = [&](uint32_t a, uint32_t b, uint32_t c) {
      if (flip) std::swap(b, c);
      mesh.indices.insert(mesh.indices.end(), {a, b, c});
    };
    if (mode == TINYGLTF_MODE_TRIANGLES) {
      for (size_t i = 0; i + 2 < idx.size(); i += 3) tri(idx[i], idx[i + 1], idx[i + 2]);
    } else if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {  // glTF 2.0 §3.7.2.1: odd triangles swap
      for (size_t i = 0; i + 2 < idx.size(); ++i)
        i % 2 ? tri(idx[i + 1], idx[i], idx[i + 2]) : tri(idx[i], idx[i + 1], idx[i + 2]);
    } else {
      for (size_t i = 1; i + 1 < idx.size(); ++i) tri(idx[0], idx[i], idx[i + 1]);
    }
    objects_.add(std::move(mesh));
  }

  const std::string& path_;
  const tinygltf::Model& m_;
  const nlohmann::json& root_;
  const ResourceLimits& limits_;
  Model& out_;
  ObjectSink objects_{out_};  // one object per node instance (docs/model-import.md "Objects")
  Reader reader_;
  std::vector<UvSource> uv_, occlusionUv_;  // per material: the base colour and the occlusion texture
  int defaultMaterial_ = -1;
  size_t skippedNonTriangles_ = 0;
};

// Where the BIN chunk of a .glb starts in the file (0 for .gltf); validates the container.
struct Container {
  bool binary = false;
  std::string json;
  uint64_t binOffset = 0, binSize = 0;
};

Container parseContainer(const std::string& path, const std::vector<uint8_t>& bytes) {
  Container c;
  if (bytes.size() < 4 || std::memcmp(bytes.data(), "glTF", 4) != 0) {
    c.json.assign(bytes.begin(), bytes.end());
    return c;
  }
  c.binary = true;
  if (bytes.size() < 20)
    throw Error(path + ": truncated .glb: " + std::to_string(bytes.size()) + " bytes, the header needs 20");
  const uint32_t length = le32(&bytes[8]), jsonLen = le32(&bytes[12]);
  if (length > bytes.size())
    throw Error(path + ": truncated .glb: the header says " + std::to_string(length) + " bytes, the file has " +
                std::to_string(bytes.size()));
  if (le32(&bytes[16]) != 0x4E4F534Au) throw Error(path + ": .glb: the first chunk is not JSON");
  if (uint64_t(jsonLen) + 20 > length) throw Error(path + ": truncated .glb: the JSON chunk runs past the end");
  c.json.assign(bytes.begin() + 20, bytes.begin() + 20 + jsonLen);
  const uint64_t next = 20 + uint64_t(jsonLen);
  if (next + 8 <= length && le32(&bytes[next + 4]) == 0x004E4942u) {
    c.binOffset = next + 8;
    c.binSize = le32(&bytes[next]);
    if (c.binOffset + c.binSize > length) throw Error(path + ": truncated .glb: the BIN chunk runs past the end");
  }
  return c;
}

}  // namespace

Model loadGltf(const std::string& path, const ResourceLimits& limits) {
  const std::vector<uint8_t> bytes = readWholeFile(path);
  if (bytes.size() >= 8 && std::memcmp(bytes.data(), "glTF", 4) == 0 && le32(&bytes[4]) == 1)
    return loadAssimp(path, limits);
  if (bytes.size() >= 8 && std::memcmp(bytes.data(), "glTF", 4) == 0 && le32(&bytes[4]) != 2)
    throw Error(path + ": .glb version " + std::to_string(le32(&bytes[4])) + " is not 2");
  if (bytes.size() >= 0xffffffffull) throw Error(path + ": files of 4 GiB or more are not supported by tinygltf");
  const Container c = parseContainer(path, bytes);
  nlohmann::json root;
  try {
    root = nlohmann::json::parse(c.json);
  } catch (const nlohmann::json::exception& e) {
    throw Error(path + ": not valid JSON: " + e.what());
  }
  if (!root.is_object()) fail(path, "/", "the glTF root must be a JSON object");
  // glTF 1.0 goes to Assimp, which reads it; one without a string version is handed over with "1.0" put
  // in, since Assimp refuses it otherwise (gltf_version.h).
  switch (gltf::generationOf(root)) {
    case gltf::Generation::One:
      return loadAssimp(path, limits);
    case gltf::Generation::OneWithoutStringVersion: {
      Model m = loadAssimp(path, limits, gltf::gltf1WithStringVersion(root));
      m.notes.push_back("glTF 1.0 without a string asset.version: read as version \"1.0\"");
      return m;
    }
    case gltf::Generation::Two:
      break;
  }
  const nlohmann::json::json_pointer vp("/asset/version");
  if (!root.contains(vp)) fail(path, "/asset/version", "missing (required by glTF 2.0)");
  if (!root.at(vp).is_string())
    fail(path, "/asset/version",
         "expected a string such as \"2.0\", not " + root.at(vp).dump().substr(0, 40) +
             " (a number is read as glTF 1.0 only in [1, 2))");
  if (!root.at(vp).get<std::string>().starts_with("2"))
    fail(path, "/asset/version", "'" + root.at(vp).get<std::string>() + "' is not 2.x");
  gltf::checkDocument(path, root, limits);  // before tinygltf, which would accept or crash on what it refuses
  if (root.contains("extensionsRequired") && root["extensionsRequired"].is_array())
    for (const auto& e : root["extensionsRequired"])
      if (e.is_string() && e != "KHR_texture_transform" && e != "KHR_mesh_quantization" && e != "KHR_materials_unlit")
        fail(path, "/extensionsRequired", "extension " + e.get<std::string>() + " is required but not supported");

  LoadContext ctx;
  const std::string base = fs::path(path).parent_path().string();
  if (root.contains("buffers") && root["buffers"].is_array())
    for (const auto& b : root["buffers"])
      if (b.is_object() && b.contains("uri") && b["uri"].is_string() &&
          !b["uri"].get<std::string>().starts_with("data:"))
        ctx.bufferFiles.insert(canonical(resolveBeside(path, uriDecode(b["uri"].get<std::string>()))));

  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(&stashImage, &ctx);
  loader.SetFsCallbacks(tinygltf::FsCallbacks{&fileExists, &expandPath, &readBufferFile, &refuseWrite, &ctx});
  tinygltf::Model gm;
  std::string err, warn;
  const bool ok = c.binary ? loader.LoadBinaryFromMemory(&gm, &err, &warn, bytes.data(), unsigned(bytes.size()), base)
                           : loader.LoadASCIIFromString(&gm, &err, &warn, c.json.data(), unsigned(c.json.size()), base);
  if (!ok) {
    while (!err.empty() && (err.back() == '\n' || err.back() == ' ')) err.pop_back();
    for (char& ch : err)
      if (ch == '\n') ch = ';';
    throw Error(path + ": " + (err.empty() ? "tinygltf could not parse the file" : err));
  }

  Model out;
  out.loader = "gltf";
  // Images: where their bytes are.
  for (size_t i = 0; i < gm.images.size(); ++i) {
    const tinygltf::Image& im = gm.images[i];
    TextureRef t;
    t.name = im.name;
    t.mimeType = im.mimeType;
    const std::string ptr = "/images/" + std::to_string(i);
    if (im.bufferView >= 0) {
      const auto& bv = gm.bufferViews[size_t(im.bufferView)];  // range-checked by tinygltf
      const auto& buf = gm.buffers[size_t(bv.buffer)];
      if (bv.byteOffset > buf.data.size() || bv.byteLength > buf.data.size() - bv.byteOffset)
        fail(path, "/bufferViews/" + std::to_string(im.bufferView), "lies outside its buffer");
      const nlohmann::json::json_pointer up("/buffers/" + std::to_string(bv.buffer) + "/uri");
      const std::string bufUri = root.contains(up) && root.at(up).is_string() ? root.at(up).get<std::string>() : "";
      if (bufUri.empty() && c.binary && bv.buffer == 0) {
        t.source = TextureRef::Source::FileRange;
        t.path = path;
        t.offset = c.binOffset + bv.byteOffset;
      } else if (!bufUri.empty() && !bufUri.starts_with("data:")) {
        t.source = TextureRef::Source::FileRange;
        t.path = resolveBeside(path, uriDecode(bufUri));
        t.offset = bv.byteOffset;
      } else {
        t.source = TextureRef::Source::Memory;
        t.bytes = std::make_shared<const std::vector<uint8_t>>(
            buf.data.begin() + ptrdiff_t(bv.byteOffset), buf.data.begin() + ptrdiff_t(bv.byteOffset + bv.byteLength));
      }
      t.size = bv.byteLength;
      if (t.name.empty()) t.name = "image" + std::to_string(i);
    } else if (auto it = ctx.dataUriImages.find(int(i)); it != ctx.dataUriImages.end()) {
      t.source = TextureRef::Source::Memory;
      t.bytes = it->second;
      t.size = it->second->size();
      if (t.name.empty()) t.name = "image" + std::to_string(i);
    } else if (!im.uri.empty()) {
      t.source = TextureRef::Source::File;
      t.uri = im.uri;
      t.path = resolveBeside(path, uriDecode(im.uri));
      requireTextureFile(path, ptr + "/uri", im.uri, t.path);
      if (t.name.empty()) t.name = fs::path(t.path).filename().string();
    } else {
      fail(path, ptr, "has neither a usable uri nor a bufferView");
    }
    out.textures.push_back(std::move(t));
  }
  Builder(path, gm, root, limits, out).run();
  return out;
}

}  // namespace tessera::model::detail
