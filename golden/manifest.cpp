#include "golden/manifest.h"

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "base/atomic_file.h"
#include "base/error.h"
#include "raster/types.h"

namespace tessera::golden {

namespace {

using nlohmann::json;

const char* kindName(const json& v) {
  if (v.is_number_unsigned()) return "an unsigned integer";
  if (v.is_number_integer()) return "a negative integer";
  if (v.is_number_float()) return "a fractional number";
  if (v.is_string()) return "a string";
  if (v.is_array()) return "an array";
  if (v.is_object()) return "an object";
  if (v.is_boolean()) return "a boolean";
  return "null";
}

// Reads the fields of one JSON object, naming "<path>: <where>.<field>" in every error.
class Fields {
 public:
  Fields(const json& object, const std::string& path, std::string where)
      : object_(object), path_(path), where_(std::move(where)) {}

  [[noreturn]] void fail(const std::string& field, const std::string& reason) const {
    const std::string name = where_.empty() ? field : field.empty() ? where_ : where_ + "." + field;
    throw Error(path_ + ": " + name + ": " + reason);
  }
  const json& get(const char* field) {
    seen_.insert(field);
    const auto it = object_.find(field);
    if (it == object_.end()) fail(field, "missing");
    return *it;
  }
  std::string string(const char* field) {
    const json& v = get(field);
    if (!v.is_string()) fail(field, std::string("expected a string, found ") + kindName(v));
    return v.get<std::string>();
  }
  uint32_t unsignedInt(const char* field, uint32_t min) {
    const json& v = get(field);
    if (!v.is_number_unsigned() || v.get<uint64_t>() > UINT32_MAX)
      fail(field, std::string("expected an unsigned 32-bit integer, found ") +
                      (v.is_number_unsigned() ? v.dump() : kindName(v)));
    const uint32_t u = v.get<uint32_t>();
    if (u < min) fail(field, "must be at least " + std::to_string(min) + ", found " + std::to_string(u));
    return u;
  }
  // Unknown fields would be lost when the manifest is written back.
  void noOthers() const {
    for (auto it = object_.begin(); it != object_.end(); ++it)
      if (!seen_.count(it.key())) fail(it.key(), "unknown field");
  }

 private:
  const json& object_;
  const std::string& path_;
  std::string where_;
  std::set<std::string> seen_;
};

bool isLowerHex(const std::string& s) {
  for (char c : s)
    if (!((c >= '0' && c <= '9') || (c >= 'a' && c <= 'f'))) return false;
  return true;
}

bool isFormatName(const std::string& s) {
  for (int f = 0; f < kFormatCount; ++f)
    if (formatName(Format(f)) == s) return true;
  return false;
}

ManifestEntry parseEntry(const json& v, const std::string& path, const std::string& name) {
  Fields f(v, path, "tests[\"" + name + "\"]");
  if (!v.is_object()) f.fail("", std::string("expected an object, found ") + kindName(v));
  ManifestEntry e;
  e.file = f.string("file");
  const std::filesystem::path file(e.file);
  if (e.file.empty() || file.is_absolute())
    f.fail("file", "expected a path relative to the golden directory, found '" + e.file + "'");
  for (const auto& part : file)
    if (part == "..") f.fail("file", "'" + e.file + "' leaves the golden directory");
  e.imageSha256 = f.string("image_sha256");
  if (e.imageSha256.size() != 64 || !isLowerHex(e.imageSha256))
    f.fail("image_sha256", "expected 64 lower-case hex digits, found '" + e.imageSha256 + "'");
  e.format = f.string("format");
  if (!isFormatName(e.format)) f.fail("format", "unknown format '" + e.format + "'");
  e.width = f.unsignedInt("width", 1);
  e.height = f.unsignedInt("height", 1);
  e.scene = f.string("scene");
  if (e.scene.empty()) f.fail("scene", "empty");
  e.attachment = f.unsignedInt("attachment", 0);
  e.layer = f.unsignedInt("layer", 0);
  e.command = f.string("command");
  f.noOthers();
  return e;
}

json entryJson(const ManifestEntry& e) {
  return {{"file", e.file},
          {"image_sha256", e.imageSha256},
          {"format", e.format},
          {"width", e.width},
          {"height", e.height},
          {"scene", e.scene},
          {"attachment", e.attachment},
          {"layer", e.layer},
          {"command", e.command}};
}

}  // namespace

Manifest parseManifest(const std::string& text, const std::string& path) {
  json j;
  try {
    j = json::parse(text);
  } catch (const json::parse_error& e) {
    throw Error(path + ": not JSON: " + e.what());
  }
  if (!j.is_object())
    throw Error(path + ": expected a JSON object with \"version\" and \"tests\", found " + kindName(j));
  Fields top(j, path, "");
  Manifest m;
  const json& version = top.get("version");
  if (!version.is_number_integer() || version.get<int64_t>() != 1)
    top.fail("version", "expected 1 (the only manifest version), found " + version.dump());
  m.version = 1;
  const json& tests = top.get("tests");
  if (!tests.is_object()) top.fail("tests", std::string("expected an object, found ") + kindName(tests));
  top.noOthers();
  for (auto it = tests.begin(); it != tests.end(); ++it)
    m.tests.emplace(it.key(), parseEntry(it.value(), path, it.key()));
  return m;
}

Manifest readManifest(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path + ": cannot open");
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw Error(path + ": read error");
  return parseManifest(text.str(), path);
}

Manifest loadManifest(const std::string& dir) {
  const std::string path = dir + "/manifest.json";
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) return Manifest{};
  return readManifest(path);
}

std::string manifestText(const Manifest& m) {
  json tests = json::object();
  for (const auto& [name, e] : m.tests) tests[name] = entryJson(e);
  const json j = {{"version", m.version}, {"tests", tests}};
  return j.dump(2) + "\n";
}

void writeManifest(const std::string& path, const Manifest& m) { writeFileAtomically(path, manifestText(m)); }

}  // namespace tessera::golden
