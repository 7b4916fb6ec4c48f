// AC3D (.ac: AC3Db, AC3Dc) and its TORCS / Speed Dreams variant (.acc), read without Assimp, whose AC3D
// importer aborts, overflows its stack or attempts huge allocations on hostile files.
//
// ac3d::parse() (model/ac3d_file.h) reads and checks the text. Here the material indices and the
// model's instance and triangle totals are checked against the file and ResourceLimits, and only then
// are meshes made: one per (object, material, two-sidedness), in object order and then material order,
// as Assimp made them. Positions are the object's vertices under the composed rot / loc of the object
// and its ancestors (double, loaders.h); polygons are triangulated by polygon_triangulation.h, strips
// become triangles, lines are dropped with a note. Texcoords get texrep / texoff (u' = u * rep + off)
// and the v flip of the project's convention (v' = 1 - v). What is read, what is dropped and where the
// result differs from Assimp's is listed in docs/model-import.md.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <tuple>

#include "base/error.h"
#include "base/resource_limits.h"
#include "model/ac3d_file.h"
#include "model/loaders.h"
#include "model/polygon_triangulation.h"

namespace tessera::model::detail {

namespace {

// The options of the commands that raise the model budgets (docs/limits.md).
constexpr std::string_view kInstancesOption = "--model-budget-instances";
constexpr std::string_view kTrianglesOption = "--model-budget-triangles";
// Ear-clipping steps per file (polygon_triangulation.h), under a second of work. Real polygons need a
// tiny fraction of it (a concave 1000-gon with 300 reflex corners takes about 10^6); a hostile comb of
// 400,000 corners uses it up and has the rest of it fanned.
constexpr uint64_t kTriangulationWork = uint64_t(1) << 26;

class Builder {
 public:
  Builder(const std::string& path, ac3d::File& p, const ResourceLimits& limits, Model& out)
      : path_(path), p_(p), limits_(limits), tally_(p.tally), out_(out) {}

  void run() {
    if (p_.materials.empty()) {  // Assimp's fallback: one grey material without a name
      p_.materials.emplace_back();
      tally_.defaultMaterial = true;
    }
    uint64_t instances = 0;
    std::optional<uint64_t> triangles = 0;
    for (const ac3d::Object& o : p_.objects) {
      for (const ac3d::Surface& s : o.surfaces)
        if (s.mat >= p_.materials.size())
          throw Error(path_ + ":" + std::to_string(s.matLine) + ": mat " + std::to_string(s.mat) +
                      " names a missing material: the file defines " + std::to_string(p_.materials.size()) + " (0 to " +
                      std::to_string(p_.materials.size() - 1) + ")");
      if (o.triangles > 0) ++instances;
      if (triangles) triangles = checkedAdd(*triangles, o.triangles);
      if (!o.vertices.empty() && o.refs.empty()) ++tally_.pointLists;
    }
    if (instances > limits_.modelInstances)
      throw Error(
          overLimitMessage(path_, "mesh instances", instances, limits_.modelInstances, kInstancesOption, false));
    if (!triangles || *triangles > limits_.modelTriangles)
      throw Error(overLimitMessage(path_, "triangles", triangles, limits_.modelTriangles, kTrianglesOption, false));

    std::vector<glm::dmat4> world(p_.objects.size());
    for (size_t i = 0; i < p_.objects.size(); ++i) {
      const ac3d::Object& o = p_.objects[i];
      glm::dmat4 local(glm::dmat3(o.rot));
      local[3] = glm::dvec4(glm::dvec3(o.loc), 1.0);
      world[i] = o.parent < 0 ? local : compose(world[size_t(o.parent)], local);
      if (o.triangles == 0) continue;
      objects_.begin(o.name.empty() ? "object" + std::to_string(i) : o.name, int32_t(i));
      object(o, world[i]);
    }
  }

