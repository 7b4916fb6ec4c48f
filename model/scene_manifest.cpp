// Reading scene manifests and model directories (scene_manifest.h); the merge is scene_merge.cpp.
#include "model/scene_manifest.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "base/det_math.h"
#include "base/error.h"
#include "model/loaders.h"

namespace tessera::model::detail {

namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return s;
}

// The extensions a directory scene picks up: the formats loadModel() reads by its own readers, and the
// common ones Assimp reads. A fixed list, so that what a directory means does not depend on the
// Assimp build.
bool isModelExtension(const std::string& ext) {
  static const char* kExtensions[] = {".gltf", ".glb", ".obj", ".ac",  ".acc", ".ac3d",
                                      ".dae",  ".fbx", ".3ds", ".ply", ".stl"};
  return std::any_of(std::begin(kExtensions), std::end(kExtensions), [&](const char* e) { return ext == e; });
}

// A JSON value as a message shows it: at most 40 characters.
std::string shownValue(const json& v) {
  const std::string s = v.dump();
  return s.size() > 40 ? s.substr(0, 40) + "..." : s;
}

class ManifestReader {
 public:
  explicit ManifestReader(const std::string& path) : path_(path) {}

  Scene read() {
    std::ifstream in(path_, std::ios::binary);
    if (!in) throw Error(path_ + ": cannot open the scene manifest for reading");
    std::stringstream ss;
    ss << in.rdbuf();
    const std::string text = ss.str();
    json doc;
    try {
      doc = json::parse(text);
    } catch (const json::parse_error& e) {
      throw Error(path_ + ":" + position(text, e.byte) + ": not valid JSON: " + e.what());
    } catch (const json::out_of_range& e) {
      // A number beyond the range of a double (1e309) is out_of_range 406, not a parse_error, and carries
      // no position; uncaught it ended `tessera` as an internal error (exit 3). Found by fuzz/scene_manifest.
      throw Error(path_ + ": not valid JSON: a number beyond the range of a double: " + e.what());
    }
    if (!doc.is_object()) fail("", "a scene manifest is a JSON object, not " + shownValue(doc));
    for (const auto& [k, v] : doc.items())
      if (k != "schema" && k != "models" && k != "comment")
        fail("/" + k, "unknown key (a scene manifest has schema, models and comment)");
    if (!doc.contains("schema")) fail("/schema", "missing: a scene manifest says \"schema\": 1");
    if (doc["schema"] != 1) fail("/schema", "expected 1, got " + shownValue(doc["schema"]));
    if (doc.contains("comment") && !doc["comment"].is_string())
      fail("/comment", "expected a string, got " + shownValue(doc["comment"]));
    if (!doc.contains("models")) fail("/models", "missing: the list of model files");
    const json& models = doc["models"];
    if (!models.is_array()) fail("/models", "expected an array of entries, got " + shownValue(models));
    if (models.empty()) fail("/models", "empty: a scene needs at least one model file");
    Scene s{.path = path_, .kind = "manifest", .entries = {}};
    for (size_t i = 0; i < models.size(); ++i) s.entries.push_back(entry(models[i], "/models/" + std::to_string(i)));
    return s;
  }

 private:
  [[noreturn]] void fail(const std::string& pointer, const std::string& why) const {
    throw Error(path_ + ": " + (pointer.empty() ? "" : pointer + ": ") + why);
  }

  // "line:column" (1-based) of byte `byte` (nlohmann's 1-based count of the bytes read).
  static std::string position(const std::string& text, size_t byte) {
    const size_t n = std::min(byte, text.size());
    const size_t last = n > 0 ? n - 1 : 0;  // the byte the parser stopped at
    size_t line = 1, column = 1;
    for (size_t i = 0; i < last; ++i) {
      if (text[i] == '\n')
        ++line, column = 1;
      else
        ++column;
    }
    return std::to_string(line) + ":" + std::to_string(column);
  }

  std::vector<double> numbers(const json& v, const std::string& pointer, size_t count) const {
    if (!v.is_array()) fail(pointer, "expected " + std::to_string(count) + " numbers, got " + shownValue(v));
    if (v.size() != count)
      fail(pointer, "expected " + std::to_string(count) + " numbers, got " + std::to_string(v.size()));
    std::vector<double> out;
    for (size_t i = 0; i < count; ++i) {
      if (!v[i].is_number() || !std::isfinite(v[i].get<double>()))
        fail(pointer + "/" + std::to_string(i), "expected a finite number, got " + shownValue(v[i]));
      out.push_back(v[i].get<double>());
    }
    return out;
  }

