#include "tools/cli/suite_spec.h"

#include <glob.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "base/byte_size.h"
#include "base/error.h"
#include "base/sha256.h"
#include "tools/cli/repo_paths.h"
#include "tools/scenes/scenes.h"

namespace tessera::cli::suite {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// The fields each kind accepts besides the common ones (name, kind, comment, timeout_seconds,
// memory_limit, args).
const std::vector<std::pair<std::string, std::set<std::string>>> kKinds = {
    {"render", {"scene", "size", "except"}},
    {"replay", {"frame"}},
    {"crosscheck", {"frame", "size", "gl_driver", "except"}},
    {"visibility", {"frame", "size", "except"}},
    {"compare", {"a", "b"}},
    {"golden", {}},
    {"mutant", {"mutant", "scenes"}},
    {"command", {"steps", "gl"}}};
const std::set<std::string> kCommon = {"name", "kind", "comment", "timeout_seconds", "memory_limit", "args"};

struct Where {
  const std::string& file;
  size_t index;
  std::string name;
  [[noreturn]] void fail(const std::string& field, const std::string& reason) const {
    throw Error(file + ": case " + std::to_string(index) + (name.empty() ? "" : " (" + name + ")") + ": field '" +
                field + "': " + reason);
  }
};

bool hasGlobChars(std::string_view s) { return s.find_first_of("*?[") != std::string_view::npos; }

std::vector<std::string> globFiles(const std::string& pattern) {
  glob_t g{};
  std::vector<std::string> out;
  if (::glob(pattern.c_str(), 0, nullptr, &g) == 0)
    for (size_t i = 0; i < g.gl_pathc; ++i)
      if (fs::is_regular_file(g.gl_pathv[i])) out.push_back(fs::absolute(g.gl_pathv[i]).lexically_normal().string());
  globfree(&g);
  return out;  // glob(3) sorts its matches
}

// A path of the suite: absolute as it is, else relative to the working directory, else to the clone.
std::string resolveFile(const std::string& p, const Where& w, const std::string& field) {
  std::error_code ec;
  if (fs::path(p).is_absolute()) {
    if (!fs::exists(p, ec)) w.fail(field, "'" + p + "' does not exist");
    return p;
  }
  if (fs::exists(p, ec)) return fs::absolute(p).lexically_normal().string();
  const fs::path c = fs::path(repoRoot()) / p;
  if (fs::exists(c, ec)) return c.lexically_normal().string();
  w.fail(field,
         "'" + p + "' does not exist (relative paths are looked up in the working directory, then in the clone)");
}

// What a "frame" or "scene" field stands for: (item name, argument) pairs.
std::vector<std::pair<std::string, std::string>> expandFrames(const std::string& v, bool scenesOnly, const Where& w,
                                                              const std::string& field,
                                                              const std::set<std::string>& except) {
  std::vector<std::pair<std::string, std::string>> out;
  if (v == "*") {
    for (const scenes::SceneInfo& s : scenes::all())
      if (!except.count(std::string(s.name))) out.emplace_back(std::string(s.name), std::string(s.name));
    return out;
  }
  if (!except.empty()) w.fail("except", "only a \"*\" over every scene takes exceptions");
  if (scenes::find(v)) return {{v, v}};
  if (scenesOnly) w.fail(field, "'" + v + "' is no built-in scene (`tessera scenes` lists them) and not \"*\"");
  if (hasGlobChars(v)) {
    std::vector<std::string> files = globFiles(v);
    if (files.empty() && !fs::path(v).is_absolute()) files = globFiles((fs::path(repoRoot()) / v).string());
    if (files.empty()) w.fail(field, "the glob '" + v + "' matches no file");
    for (const std::string& f : files) out.emplace_back(fs::path(f).stem().string(), f);
    return out;
  }
  const std::string f = resolveFile(v, w, field);
  return {{fs::path(f).stem().string(), f}};
}

std::string stringField(const json& c, const std::string& key, const Where& w, bool required) {
  if (!c.contains(key)) {
    if (required) w.fail(key, "missing");
    return "";
  }
  if (!c[key].is_string() || c[key].get<std::string>().empty()) w.fail(key, "must be a non-empty string");
  return c[key].get<std::string>();
}

std::vector<std::string> stringList(const json& v, const Where& w, const std::string& field) {
  if (!v.is_array()) w.fail(field, "must be an array of strings");
  std::vector<std::string> out;
  for (const json& s : v) {
    if (!s.is_string()) w.fail(field, "must be an array of strings");
    out.push_back(s.get<std::string>());
  }
  return out;
}

double timeoutField(const json& v, const Where& w) {
  if (!v.is_number() || !(v.get<double>() > 0) || v.get<double>() > 86400)
    w.fail("timeout_seconds", "must be a number in (0, 86400]");
  return v.get<double>();
}

uint64_t memoryField(const json& v, const Where& w) {
  if (!v.is_string()) w.fail("memory_limit", "must be a byte size such as \"4GiB\" (docs/limits.md)");
  try {
    const uint64_t b = parseByteSize(v.get<std::string>(), "memory_limit");
    if (b < (uint64_t(16) << 20)) w.fail("memory_limit", "'" + v.get<std::string>() + "' is below 16MiB");
    return b;
  } catch (const Error& e) {
    w.fail("memory_limit", e.what());
  }
}

}  // namespace

