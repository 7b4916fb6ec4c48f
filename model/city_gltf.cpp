// Writing a generated city as glTF 2.0: DIR/<name>.gltf (JSON), DIR/<name>.bin (positions, then
// texcoords, then uint32 indices, one bufferView each) and DIR/textures/tNNNNN.png|jpg.
// Textures are rendered and encoded in parallel (TBB), each into its own file, so the bytes do not
// depend on the schedule. Every file is written atomically (base/atomic_file.h); the .gltf comes
// last, so its presence means the rest is complete.
#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <atomic>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <glm/common.hpp>
#include <mutex>

#include "base/atomic_file.h"
#include "base/det_math.h"
#include "model/city_scene.h"
#include "raster/command_list.h"
#include "raster/image_io.h"

namespace tessera::model::city {

namespace {

namespace fs = std::filesystem;

void writeBytes(const std::string& path, const void* data, size_t size) {
  writeFileAtomically(path, std::span<const uint8_t>(static_cast<const uint8_t*>(data), size));
}

void writeImageFile(const std::string& path, const TexSpec& t, const std::vector<uint8_t>& px, bool jpg) {
  Image8Options o;
  if (jpg)
    o.jpegQuality = 90;
  else
    o.pngCompressionLevel = 1;
  writeImage8(path, int(t.width), int(t.height), t.rgba() ? 4 : 3, px.data(), o);
}

uint64_t fileSize(const std::string& path) {
  std::error_code ec;
  const auto n = fs::file_size(path, ec);
  return ec ? 0 : uint64_t(n);
}

template <class T>
void append(std::vector<uint8_t>& bin, const std::vector<T>& v) {
  const size_t at = bin.size();
  bin.resize(at + v.size() * sizeof(T));
  if (!v.empty()) std::memcpy(bin.data() + at, v.data(), v.size() * sizeof(T));
}

}  // namespace

void writeScene(const Scene& scene, const CityOptions& o, CitySummary& s) {
  const std::string dir = o.outDir;
  std::error_code ec;
  fs::create_directories(dir + "/textures", ec);
  if (ec) throw Error(dir + "/textures: cannot create the output directory: " + ec.message());

  // Textures.
  const bool jpg = o.format == CityImageFormat::Jpg;
  const size_t nt = scene.textures.size();
  std::vector<std::string> names(nt);
  std::vector<uint64_t> sizes(nt);
  const int digits = std::max<int>(5, int(std::to_string(nt).size()));
  for (size_t i = 0; i < nt; ++i)
    names[i] = fmt::format("textures/t{:0{}}.{}", i, digits, jpg && !scene.textures[i].rgba() ? "jpg" : "png");
  std::atomic<size_t> done{0};
  std::mutex printMutex;
  const bool progress = o.progress && nt >= 200;
  tbb::parallel_for(size_t(0), nt, [&](size_t i) {
    const TexSpec& t = scene.textures[i];
    const std::string path = dir + "/" + names[i];
    writeImageFile(path, t, renderTexture(t), names[i].ends_with(".jpg"));
    sizes[i] = fileSize(path);
    const size_t d = ++done;
    if (progress && (d % std::max<size_t>(nt / 20, 1) == 0 || d == nt)) {
      std::lock_guard<std::mutex> lock(printMutex);
      std::fprintf(stderr, "city: %s textures %zu/%zu\n", scene.name.c_str(), d, nt);
    }
  });
  for (size_t i = 0; i < nt; ++i) {
    const TexSpec& t = scene.textures[i];
    s.texelCount += uint64_t(t.width) * t.height;
    s.textureBytesRaw += uint64_t(t.width) * t.height * (t.rgba() ? 4 : 3);
    s.rgbaTextures += t.rgba();
    s.bytesOnDisk += sizes[i];
    s.files.push_back(names[i]);
  }
  s.textures = nt;

  // Geometry: three bufferViews (positions, texcoords, indices) in one .bin.
  std::vector<uint8_t> pos, uv, idx;
  nlohmann::json accessors = nlohmann::json::array(), meshes = nlohmann::json::array(), nodes = nlohmann::json::array();
  for (const Node& n : scene.nodes) {
    nlohmann::json jn = {{"name", n.name}};
    if (n.translation != std::array<double, 3>{0, 0, 0}) jn["translation"] = n.translation;
    if (n.yaw != 0.0)  // about +Y: (0, sin(yaw/2), 0, cos(yaw/2)), stored as float like every glTF number
      jn["rotation"] = {0.0, double(float(detSin(n.yaw / 2))), 0.0, double(float(detCos(n.yaw / 2)))};
    if (!n.children.empty()) jn["children"] = n.children;
    if (!n.primitives.empty()) {
      nlohmann::json prims = nlohmann::json::array();
      for (const Primitive& p : n.primitives) {
        glm::vec3 lo = p.positions.front(), hi = p.positions.front();
        for (const glm::vec3& v : p.positions)
          lo = glm::min(lo, v), hi = glm::max(hi, v);  // per component, as std::min / std::max
        const size_t a = accessors.size();
        accessors.push_back({{"bufferView", 0},
                             {"byteOffset", pos.size()},
                             {"componentType", 5126},
                             {"count", p.positions.size()},
                             {"type", "VEC3"},
                             {"min", {lo.x, lo.y, lo.z}},
                             {"max", {hi.x, hi.y, hi.z}}});
        const bool textured = !p.texcoords.empty();
        if (textured != (p.material < nt) || (textured && p.texcoords.size() != p.positions.size()))
          throw Error(n.name + ": texcoords do not match material " + std::to_string(p.material) +
                      " (internal error in the city generator)");
        nlohmann::json attributes = {{"POSITION", a}};
        if (textured) {
          attributes["TEXCOORD_0"] = accessors.size();
          accessors.push_back({{"bufferView", 1},
                               {"byteOffset", uv.size()},
                               {"componentType", 5126},
                               {"count", p.texcoords.size()},
                               {"type", "VEC2"}});
        }
        const size_t ia = accessors.size();
        accessors.push_back({{"bufferView", 2},
                             {"byteOffset", idx.size()},
                             {"componentType", 5125},
                             {"count", p.indices.size()},
                             {"type", "SCALAR"}});
        append(pos, p.positions), append(uv, p.texcoords), append(idx, p.indices);
        prims.push_back({{"attributes", attributes}, {"indices", ia}, {"material", p.material}, {"mode", 4}});
        s.triangles += p.indices.size() / 3;
        s.vertices += p.positions.size();
        ++s.primitives;
      }
      jn["mesh"] = meshes.size();
      meshes.push_back({{"name", n.name}, {"primitives", prims}});
    }
    nodes.push_back(jn);
  }
  nlohmann::json materials = nlohmann::json::array(), textures = nlohmann::json::array(),
                 images = nlohmann::json::array();
  for (size_t i = 0; i < nt; ++i) {
    const TexSpec& t = scene.textures[i];
    nlohmann::json m = {{"name", fmt::format("m{}", i)},
                        {"pbrMetallicRoughness",
                         {{"baseColorTexture", {{"index", i}}}, {"metallicFactor", 0.0}, {"roughnessFactor", 1.0}}}};
    if (t.kind == TexKind::Fence || t.kind == TexKind::Tree)
      m["alphaMode"] = "MASK", m["alphaCutoff"] = 0.5, m["doubleSided"] = true;
    if (t.kind == TexKind::Glass) m["alphaMode"] = "BLEND", m["doubleSided"] = true;
    materials.push_back(m);
    textures.push_back({{"source", i}, {"sampler", 0}});
    images.push_back({{"uri", names[i]}});
  }
  for (const ColourMaterial& c : scene.colours)  // untextured: a base colour factor only
    materials.push_back({{"name", c.name},
                         {"pbrMetallicRoughness",
                          {{"baseColorFactor", {c.rgb[0], c.rgb[1], c.rgb[2], 1.0}},
                           {"metallicFactor", 0.0},
                           {"roughnessFactor", 1.0}}}});
  const std::string binName = scene.name + ".bin";
  const size_t binSize = pos.size() + uv.size() + idx.size();
  nlohmann::json root = {
      {"asset",
       {{"version", "2.0"},
        {"generator", fmt::format("tessera city --preset {} --buildings {} --seed {} --texture-size {} --format {}",
                                  scene.name, scene.buildings, o.seed, o.textureSize, jpg ? "jpg" : "png")}}},
      {"scene", 0},
      {"scenes", {{{"name", scene.name}, {"nodes", scene.roots}}}},
      {"nodes", nodes},
      {"meshes", meshes},
      {"accessors", accessors},
      {"bufferViews",
       {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", pos.size()}, {"byteStride", 12}, {"target", 34962}},
        {{"buffer", 0}, {"byteOffset", pos.size()}, {"byteLength", uv.size()}, {"byteStride", 8}, {"target", 34962}},
        {{"buffer", 0}, {"byteOffset", pos.size() + uv.size()}, {"byteLength", idx.size()}, {"target", 34963}}}},
      {"buffers", {{{"uri", binName}, {"byteLength", binSize}}}},
      {"materials", materials},
      {"textures", textures},
      {"images", images},
      {"samplers", {{{"magFilter", 9729}, {"minFilter", 9987}, {"wrapS", 10497}, {"wrapT", 10497}}}}};
  std::vector<uint8_t> bin;
  bin.reserve(binSize);
  bin.insert(bin.end(), pos.begin(), pos.end());
  bin.insert(bin.end(), uv.begin(), uv.end());
  bin.insert(bin.end(), idx.begin(), idx.end());
  writeBytes(dir + "/" + binName, bin.data(), bin.size());
  const std::string json = root.dump() + "\n";
  const std::string gltf = dir + "/" + scene.name + ".gltf";
  writeBytes(gltf, json.data(), json.size());
  s.files.push_back(binName);
  s.files.push_back(scene.name + ".gltf");
  s.bytesOnDisk += bin.size() + json.size();
  s.gltf = gltf;
}

}  // namespace tessera::model::city
