// Every other format through Assimp (Debian's libassimp): COLLADA .dae, glTF 1.0, 3DS, FBX, PLY, ...
// whatever Assimp's importers read. AC3D never comes here: load_ac3d.cpp reads it.
//
// Post-processing is limited to Triangulate + SortByPType (points and lines are removed and noted);
// node transforms are composed here in double rather than by PreTransformVertices (float). The
// diffuse (or glTF base colour) texture of each material is its base colour texture; textures
// Assimp embeds ("*N") are kept in memory, external ones are resolved beside the model file and
// checked to exist. Assimp stores v up; it is flipped to the glTF convention (v' = 1 - v).
// A glTF 1.0 document whose asset.version load_gltf.cpp normalized is read from memory in place of
// its file (ReplacedFileIO); its buffers and images are still read beside the file.
#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <assimp/DefaultIOSystem.h>
#include <assimp/Importer.hpp>
#include <assimp/MemoryIOWrapper.h>
#include <filesystem>
#include <map>

#include "model/loaders.h"
#include "raster/command_list.h"

namespace tessera::model::detail {

namespace {

glm::dmat4 toTransform(const aiMatrix4x4& a) {
  glm::dmat4 t;
  const ai_real* p = &a.a1;  // row-major
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) t[c][r] = double(p[r * 4 + c]);
  return t;
}

Wrap wrapOf(aiTextureMapMode m) {
  if (m == aiTextureMapMode_Clamp || m == aiTextureMapMode_Decal) return Wrap::ClampToEdge;
  if (m == aiTextureMapMode_Mirror) return Wrap::MirroredRepeat;
  return Wrap::Repeat;
}

struct UvChannel {
  unsigned channel = 0;
  bool transform = false;
  aiUVTransform uvt;
};

class AssimpBuilder {
 public:
  AssimpBuilder(const std::string& path, const aiScene& sc, Model& out) : path_(path), sc_(sc), out_(out) {}

  void run() {
    for (unsigned i = 0; i < sc_.mNumMaterials; ++i) material(*sc_.mMaterials[i], i);
    node(*sc_.mRootNode, glm::dmat4(1.0), 0);
    if (skippedMeshes_) out_.notes.push_back(std::to_string(skippedMeshes_) + " point / line meshes skipped");
  }

 private:
  void material(const aiMaterial& am, unsigned index) {
    Material m;
    aiString name;
    if (am.Get(AI_MATKEY_NAME, name) == AI_SUCCESS) m.name = name.C_Str();
    aiColor4D c(1, 1, 1, 1);
    if (am.Get(AI_MATKEY_BASE_COLOR, c) == AI_SUCCESS || am.Get(AI_MATKEY_COLOR_DIFFUSE, c) == AI_SUCCESS)
      m.baseColorFactor = {float(c.r), float(c.g), float(c.b), float(c.a)};
    ai_real opacity = 1;
    if (am.Get(AI_MATKEY_OPACITY, opacity) == AI_SUCCESS && opacity < 1) {
      m.baseColorFactor[3] = float(opacity);
      m.alphaMode = AlphaMode::Blend;
    }
    int twoSided = 0;
    if (am.Get(AI_MATKEY_TWOSIDED, twoSided) == AI_SUCCESS) m.doubleSided = twoSided != 0;
    UvChannel uv;
    const aiTextureType type = am.GetTextureCount(aiTextureType_DIFFUSE)      ? aiTextureType_DIFFUSE
                               : am.GetTextureCount(aiTextureType_BASE_COLOR) ? aiTextureType_BASE_COLOR
                                                                              : aiTextureType_NONE;
    if (type != aiTextureType_NONE) {
      aiString texPath;
      aiTextureMapMode modes[2] = {aiTextureMapMode_Wrap, aiTextureMapMode_Wrap};
      unsigned uvIndex = 0;
      if (am.GetTexture(type, 0, &texPath, nullptr, &uvIndex, nullptr, nullptr, modes) == AI_SUCCESS) {
        m.baseColorTexture = texture(texPath.C_Str(), m.name);
        m.wrapS = wrapOf(modes[0]), m.wrapT = wrapOf(modes[1]);
        uv.channel = uvIndex;
        if (am.Get(AI_MATKEY_UVTRANSFORM(type, 0), uv.uvt) == AI_SUCCESS &&
            (uv.uvt.mScaling.x != 1 || uv.uvt.mScaling.y != 1 || uv.uvt.mTranslation.x != 0 ||
             uv.uvt.mTranslation.y != 0)) {
          uv.transform = true;
          if (uv.uvt.mRotation != 0)
            out_.notes.push_back("material " + std::to_string(index) +
                                 ": UV rotation ignored (scale and offset applied)");
        }
      }
    }
    out_.materials.push_back(m);
    uv_.push_back(uv);
  }