bool isValidCaseName(std::string_view name) {
  if (name.empty() || name.size() > 200) return false;
  size_t start = 0;
  while (true) {
    const size_t end = std::min(name.find('/', start), name.size());
    const std::string_view seg = name.substr(start, end - start);
    if (seg.empty() || seg == "." || seg == "..") return false;
    for (char ch : seg)
      if (!(std::isalnum(static_cast<unsigned char>(ch)) ||
            std::string_view("._@+=-").find(ch) != std::string_view::npos))
        return false;
    if (end == name.size()) return true;
    start = end + 1;
  }
}

std::string repoRoot() {
  const std::string m = repoPath("golden/manifest.json");
  std::error_code ec;
  if (!fs::exists(m, ec)) return fs::current_path().string();
  return fs::absolute(m).parent_path().parent_path().lexically_normal().string();
}

Suite loadSuite(const std::string& path, const LoadOptions& options) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path + ": cannot read the suite file");
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string text = ss.str();
  json doc;
  try {
    doc = json::parse(text);
  } catch (const json::parse_error& e) {
    throw Error(path + ": not valid JSON: " + e.what());
  }
  Suite s;
  s.file = path;
  s.sha256 = sha256Hex(std::span(reinterpret_cast<const uint8_t*>(text.data()), text.size()));
  if (!doc.is_object()) throw Error(path + ": the suite must be a JSON object");
  for (const auto& [k, v] : doc.items())
    if (k != "schema" && k != "name" && k != "comment" && k != "defaults" && k != "cases")
      throw Error(path + ": field '" + k + "': unknown (schema 1 has schema, name, comment, defaults, cases)");
  if (!doc.contains("schema") || doc["schema"] != 1) throw Error(path + ": field 'schema': must be 1");
  if (!doc.contains("name") || !doc["name"].is_string() || !isValidCaseName(doc["name"].get<std::string>()) ||
      doc["name"].get<std::string>().find('/') != std::string::npos)
    throw Error(path + ": field 'name': must be a name of [A-Za-z0-9._@+=-]");
  s.name = doc["name"];
  double timeout = 300;
  uint64_t memory = 0;
  if (doc.contains("defaults")) {
    const json& d = doc["defaults"];
    if (!d.is_object()) throw Error(path + ": field 'defaults': must be an object");
    for (const auto& [k, v] : d.items()) {
      if (k == "timeout_seconds") {
        if (!v.is_number() || !(v.get<double>() > 0) || v.get<double>() > 86400)
          throw Error(path + ": field 'defaults.timeout_seconds': must be a number in (0, 86400]");
        timeout = v.get<double>();
      } else if (k == "memory_limit") {
        if (!v.is_string()) throw Error(path + ": field 'defaults.memory_limit': must be a byte size such as \"4GiB\"");
        memory = parseByteSize(v.get<std::string>(), path + ": field 'defaults.memory_limit'");
        if (memory < (uint64_t(16) << 20)) throw Error(path + ": field 'defaults.memory_limit': below 16MiB");
      } else {
        throw Error(path + ": field 'defaults." + k + "': unknown (timeout_seconds, memory_limit)");
      }
    }
  }
  if (!doc.contains("cases") || !doc["cases"].is_array() || doc["cases"].empty())
    throw Error(path + ": field 'cases': must be a non-empty array");
  std::set<std::string> names;
  for (size_t i = 0; i < doc["cases"].size(); ++i) {
    const json& c = doc["cases"][i];
    Where w{path, i, ""};
    if (!c.is_object()) w.fail("", "a case must be a JSON object");
    const std::string name = stringField(c, "name", w, true);
    w.name = name;
    if (!isValidCaseName(name)) w.fail("name", "'" + name + "': segments of [A-Za-z0-9._@+=-] joined by '/'");
    const std::string kind = stringField(c, "kind", w, true);
    const auto k = std::find_if(kKinds.begin(), kKinds.end(), [&](const auto& p) { return p.first == kind; });
    if (k == kKinds.end())
      w.fail("kind",
             "'" + kind + "': unknown (render, replay, crosscheck, visibility, compare, golden, mutant, command)");
    for (const auto& [key, v] : c.items())
      if (!kCommon.count(key) && !k->second.count(key)) w.fail(key, "unknown for kind '" + kind + "'");
    SuiteCase base;
    base.kind = kind;
    base.timeoutSeconds = c.contains("timeout_seconds") ? timeoutField(c["timeout_seconds"], w) : timeout;
    base.memoryBytes = c.contains("memory_limit") ? memoryField(c["memory_limit"], w) : memory;
    const std::vector<std::string> extra =
        c.contains("args") ? stringList(c["args"], w, "args") : std::vector<std::string>{};
    if (kind == "command" && !extra.empty()) w.fail("args", "a command case gives its arguments in 'steps'");
    const std::string size = c.contains("size") ? stringField(c, "size", w, true) : "";
    // "except": scenes that a "*" leaves out (each must exist, so a renamed scene is noticed).
    std::set<std::string> except;
    if (c.contains("except"))
      for (const std::string& e : stringList(c["except"], w, "except")) {
        if (!scenes::find(e)) w.fail("except", "'" + e + "' is no built-in scene");
        except.insert(e);
      }
    const std::string glDriver = c.contains("gl_driver") ? stringField(c, "gl_driver", w, true) : options.glDriver;
    auto withSize = [&](std::vector<std::string> v) {
      if (!size.empty()) v.insert(v.end(), {"--size", size});
      return v;
    };
    auto withGl = [&](std::vector<std::string> v) {
      if (!glDriver.empty()) v.insert(v.end(), {"--gl-driver", glDriver});
      return v;
    };
    // (item suffix or "" for a single case, steps)
    std::vector<std::pair<std::string, std::vector<std::string>>> items;
    bool expands = false;
    if (kind == "render") {
      const std::string v = stringField(c, "scene", w, true);
      expands = v == "*";
      for (const auto& [item, arg] : expandFrames(v, true, w, "scene", except))
        items.push_back({item, withSize({"render", arg, "-o", "{out}/image.png", "--stats", "{out}/stats.json"})});
    } else if (kind == "replay" || kind == "crosscheck" || kind == "visibility") {
      const std::string v = stringField(c, "frame", w, true);
      expands = v == "*" || (!scenes::find(v) && hasGlobChars(v));
      for (const auto& [item, arg] : expandFrames(v, false, w, "frame", except)) {
        if (kind == "replay") {
          if (scenes::find(arg))
            w.fail("frame", "replay needs .tframe files, '" + arg + "' is a scene (use kind render)");
          items.push_back({item, {"replay", arg, "-o", "{out}/image.png", "--stats", "{out}/stats.json"}});
        } else if (kind == "crosscheck") {
          items.push_back({item, withGl(withSize({"crosscheck", arg, "--report", "{out}/report"}))});
        } else {
          items.push_back({item, withSize({"visibility", arg})});
        }
      }
    } else if (kind == "compare") {
      const std::string a = resolveFile(stringField(c, "a", w, true), w, "a");
      const std::string b = resolveFile(stringField(c, "b", w, true), w, "b");
      items.push_back({"", {"compare", a, b, "--report", "{out}/report"}});
    } else if (kind == "golden") {
      items.push_back({"", {"golden", "check"}});
    } else if (kind == "mutant") {
      const std::string m = stringField(c, "mutant", w, true);
      std::vector<std::string> v = {"mutants", "--mutants", m, "--report", "{out}/report"};
      if (c.contains("scenes")) v.insert(v.end(), {"--scenes", stringField(c, "scenes", w, true)});
      items.push_back({"", withGl(v)});
    }
    if (kind == "command") {
      if (!c.contains("steps") || !c["steps"].is_array() || c["steps"].empty())
        w.fail("steps", "must be a non-empty array of command lines (arrays of strings)");
      base.name = name;
      for (const json& step : c["steps"]) {
        std::vector<std::string> argv = stringList(step, w, "steps");
        if (argv.empty()) w.fail("steps", "a step must name a tessera command");
        base.steps.push_back(std::move(argv));
      }
      if (c.contains("gl") && !c["gl"].is_boolean()) w.fail("gl", "must be true or false");
      base.needsGl = c.value("gl", false);
      if (!names.insert(name).second) w.fail("name", "'" + name + "' is used by an earlier case");
      if (base.needsGl && !options.gl) continue;
      base.index = s.cases.size();
      s.cases.push_back(base);
      continue;
    }
    base.needsGl = kind == "crosscheck" || kind == "mutant";
    for (auto& [item, argv] : items) {
      SuiteCase sc = base;
      sc.name = expands ? name + "/" + item : name;
      if (!isValidCaseName(sc.name)) w.fail("name", "the expanded name '" + sc.name + "' is not a valid case name");
      if (!names.insert(sc.name).second) w.fail("name", "'" + sc.name + "' is used by an earlier case");
      argv.insert(argv.end(), extra.begin(), extra.end());
      sc.steps = {argv};
      if (sc.needsGl && !options.gl) continue;
      sc.index = s.cases.size();
      s.cases.push_back(std::move(sc));
    }
  }
  return s;
}

