#include "model/gltf_checks.h"

#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <utility>
#include <vector>

#include "base/error.h"

namespace tessera::model::detail::gltf {

namespace {

using nlohmann::json;

class Checker {
 public:
  Checker(const std::string& path, const json& root) : path_(path), root_(root) {}

  [[noreturn]] void fail(const std::string& pointer, const std::string& why) const {
    throw Error(path_ + ": " + pointer + ": " + why);
  }

  // Arrays and objects nested deeper than `limit` (the root is level 1), walked with an explicit stack:
  // the document itself may be what would overflow a recursion. The stack is the path to the value being
  // looked at, so the error can name it.
  void depth(uint32_t limit) const {
    struct Frame {
      const json* value;
      json::const_iterator at;  // the child being looked at
    };
    if (!root_.is_structured()) return;
    std::vector<Frame> stack{{&root_, root_.cbegin()}};
    while (!stack.empty()) {
      Frame& f = stack.back();
      if (f.at == f.value->cend()) {
        stack.pop_back();
        if (!stack.empty()) ++stack.back().at;
        continue;
      }
      const json& child = *f.at;
      if (!child.is_structured()) {
        ++f.at;
        continue;
      }
      if (stack.size() + 1 > limit) {
        std::string p;  // the first levels of the pointer: enough to find the place
        for (size_t k = 0; k < stack.size() && k < 16; ++k) {
          const Frame& g = stack[k];
          p += "/" + (g.value->is_object() ? escape(g.at.key()) : std::to_string(g.at - g.value->cbegin()));
        }
        if (stack.size() > 16) p += "/...";
        fail(p, "JSON arrays and objects nest deeper than the limit of " + std::to_string(limit) + " levels");
      }
      stack.push_back({&child, child.cbegin()});
    }
  }

  // Index and count fields: non-negative integers; those tinygltf reads as int must fit in one.
  void integers() const {
    eachObject("/scenes", [&](const std::string& p, const json& s) { indexArray(p, s, "nodes"); });
    if (root_.contains("scene")) index("/scene", root_["scene"]);
    eachObject("/nodes", [&](const std::string& p, const json& n) {
      optionalIndex(p, n, "mesh");
      indexArray(p, n, "children");
    });
    eachObject("/meshes", [&](const std::string& p, const json& m) {
      if (!m.contains("primitives") || !m["primitives"].is_array()) return;
      for (size_t k = 0; k < m["primitives"].size(); ++k) {
        const json& prim = m["primitives"][k];
        const std::string pp = p + "/primitives/" + std::to_string(k);
        if (!prim.is_object()) continue;
        optionalIndex(pp, prim, "indices");
        optionalIndex(pp, prim, "material");
        if (prim.contains("mode") && !(isIndex(prim["mode"]) && prim["mode"].get<int64_t>() <= 6))
          fail(pp + "/mode", describe(prim["mode"]) + " is not a glTF 2.0 primitive mode (0 to 6)");
        if (prim.contains("attributes") && prim["attributes"].is_object())
          for (const auto& [name, a] : prim["attributes"].items()) index(pp + "/attributes/" + escape(name), a);
      }
    });
    eachObject("/accessors", [&](const std::string& p, const json& a) {
      optionalIndex(p, a, "bufferView");
      optionalSize(p, a, "byteOffset");
      optionalSize(p, a, "count");
      optionalIndex(p, a, "componentType");
      if (!a.contains("sparse") || !a["sparse"].is_object()) return;
      const json& s = a["sparse"];
      optionalIndex(p + "/sparse", s, "count");
      for (const char* part : {"indices", "values"}) {
        if (!s.contains(part) || !s[part].is_object()) continue;
        const std::string sp = p + "/sparse/" + part;
        optionalIndex(sp, s[part], "bufferView");
        optionalSize(sp, s[part], "byteOffset");
        optionalIndex(sp, s[part], "componentType");
      }
    });
    eachObject("/bufferViews", [&](const std::string& p, const json& v) {
      optionalIndex(p, v, "buffer");
      optionalSize(p, v, "byteOffset");
      optionalSize(p, v, "byteLength");
      optionalSize(p, v, "byteStride");
    });
    eachObject("/buffers", [&](const std::string& p, const json& b) { optionalSize(p, b, "byteLength"); });
    eachObject("/images", [&](const std::string& p, const json& i) { optionalIndex(p, i, "bufferView"); });
    eachObject("/textures", [&](const std::string& p, const json& t) {
      optionalIndex(p, t, "source");
      optionalIndex(p, t, "sampler");
    });
    eachObject("/materials", [&](const std::string& p, const json& m) {
      const json::json_pointer bp("/pbrMetallicRoughness/baseColorTexture");
      if (!m.contains(bp) || !m.at(bp).is_object()) return;
      const json& ti = m.at(bp);
      const std::string tp = p + "/pbrMetallicRoughness/baseColorTexture";
      optionalIndex(tp, ti, "index");
      optionalIndex(tp, ti, "texCoord");
      const json::json_pointer xp("/extensions/KHR_texture_transform");
      if (ti.contains(xp) && ti.at(xp).is_object())
        optionalIndex(tp + "/extensions/KHR_texture_transform", ti.at(xp), "texCoord");
    });
  }