  int32_t texture(const std::string& ref, const std::string& materialName) {
    if (auto it = byRef_.find(ref); it != byRef_.end()) return it->second;
    TextureRef t;
    if (const aiTexture* emb = sc_.GetEmbeddedTexture(ref.c_str())) {
      t.source = TextureRef::Source::Memory;
      t.name = emb->mFilename.length ? emb->mFilename.C_Str() : ref;
      if (emb->mHeight == 0) {  // compressed: mWidth bytes of a file
        const auto* b = reinterpret_cast<const uint8_t*>(emb->pcData);
        t.bytes = std::make_shared<const std::vector<uint8_t>>(b, b + emb->mWidth);
        t.size = emb->mWidth;
        const std::string hint = emb->achFormatHint;
        t.mimeType = hint == "png" ? "image/png" : hint == "jpg" || hint == "jpeg" ? "image/jpeg" : "";
      } else {  // raw aiTexel (BGRA) texels
        auto px = std::make_shared<std::vector<uint8_t>>(size_t(emb->mWidth) * emb->mHeight * 4);
        for (size_t i = 0; i < size_t(emb->mWidth) * emb->mHeight; ++i) {
          const aiTexel& x = emb->pcData[i];
          (*px)[i * 4] = x.r, (*px)[i * 4 + 1] = x.g, (*px)[i * 4 + 2] = x.b, (*px)[i * 4 + 3] = x.a;
        }
        t.bytes = px;
        t.rawRGBA = true;
        t.rawWidth = emb->mWidth, t.rawHeight = emb->mHeight;
      }
    } else {
      t.source = TextureRef::Source::File;
      t.uri = ref;
      t.path = resolveBeside(path_, ref);
      std::error_code ec;
      if (!std::filesystem::is_regular_file(t.path, ec)) {  // COLLADA writes URIs; try them percent-decoded
        const std::string decoded = resolveBeside(path_, uriDecode(ref));
        if (std::filesystem::is_regular_file(decoded, ec)) t.path = decoded;
      }
      requireTextureFile(path_, "material '" + materialName + "' diffuse texture", ref, t.path);
      t.name = std::filesystem::path(t.path).filename().string();
    }
    const int32_t index = int32_t(out_.textures.size());
    out_.textures.push_back(std::move(t));
    byRef_[ref] = index;
    return index;
  }

  void node(const aiNode& n, const glm::dmat4& parent, int depth) {
    if (depth > 1000) throw Error(path_ + ": the node hierarchy is deeper than 1000 levels");
    const glm::dmat4 world = compose(parent, toTransform(n.mTransformation));
    const int32_t ordinal = nodes_++;
    objects_.begin(n.mName.length ? n.mName.C_Str() : "node" + std::to_string(ordinal), ordinal);
    for (unsigned i = 0; i < n.mNumMeshes; ++i) {
      if (n.mMeshes[i] >= sc_.mNumMeshes)
        throw Error(path_ + ": node '" + std::string(n.mName.C_Str()) + "' names a missing mesh");
      mesh(*sc_.mMeshes[n.mMeshes[i]], world);
    }
    for (unsigned i = 0; i < n.mNumChildren; ++i) node(*n.mChildren[i], world, depth + 1);
  }