 private:
  void object(const ac3d::Object& o, const glm::dmat4& world) {
    const int32_t texture = o.texture.empty() ? -1 : textureIndex(o);
    // Every vertex goes through the transform, even an identity one: Assimp added loc to every vertex,
    // which turns a -0 coordinate into +0, and so does the transform's final + m3.
    std::vector<glm::vec3> positions(o.vertices.size()), normals(o.normals.size());
    for (size_t i = 0; i < o.vertices.size(); ++i) {
      positions[i] = transformPoint(world, o.vertices[i]);
      if (!std::isfinite(positions[i].x) || !std::isfinite(positions[i].y) || !std::isfinite(positions[i].z))
        throw Error(path_ + ": vertex " + std::to_string(i) + " of " + o.label() +
                    " is outside the float range once its transforms are applied");
    }
    const bool identity = isIdentity(world), flip = det3(world) < 0.0;
    for (size_t i = 0; i < o.normals.size(); ++i)
      normals[i] = identity ? o.normals[i] : transformNormal(world, o.normals[i]);
    const glm::vec2 rep = o.texRep.x == 0.0f || o.texRep.y == 0.0f ? glm::vec2(1.0f) : o.texRep;  // as Assimp
    const bool uvTransform = rep != glm::vec2(1.0f) || o.texOff != glm::vec2(0.0f);

    std::map<std::pair<uint64_t, bool>, Mesh> meshes;  // by (material, two-sided): Assimp's order
    std::vector<glm::vec3> corners;
    std::vector<uint32_t> local;
    for (const ac3d::Surface& s : o.surfaces) {
      if (s.isLine()) {
        ++tally_.lines;
        continue;
      }
      if (s.refCount < 3) {
        ++tally_.smallPolygons;
        continue;
      }
      if (s.type() != 0 && s.type() != 4) ++tally_.unknownTypes;  // read as a polygon, as Assimp did
      auto [it, fresh] = meshes.try_emplace({s.mat, s.twoSided()});
      Mesh& mesh = it->second;
      if (fresh) {
        mesh.name = o.name;
        mesh.material = materialIndex(s.mat, texture, s.twoSided());
      }
      const size_t base = mesh.positions.size();
      if (base + s.refCount > UINT32_MAX) throw Error(path_ + ": " + o.label() + " has more than 2^32 - 1 corners");
      const ac3d::Ref* refs = &o.refs[s.firstRef];
      for (size_t k = 0; k < s.refCount; ++k) {
        mesh.positions.push_back(positions[refs[k].vertex]);
        if (!normals.empty()) mesh.normals.push_back(normals[refs[k].vertex]);
        if (texture < 0) continue;
        float u = refs[k].u, v = refs[k].v;
        if (uvTransform) u = float(double(u) * rep.x + o.texOff.x), v = float(double(v) * rep.y + o.texOff.y);
        if (!std::isfinite(u) || !std::isfinite(v))
          throw Error(path_ + ":" + std::to_string(s.line) + ": a texcoord of this SURF leaves the float range under " +
                      "texrep / texoff");
        mesh.texcoords.push_back({u, 1.0f - v});
      }
      auto triangle = [&](size_t a, size_t b, size_t c) {
        if (flip) std::swap(b, c);
        mesh.indices.insert(mesh.indices.end(), {uint32_t(base + a), uint32_t(base + b), uint32_t(base + c)});
      };
      if (s.type() == 4) {
        // A strip: triangle i is (i, i+1, i+2), the odd ones with their first two swapped; like Assimp,
        // triangles with two corners at one position (the joints between strips) are skipped.
        for (size_t i = 0; i + 2 < s.refCount; ++i) {
          const glm::vec3 &a = o.vertices[refs[i].vertex], &b = o.vertices[refs[i + 1].vertex],
                          &c = o.vertices[refs[i + 2].vertex];
          if (a == b || a == c || b == c) {
            ++tally_.degenerateStrip;
            continue;
          }
          if (i % 2 == 0)
            triangle(i, i + 1, i + 2);
          else
            triangle(i + 1, i, i + 2);
        }
      } else {
        corners.clear();
        for (size_t k = 0; k < s.refCount; ++k) corners.push_back(o.vertices[refs[k].vertex]);
        local.clear();
        if (!triangulatePolygon(corners, local, work_)) ++tally_.notSimple;
        for (size_t k = 0; k < local.size(); k += 3) triangle(local[k], local[k + 1], local[k + 2]);
      }
    }
    for (auto& [key, mesh] : meshes)
      if (!mesh.indices.empty()) objects_.add(std::move(mesh));
  }