Fraction parseFraction(std::string_view text) {
  const std::string t(text);
  auto bad = [&](const std::string& why) { return Error("--fraction '" + t + "': " + why); };
  const size_t slash = t.find('/');
  if (slash == std::string::npos) throw bad("expected K/M (shard K of M, K from 1)");
  auto num = [&](std::string_view s) {
    if (s.empty() || s.size() > 9 || s.find_first_not_of("0123456789") != std::string_view::npos)
      throw bad("expected K/M with whole numbers (shard K of M, K from 1)");
    return size_t(std::stoul(std::string(s)));
  };
  Fraction f{num(std::string_view(t).substr(0, slash)), num(std::string_view(t).substr(slash + 1))};
  if (f.m < 1) throw bad("M must be at least 1");
  if (f.k < 1 || f.k > f.m)
    throw bad("K must be in 1.." + std::to_string(f.m) + " (K is 1-based, as GitLab's CI_NODE_INDEX)");
  return f;
}

std::vector<SuiteCase> selectFraction(const std::vector<SuiteCase>& cases, const Fraction& f) {
  std::vector<SuiteCase> out;
  for (const SuiteCase& c : cases)
    if (c.index % f.m == f.k - 1) out.push_back(c);
  return out;
}

}  // namespace tessera::cli::suite