  void mesh(const aiMesh& am, const glm::dmat4& world) {
    if (!(am.mPrimitiveTypes & aiPrimitiveType_TRIANGLE)) {
      ++skippedMeshes_;
      return;
    }
    Mesh mesh;
    mesh.name = am.mName.C_Str();
    if (am.mMaterialIndex < out_.materials.size()) {
      mesh.material = am.mMaterialIndex;
    } else {
      if (defaultMaterial_ < 0) {
        defaultMaterial_ = int(out_.materials.size());
        out_.materials.push_back(Material{.name = "default"});
        uv_.push_back(UvChannel{});
      }
      mesh.material = uint32_t(defaultMaterial_);
    }
    const bool identity = isIdentity(world);
    mesh.positions.resize(am.mNumVertices);
    for (unsigned i = 0; i < am.mNumVertices; ++i) {
      const glm::vec3 p{float(am.mVertices[i].x), float(am.mVertices[i].y), float(am.mVertices[i].z)};
      mesh.positions[i] = identity ? p : transformPoint(world, p);
    }
    const UvChannel& uv = uv_[mesh.material];
    if (uv.channel < AI_MAX_NUMBER_OF_TEXTURECOORDS && am.mTextureCoords[uv.channel]) {
      mesh.texcoords.resize(am.mNumVertices);
      for (unsigned i = 0; i < am.mNumVertices; ++i) {
        float u = float(am.mTextureCoords[uv.channel][i].x), v = float(am.mTextureCoords[uv.channel][i].y);
        if (uv.transform)
          u = float(double(u) * uv.uvt.mScaling.x + uv.uvt.mTranslation.x),
          v = float(double(v) * uv.uvt.mScaling.y + uv.uvt.mTranslation.y);
        mesh.texcoords[i] = {u, 1.0f - v};
      }
    }
    if (am.mNormals) {
      mesh.normals.resize(am.mNumVertices);
      for (unsigned i = 0; i < am.mNumVertices; ++i) {
        const glm::vec3 n{float(am.mNormals[i].x), float(am.mNormals[i].y), float(am.mNormals[i].z)};
        mesh.normals[i] = identity ? n : transformNormal(world, n);
      }
    }
    const bool flip = det3(world) < 0.0;
    for (unsigned f = 0; f < am.mNumFaces; ++f) {
      const aiFace& face = am.mFaces[f];
      if (face.mNumIndices != 3) continue;  // SortByPType removed the rest
      uint32_t a = face.mIndices[0], b = face.mIndices[1], c = face.mIndices[2];
      if (a >= am.mNumVertices || b >= am.mNumVertices || c >= am.mNumVertices)
        throw Error(path_ + ": mesh '" + mesh.name + "' face " + std::to_string(f) + " indexes a missing vertex");
      if (flip) std::swap(b, c);
      mesh.indices.insert(mesh.indices.end(), {a, b, c});
    }
    if (!mesh.indices.empty()) objects_.add(std::move(mesh));
  }

  const std::string& path_;
  const aiScene& sc_;
  Model& out_;
  ObjectSink objects_{out_};  // one object per node instance (docs/model-import.md "Objects")
  int32_t nodes_ = 0;         // aiNodes visited so far: the next node's pre-order ordinal
  std::vector<UvChannel> uv_;
  std::map<std::string, int32_t> byRef_;
  int defaultMaterial_ = -1;
  size_t skippedMeshes_ = 0;
};

}  // namespace

namespace {

// Assimp's file system with one file replaced by text in memory; the importer owns it.
class ReplacedFileIO : public Assimp::DefaultIOSystem {
 public:
  ReplacedFileIO(std::string path, const std::string& text) : path_(std::move(path)), text_(text) {}
  Assimp::IOStream* Open(const char* file, const char* mode) override {
    if (file && path_ == file)
      return new Assimp::MemoryIOStream(reinterpret_cast<const uint8_t*>(text_.data()), text_.size());
    return Assimp::DefaultIOSystem::Open(file, mode);
  }

 private:
  std::string path_;
  const std::string& text_;  // outlives the importer (loadAssimp's argument)
};

Model read(const std::string& path, const std::string* text) {
  Assimp::Importer importer;
  if (text) importer.SetIOHandler(new ReplacedFileIO(path, *text));
  importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE, aiPrimitiveType_POINT | aiPrimitiveType_LINE);
  const aiScene* sc = importer.ReadFile(path, aiProcess_Triangulate | aiProcess_SortByPType);
  if (!sc || !sc->mRootNode || (sc->mFlags & AI_SCENE_FLAGS_INCOMPLETE))
    throw Error(path + ": Assimp cannot read it: " + std::string(importer.GetErrorString()));
  Model out;
  std::string ext = std::filesystem::path(path).extension().string();
  out.loader = "assimp:" + (ext.empty() ? std::string("?") : ext.substr(1));
  AssimpBuilder(path, *sc, out).run();
  return out;
}

}  // namespace

// limits: checked by loadModel() on the result
Model loadAssimp(const std::string& path, const ResourceLimits&) { return read(path, nullptr); }
Model loadAssimp(const std::string& path, const ResourceLimits&, const std::string& text) { return read(path, &text); }

}  // namespace tessera::model::detail