  int32_t textureIndex(const ac3d::Object& o) {
    if (auto it = textures_.find(o.texture); it != textures_.end()) return it->second;
    TextureRef t;
    t.source = TextureRef::Source::File;
    t.uri = o.texture;
    t.path = resolveBeside(path_, o.texture);
    requireTextureFile(path_ + ":" + std::to_string(o.textureLine), "texture of object '" + ac3d::shown(o.name) + "'",
                       o.texture, t.path);
    t.name = std::filesystem::path(t.path).filename().string();
    const int32_t index = int32_t(out_.textures.size());
    out_.textures.push_back(std::move(t));
    textures_.emplace(o.texture, index);
    return index;
  }

  uint32_t materialIndex(uint64_t mat, int32_t texture, bool twoSided) {
    const auto key = std::make_tuple(mat, texture, twoSided);
    if (auto it = materials_.find(key); it != materials_.end()) return it->second;
    const ac3d::Material& ac = p_.materials[size_t(mat)];
    Material m;
    m.name = ac.name;
    m.baseColorTexture = texture;
    m.baseColorFactor = {ac.rgb.r, ac.rgb.g, ac.rgb.b, 1.0f};
    const float opacity = 1.0f - ac.trans;
    if (opacity < 1.0f) m.baseColorFactor[3] = opacity, m.alphaMode = AlphaMode::Blend;
    m.doubleSided = twoSided;
    const uint32_t index = uint32_t(out_.materials.size());
    out_.materials.push_back(std::move(m));
    materials_.emplace(key, index);
    return index;
  }

  const std::string& path_;
  ac3d::File& p_;
  const ResourceLimits& limits_;
  ac3d::Tally& tally_;
  Model& out_;
  ObjectSink objects_{out_};  // one object per AC3D object with triangles (docs/model-import.md "Objects")
  uint64_t work_ = kTriangulationWork;
  std::map<std::string, int32_t> textures_;
  std::map<std::tuple<uint64_t, int32_t, bool>, uint32_t> materials_;
};

void writeNotes(const ac3d::Tally& t, Model& out) {
  auto add = [&](size_t n, const std::string& what) {
    if (n > 0) out.notes.push_back(std::to_string(n) + " " + what);
  };
  if (t.newerVersion >= 0)
    out.notes.push_back("AC3D version " + std::to_string(t.newerVersion) + " is newer than 12 (AC3Dc); read as AC3Dc");
  if (t.defaultMaterial) out.notes.push_back("no MATERIAL: every surface uses a grey default material");
  add(t.lines, "line surfaces dropped (closed and open lines)");
  add(t.smallPolygons, "surfaces with fewer than 3 refs dropped");
  add(t.unknownTypes, "surfaces of an unknown type read as polygons");
  add(t.degenerateStrip, "strip triangles with two corners at one position skipped");
  add(t.notSimple, "polygons not ear-clipped to the end (not simple, or over the work budget): their rest was fanned");
  add(t.pointLists, "objects with vertices but no refs (point lists) dropped");
  add(t.lights, "light objects ignored");
  add(t.unknownObjectTypes, "objects of an unknown type read as poly");
  add(t.subdiv, "objects with subdiv > 0: the control mesh is kept, not subdivided");
  add(t.layers, "TORCS texture layers (tiled, skids, shad) ignored: the base texture is used");
  add(t.mixedNormals, "objects with normals on some vertex lines only: their normals dropped");
  add(t.shortData, "data sections shorter than their last line: the rest of the line skipped");
  for (const auto& [what, seen] : t.unknown)
    out.notes.push_back(what + " skipped on " + std::to_string(seen.first) + " line(s), the first at line " +
                        std::to_string(seen.second));
  add(t.unknownKinds, "more lines with other unknown tokens skipped");
}

}  // namespace

Model loadAc3d(const std::string& path, const ResourceLimits& limits) {
  std::ifstream f(path, std::ios::binary);
  if (!f) throw Error(path + ": cannot open for reading");
  f.seekg(0, std::ios::end);
  const std::streamoff size = f.tellg();
  f.seekg(0);
  std::string text(size_t(std::max<std::streamoff>(size, 0)), '\0');
  if (!text.empty() && !f.read(text.data(), std::streamsize(text.size()))) throw Error(path + ": read failed");
  ac3d::File file = ac3d::parse(path, text, limits);
  Model out;
  out.loader = "ac3d";
  Builder(path, file, limits, out).run();
  writeNotes(file.tally, out);
  return out;
}

}  // namespace tessera::model::detail
