// Wavefront OBJ + MTL through tinyobjloader (Debian's libtinyobjloader, float build).
//
// One Mesh per (OBJ shape, material). Corners are de-duplicated by their (position, texcoord,
// normal) index triple. map_Kd is the base colour texture, resolved relative to the OBJ (the MTL
// search path is the OBJ's directory); its -o / -s options are applied to the texcoords (the OBJ
// analogue of KHR_texture_transform) before v is flipped to the glTF convention (v' = 1 - v).
// Kd is the base colour factor, d < 1 (or Tr > 0) makes the material Blend, -clamp on makes it clamp.
// The file is read once; obj_scan.h checks its indices and mtllib statements and counts its triangles
// (against the budget) before tinyobjloader parses the same text.
#include <tiny_obj_loader.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <tuple>

#include "model/loaders.h"
#include "model/obj_scan.h"
#include "raster/command_list.h"

namespace tessera::model::detail {

namespace {

// Hands tinyobjloader the material libraries obj_scan.h already read: all of them, in the order the
// file names them, the first time it asks. (tinyobjloader itself would read only the first file an
// `mtllib` statement names that it can open; OBJ means all of them.)
class Libraries : public tinyobj::MaterialReader {
 public:
  explicit Libraries(const std::vector<MaterialLibrary>& libraries) : libraries_(libraries) {}
  bool operator()(const std::string&, std::vector<tinyobj::material_t>* materials, std::map<std::string, int>* byName,
                  std::string* warn, std::string* err) override {
    if (read_) return true;
    read_ = true;
    for (const MaterialLibrary& l : libraries_) {
      std::istringstream in(l.text);
      tinyobj::LoadMtl(byName, materials, &in, warn, err);
    }
    return true;
  }