  SceneEntry entry(const json& e, const std::string& pointer) const {
    if (!e.is_object()) fail(pointer, "expected an object with \"file\", got " + shownValue(e));
    for (const auto& [k, v] : e.items())
      if (k != "file" && k != "name" && k != "transform" && k != "translation" && k != "rotation" && k != "scale")
        fail(pointer + "/" + k,
             "unknown key (an entry has file, name, and transform or translation / rotation / scale)");
    SceneEntry out;
    out.where = pointer;
    if (!e.contains("file")) fail(pointer + "/file", "missing: the model file of this entry");
    if (!e["file"].is_string() || e["file"].get<std::string>().empty())
      fail(pointer + "/file", "expected a file name, got " + shownValue(e["file"]));
    const std::string written = e["file"];
    out.file = resolveBeside(path_, written);
    std::error_code ec;
    if (fs::is_directory(out.file, ec))
      fail(pointer + "/file", "'" + written + "' is a directory: a manifest lists model files, not scenes");
    if (isScenePath(out.file))
      fail(pointer + "/file",
           "'" + written + "' is a scene manifest: manifests do not nest (so they cannot form a cycle)");
    if (!fs::is_regular_file(out.file, ec))
      fail(pointer + "/file", "'" + written + "' (resolved to '" + out.file + "') does not exist");
    if (e.contains("name")) {
      if (!e["name"].is_string()) fail(pointer + "/name", "expected a string, got " + shownValue(e["name"]));
      out.name = e["name"];
    }
    const bool trs = e.contains("translation") || e.contains("rotation") || e.contains("scale");
    if (e.contains("transform")) {
      if (trs) fail(pointer, "has both transform and translation / rotation / scale: give one or the other");
      const std::vector<double> m = numbers(e["transform"], pointer + "/transform", 16);
      if (m[3] != 0.0 || m[7] != 0.0 || m[11] != 0.0 || m[15] != 1.0)
        fail(pointer + "/transform",
             "not affine: elements 3, 7, 11, 15 (the last row, column-major as glTF's node.matrix) must be 0 0 0 1, "
             "got " +
                 shownValue(json{m[3], m[7], m[11], m[15]}) + " (a row-major matrix puts its translation there)");
      for (int i = 0; i < 16; ++i) out.transform[i / 4][i % 4] = m[size_t(i)];
    } else if (trs) {
      glm::dvec3 t(0.0), r(0.0), s(1.0);
      if (e.contains("translation")) {
        const auto v = numbers(e["translation"], pointer + "/translation", 3);
        t = {v[0], v[1], v[2]};
      }
      if (e.contains("rotation")) {
        const auto v = numbers(e["rotation"], pointer + "/rotation", 3);
        r = {v[0], v[1], v[2]};
      }
      if (e.contains("scale")) {
        const auto v = numbers(e["scale"], pointer + "/scale", 3);
        for (int i = 0; i < 3; ++i)
          if (v[size_t(i)] == 0.0) fail(pointer + "/scale/" + std::to_string(i), "0 would flatten the model");
        s = {v[0], v[1], v[2]};
      }
      out.transform = trsMatrix(t, r, s);
    }
    return out;
  }

  const std::string& path_;
};

}  // namespace

bool isScenePath(const std::string& path) {
  std::error_code ec;
  if (fs::is_directory(path, ec)) return true;
  return lower(fs::path(path).extension().string()) == ".json";
}

Scene readSceneManifest(const std::string& path) { return ManifestReader(path).read(); }

Scene readSceneDirectory(const std::string& path) {
  std::vector<std::string> names;
  std::error_code ec;
  for (fs::directory_iterator it(path, ec), end; !ec && it != end; it.increment(ec)) {
    std::error_code fec;
    if (!it->is_regular_file(fec)) continue;  // subdirectories (textures/) and the like
    if (isModelExtension(lower(it->path().extension().string()))) names.push_back(it->path().filename().string());
  }
  if (ec) throw Error(path + ": cannot list the directory: " + ec.message());
  if (names.empty())
    throw Error(path + ": no model file in this directory (.gltf .glb .obj .ac .acc .ac3d .dae .fbx .3ds .ply .stl)");
  std::sort(names.begin(), names.end());  // byte order: the same scene on every file system
  Scene s{.path = path, .kind = "directory", .entries = {}};
  for (const std::string& n : names)
    s.entries.push_back(SceneEntry{.file = (fs::path(path) / n).string(), .name = "", .where = n});
  return s;
}

void sinCosDegrees(double degrees, double& s, double& c) {
  double r = std::fmod(degrees, 360.0);  // exact
  if (r < 0.0) r += 360.0;
  if (r >= 360.0) r = 0.0;  // a tiny negative r rounds up to 360
  int q = std::min(3, int(r / 90.0));
  if (r < 90.0 * q) --q;  // the division rounded up to the next quarter
  const double x = (r - 90.0 * q) * (kPi / 180.0);
  const double s0 = detSin(x), c0 = detCos(x);
  // Quarter turns rotate (c0, s0) exactly: sin(a + 90) = cos a, cos(a + 90) = -sin a. The + 0.0 turns -0 into +0.
  switch (q) {
    case 0:
      s = s0, c = c0;
      break;
    case 1:
      s = c0, c = -s0 + 0.0;
      break;
    case 2:
      s = -s0 + 0.0, c = -c0 + 0.0;
      break;
    default:
      s = -c0 + 0.0, c = s0;
      break;
  }
}

glm::dmat4 trsMatrix(const glm::dvec3& translation, const glm::dvec3& rotationDegrees, const glm::dvec3& scale) {
  // One rotation about a coordinate axis, column-major: axis 0 = x, 1 = y, 2 = z.
  const auto axisRotation = [](int axis, double degrees) {
    double s = 0.0, c = 1.0;
    sinCosDegrees(degrees, s, c);
    const int a = (axis + 1) % 3, b = (axis + 2) % 3;  // the plane it turns: a towards b
    glm::dmat4 m(1.0);
    m[a][a] = c, m[a][b] = s, m[b][a] = -s + 0.0, m[b][b] = c;
    return m;
  };
  glm::dmat4 t(1.0), sc(1.0);
  t[3] = glm::dvec4(translation, 1.0);
  sc[0][0] = scale.x, sc[1][1] = scale.y, sc[2][2] = scale.z;
  const glm::dmat4 r = compose(axisRotation(2, rotationDegrees.z),
                               compose(axisRotation(1, rotationDegrees.y), axisRotation(0, rotationDegrees.x)));
  return compose(compose(t, r), sc);
}

}  // namespace tessera::model::detail