  // glTF 2.0 §5.25 (node): matrix is 16 numbers, translation 3, rotation 4 (a quaternion), scale 3.
  // tinygltf would ignore a matrix of another length and use the identity instead.
  void nodeTransforms() const {
    eachObject("/nodes", [&](const std::string& p, const json& n) {
      static constexpr std::pair<const char*, size_t> kArity[] = {
          {"matrix", 16}, {"translation", 3}, {"rotation", 4}, {"scale", 3}};
      for (const auto& [name, size] : kArity) {
        if (!n.contains(name)) continue;
        const json& a = n[name];
        if (!a.is_array() || a.size() != size)
          fail(p + "/" + name, "expected " + std::to_string(size) + " numbers, got " + describe(a));
        for (size_t k = 0; k < size; ++k)
          if (!a[k].is_number() || !std::isfinite(a[k].get<double>()))
            fail(p + "/" + name + "/" + std::to_string(k), "expected a finite number, got " + describe(a[k]));
      }
    });
  }

  // glTF 2.0 §5.26 (sampler): the GL enums it allows; tinygltf passes any integer through.
  void samplers() const {
    eachObject("/samplers", [&](const std::string& p, const json& s) {
      enumField(p, s, "wrapS", {33071, 33648, 10497}, "33071 CLAMP_TO_EDGE, 33648 MIRRORED_REPEAT, 10497 REPEAT");
      enumField(p, s, "wrapT", {33071, 33648, 10497}, "33071 CLAMP_TO_EDGE, 33648 MIRRORED_REPEAT, 10497 REPEAT");
      enumField(p, s, "magFilter", {9728, 9729}, "9728 NEAREST, 9729 LINEAR");
      enumField(p, s, "minFilter", {9728, 9729, 9984, 9985, 9986, 9987}, "9728, 9729, 9984 to 9987");
    });
  }

 private:
  template <class F>
  void eachObject(const char* array, F&& f) const {
    const std::string name = array + 1;
    if (!root_.contains(name)) return;
    const json& a = root_[name];
    if (!a.is_array()) fail(array, "expected an array, got " + describe(a));
    for (size_t i = 0; i < a.size(); ++i) {
      const std::string p = std::string(array) + "/" + std::to_string(i);
      if (!a[i].is_object()) fail(p, "expected an object, got " + describe(a[i]));
      f(p, a[i]);
    }
  }

  static bool isIndex(const json& v) {
    return v.is_number_unsigned() || (v.is_number_integer() && v.get<int64_t>() >= 0);
  }
  void index(const std::string& p, const json& v) const {
    if (!isIndex(v) || v.get<uint64_t>() > uint64_t(INT32_MAX))
      fail(p, describe(v) + " is not an index (an integer from 0 to 2147483647)");
  }
  void optionalIndex(const std::string& p, const json& o, const char* field) const {
    if (o.contains(field)) index(p + "/" + field, o[field]);
  }
  void optionalSize(const std::string& p, const json& o, const char* field) const {
    if (o.contains(field) && !isIndex(o[field]))
      fail(p + "/" + field, describe(o[field]) + " is not a non-negative integer");
  }
  void indexArray(const std::string& p, const json& o, const char* field) const {
    if (!o.contains(field)) return;
    const json& a = o[field];
    if (!a.is_array()) fail(p + "/" + field, "expected an array of indices, got " + describe(a));
    for (size_t k = 0; k < a.size(); ++k) index(p + "/" + field + "/" + std::to_string(k), a[k]);
  }
  void enumField(const std::string& p, const json& o, const char* field, std::initializer_list<int64_t> allowed,
                 const char* names) const {
    if (!o.contains(field)) return;
    const json& v = o[field];
    if (v.is_number_integer())
      for (int64_t a : allowed)
        if (v.get<int64_t>() == a) return;
    fail(p + "/" + field, describe(v) + " is not one of glTF 2.0's values (" + names + ")");
  }

  // A value as it may appear in a message: numbers and short strings as written, anything else by type.
  static std::string describe(const json& v) {
    if (v.is_number()) return v.dump();
    if (v.is_string()) {
      const std::string s = v.get<std::string>();
      return s.size() <= 40 ? v.dump() : "a string";
    }
    if (v.is_array()) return std::to_string(v.size()) + " values";
    return std::string("a JSON ") + v.type_name();
  }
  static std::string escape(const std::string& key) {  // RFC 6901
    std::string out;
    for (char c : key) out += c == '~' ? "~0" : c == '/' ? "~1" : std::string(1, c);
    return out;
  }
  const std::string& path_;
  const json& root_;
};

}  // namespace

void checkDocument(const std::string& path, const nlohmann::json& root, const ResourceLimits& limits) {
  const Checker c(path, root);
  c.depth(limits.graphDepth);
  c.integers();
  c.nodeTransforms();
  c.samplers();
}

}  // namespace tessera::model::detail::gltf