 private:
  const std::vector<MaterialLibrary>& libraries_;
  bool read_ = false;
};

}  // namespace

Model loadObj(const std::string& path, const ResourceLimits& limits) {
  std::string text;
  {
    std::ifstream f(path, std::ios::binary);
    if (!f) throw Error(path + ": cannot open for reading");
    text.assign(std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>());
  }
  // Indices, mtllib statements and the triangle count are checked before tinyobjloader sees the text.
  const ObjScan scan = scanObj(path, text);
  requireWithinBudget(path, ModelBudget::Triangles, scan.triangles, limits);
  tinyobj::attrib_t attrib;
  std::vector<tinyobj::shape_t> shapes;
  std::vector<tinyobj::material_t> mats;
  std::string warning, error;
  std::istringstream in(text);
  Libraries libraries(scan.libraries);
  if (!tinyobj::LoadObj(&attrib, &shapes, &mats, &warning, &error, &in, &libraries, /*triangulate=*/true,
                        /*default_vcols_fallback=*/false)) {
    while (!error.empty() && error.back() == '\n') error.pop_back();
    throw Error(path + ": " + (error.empty() ? "not a readable OBJ file" : error));
  }

  Model out;
  out.loader = "obj";
  if (!warning.empty()) {
    std::string w = warning;
    while (!w.empty() && w.back() == '\n') w.pop_back();
    out.notes.push_back("tinyobjloader: " + w);
  }
  std::map<std::string, int32_t> textureByPath;
  struct UvOpt {
    float offset[2] = {0, 0}, scale[2] = {1, 1};
  };
  std::vector<UvOpt> uvOpt;
  for (size_t i = 0; i < mats.size(); ++i) {
    const tinyobj::material_t& tm = mats[i];
    Material m;
    m.name = tm.name;
    m.baseColorFactor = {tm.diffuse[0], tm.diffuse[1], tm.diffuse[2], tm.dissolve};
    m.alphaMode = tm.dissolve < 1.0f ? AlphaMode::Blend : AlphaMode::Opaque;
    UvOpt o;
    if (!tm.diffuse_texname.empty()) {
      const std::string resolved = resolveBeside(path, tm.diffuse_texname);
      requireTextureFile(path, "material '" + tm.name + "' map_Kd", tm.diffuse_texname, resolved);
      auto [it, fresh] = textureByPath.try_emplace(resolved, int32_t(out.textures.size()));
      if (fresh) {
        TextureRef t;
        t.source = TextureRef::Source::File;
        t.uri = tm.diffuse_texname;
        t.path = resolved;
        t.name = std::filesystem::path(resolved).filename().string();
        out.textures.push_back(std::move(t));
      }
      m.baseColorTexture = it->second;
      const tinyobj::texture_option_t& opt = tm.diffuse_texopt;
      o.offset[0] = opt.origin_offset[0], o.offset[1] = opt.origin_offset[1];
      o.scale[0] = opt.scale[0], o.scale[1] = opt.scale[1];
      if (opt.clamp) m.wrapS = m.wrapT = Wrap::ClampToEdge;
    }
    if (!tm.alpha_texname.empty())
      out.notes.push_back("material '" + tm.name + "': map_d (alpha texture) is not combined with map_Kd; ignored");
    out.materials.push_back(m);
    uvOpt.push_back(o);
  }
  int32_t defaultMaterial = -1;

  ObjectSink objects(out);  // one object per tinyobjloader shape (`o` / `g`), docs/model-import.md "Objects"
  const size_t nPos = attrib.vertices.size() / 3, nUv = attrib.texcoords.size() / 2, nN = attrib.normals.size() / 3;
  for (size_t s = 0; s < shapes.size(); ++s) {
    const tinyobj::mesh_t& sm = shapes[s].mesh;
    objects.begin(shapes[s].name.empty() ? "shape" + std::to_string(s) : shapes[s].name, int32_t(s));
    // Faces grouped by material, in first-use order.
    std::map<int, Mesh> byMaterial;
    std::vector<int> order;
    std::map<int, std::map<std::tuple<int, int, int>, uint32_t>> corner;
    size_t first = 0;
    for (size_t f = 0; f < sm.num_face_vertices.size(); ++f) {
      const size_t n = sm.num_face_vertices[f];
      if (first + n > sm.indices.size())
        throw Error(path + ": shape '" + shapes[s].name + "': face " + std::to_string(f) + " runs past the index list");
      int mat = f < sm.material_ids.size() ? sm.material_ids[f] : -1;
      if (mat < 0 || size_t(mat) >= out.materials.size()) {
        if (defaultMaterial < 0) {
          defaultMaterial = int32_t(out.materials.size());
          out.materials.push_back(Material{.name = "default"});
          uvOpt.push_back(UvOpt{});
        }
        mat = defaultMaterial;
      }
      if (!byMaterial.count(mat)) order.push_back(mat);
      Mesh& mesh = byMaterial[mat];
      if (n != 3) {  // triangulate = true leaves only triangles; anything else is a point or a line
        first += n;
        continue;
      }
      const UvOpt& o = uvOpt[size_t(mat)];
      for (size_t k = 0; k < 3; ++k) {
        const tinyobj::index_t ix = sm.indices[first + k];
        if (ix.vertex_index < 0 || size_t(ix.vertex_index) >= nPos)
          throw Error(path + ": shape '" + shapes[s].name + "' face " + std::to_string(f) + ": vertex index " +
                      std::to_string(ix.vertex_index + 1) + " does not exist (" + std::to_string(nPos) + " vertices)");
        const int t = ix.texcoord_index >= 0 && size_t(ix.texcoord_index) < nUv ? ix.texcoord_index : -1;
        const int nn = ix.normal_index >= 0 && size_t(ix.normal_index) < nN ? ix.normal_index : -1;
        auto [it, fresh] = corner[mat].try_emplace({ix.vertex_index, t, nn}, uint32_t(mesh.positions.size()));
        if (fresh) {
          const float* p = &attrib.vertices[size_t(ix.vertex_index) * 3];
          mesh.positions.push_back({p[0], p[1], p[2]});
          float u = 0.0f, v = 0.0f;
          if (t >= 0) {
            u = attrib.texcoords[size_t(t) * 2], v = attrib.texcoords[size_t(t) * 2 + 1];
            if (o.scale[0] != 1.0f || o.scale[1] != 1.0f || o.offset[0] != 0.0f || o.offset[1] != 0.0f)
              u = float(double(u) * o.scale[0] + o.offset[0]), v = float(double(v) * o.scale[1] + o.offset[1]);
          }
          mesh.texcoords.push_back({u, 1.0f - v});
          if (nn >= 0) {
            const float* q = &attrib.normals[size_t(nn) * 3];
            mesh.normals.push_back({q[0], q[1], q[2]});
          } else {
            mesh.normals.push_back({0.0f, 0.0f, 0.0f});
          }
        }
        mesh.indices.push_back(it->second);
      }
      first += n;
    }
    for (int mat : order) {
      Mesh& mesh = byMaterial[mat];
      if (mesh.indices.empty()) continue;
      mesh.material = uint32_t(mat);
      mesh.name = shapes[s].name;
      if (nN == 0) mesh.normals.clear();
      if (nUv == 0) mesh.texcoords.clear();
      objects.add(std::move(mesh));
    }
  }
  return out;
}

}  // namespace tessera::model::detail
