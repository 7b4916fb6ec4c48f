#include "verify/expectations.h"

#include <sched.h>

#include <algorithm>
#include <charconv>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>

#include "base/error.h"
#include "base/sha256.h"
#include "gl/gl_backend.h"
#include "raster/cpu_backend.h"
#include "raster/image_io.h"
#include "raster/serialize.h"
#include "verify/crosscheck.h"

namespace tessera::verify {

namespace {

std::optional<int64_t> parseInt(std::string_view s) {
  int64_t v = 0;
  const auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc() || p != s.data() + s.size() || s.empty()) return std::nullopt;
  return v;
}

}  // namespace

bool IntCondition::matches(int64_t v) const {
  switch (op) {
    case Op::Any: return true;
    case Op::Eq: return v == value;
    case Op::Ne: return v != value;
    case Op::Ge: return v >= value;
    case Op::Le: return v <= value;
    case Op::Gt: return v > value;
    case Op::Lt: return v < value;
  }
  return false;
}

std::string IntCondition::text() const {
  static const char* names[] = {"any", "==", "!=", ">=", "<=", ">", "<"};
  return op == Op::Any ? "any" : names[int(op)] + std::to_string(value);
}

IntCondition parseIntCondition(std::string_view text, const std::string& where) {
  IntCondition c;
  if (text == "any") return c;
  static const std::pair<std::string_view, IntCondition::Op> ops[] = {
      {"==", IntCondition::Op::Eq}, {"!=", IntCondition::Op::Ne}, {">=", IntCondition::Op::Ge},
      {"<=", IntCondition::Op::Le}, {">", IntCondition::Op::Gt},  {"<", IntCondition::Op::Lt}};
  std::string_view rest = text;
  c.op = IntCondition::Op::Eq;
  for (const auto& [prefix, op] : ops)
    if (rest.starts_with(prefix)) {
      c.op = op;
      rest.remove_prefix(prefix.size());
      break;
    }
  const auto v = parseInt(rest);
  if (!v)
    throw Error(where + ": '" + std::string(text) +
                "' is not a condition (expected any, N, ==N, !=N, >=N, <=N, >N or <N with an integer N)");
  c.value = *v;
  return c;
}

nlohmann::json RunCondition::toJson() const {
  return {{"implementation", implementation}, {"version", version}, {"strict", strict}, {"lp_threads", lpThreads}};
}

int defaultLpThreads() {
  if (const char* env = std::getenv("LP_NUM_THREADS"))
    if (const auto v = parseInt(env)) return int(*v);
  cpu_set_t set;
  CPU_ZERO(&set);
  int cpus = 1;
  if (sched_getaffinity(0, sizeof set, &set) == 0) cpus = std::max(1, CPU_COUNT(&set));
  return cpus > 1 ? cpus : 0;
}

RunCondition runConditionOf(const gl::GlBackend& gl) {
  RunCondition c;
  const gl::GlInfo& info = gl.info();
  // "llvmpipe (LLVM 15.0.6, 256 bits)" -> "llvmpipe"; "zink (...)" -> "zink".
  std::string first = info.renderer.substr(0, info.renderer.find_first_of(" ("));
  std::transform(first.begin(), first.end(), first.begin(), [](unsigned char ch) { return char(std::tolower(ch)); });
  c.implementation = first;
  c.version = info.mesaVersion;
  c.strict = gl.options().strict;
  c.lpThreads = defaultLpThreads();
  for (const auto& [name, value] : info.env)  // the value llvmpipe read when the display was initialised
    if (name == "LP_NUM_THREADS" && value)
      if (const auto v = parseInt(*value)) c.lpThreads = int(*v);
  return c;
}

std::vector<const Expectation*> ExpectationSet::matching(const RunCondition& run, std::string_view frame,
                                                         const CommandList* list) const {
  const std::string frameFile = std::filesystem::path(frame).filename().string();
  std::string listSha;  // computed once, for the first entry that asks
  std::vector<const Expectation*> out;
  for (const Expectation& e : entries) {
    if (e.implementation != run.implementation) continue;
    if (!std::regex_match(run.version, std::regex(e.versions))) continue;
    if (e.strict && *e.strict != run.strict) continue;
    if (!e.lpThreads.matches(run.lpThreads)) continue;
    const std::string entryFile = std::filesystem::path(e.frame).filename().string();
    if (e.frame != frame && !(e.frame.ends_with(".tframe") && entryFile == frameFile)) continue;
    if (!e.frameSha256.empty()) {
      if (!list) continue;
      if (listSha.empty()) listSha = sha256Hex(encodeFrame(*list));
      if (listSha != e.frameSha256) continue;
    }
    out.push_back(&e);
  }
  return out;
}

ExpectationSet parseExpectations(const nlohmann::json& doc, const std::string& file) {
  ExpectationSet set;
  set.file = file;
  if (!doc.is_object()) throw Error(file + ": the top level must be an object {\"schema\": 1, \"entries\": [...]}");
  for (const auto& [key, value] : doc.items())
    if (key != "schema" && key != "entries" && key != "comment")
      throw Error(file + ": unknown top-level field '" + key + "' (known: schema, entries, comment)");
  if (!doc.contains("schema") || doc["schema"] != 1) throw Error(file + ": field 'schema' must be 1");
  if (!doc.contains("entries") || !doc["entries"].is_array()) throw Error(file + ": field 'entries' must be an array");
  std::set<std::string> ids;
  size_t index = 0;
  for (const nlohmann::json& j : doc["entries"]) {
    std::string where = file + ": entry " + std::to_string(index++);
    if (!j.is_object()) throw Error(where + ": must be an object");
    static const std::set<std::string> known = {"id",    "implementation", "versions", "condition", "frame",
                                                "draw",  "pixels",         "reason",   "reproducer", "frame_sha256"};
    for (const auto& [key, value] : j.items())
      if (!known.count(key)) throw Error(where + ": unknown field '" + key + "'");
    auto str = [&](const char* name) {
      if (!j.contains(name) || !j[name].is_string() || j[name].get<std::string>().empty())
        throw Error(where + ": field '" + name + "' must be a non-empty string");
      return j[name].get<std::string>();
    };
    Expectation e;
    e.id = str("id");
    where += " (" + e.id + ")";
    if (!std::all_of(e.id.begin(), e.id.end(), [](char ch) {
          return (ch >= 'a' && ch <= 'z') || (ch >= '0' && ch <= '9') || ch == '_' || ch == '-';
        }))
      throw Error(where + ": field 'id' may hold only a-z, 0-9, '_' and '-' (it names the reproducer)");
    if (!ids.insert(e.id).second) throw Error(where + ": field 'id': duplicate id");
    e.implementation = str("implementation");
    e.versions = str("versions");
    try {
      (void)std::regex(e.versions);
    } catch (const std::regex_error& x) {
      throw Error(where + ": field 'versions': not a regular expression (" + x.what() + ")");
    }
    if (!j.contains("condition") || !j["condition"].is_object())
      throw Error(where + ": field 'condition' must be an object ({} = any condition)");
    for (const auto& [key, value] : j["condition"].items()) {
      if (key == "strict") {
        if (!value.is_boolean()) throw Error(where + ": field 'condition.strict' must be true or false");
        e.strict = value.get<bool>();
      } else if (key == "lp_threads") {
        if (!value.is_string()) throw Error(where + ": field 'condition.lp_threads' must be a string such as \">=2\"");
        e.lpThreads = parseIntCondition(value.get<std::string>(), where + ": field 'condition.lp_threads'");
      } else {
        throw Error(where + ": unknown field 'condition." + key + "' (known: strict, lp_threads)");
      }
    }
    e.frame = str("frame");
    if (j.contains("frame_sha256")) {
      e.frameSha256 = str("frame_sha256");
      if (e.frameSha256.size() != 64 || !std::all_of(e.frameSha256.begin(), e.frameSha256.end(), [](char ch) {
            return (ch >= '0' && ch <= '9') || (ch >= 'a' && ch <= 'f');
          }))
        throw Error(where + ": field 'frame_sha256' must be 64 lowercase hex digits (sha256sum of the .tframe)");
    }
    if (!j.contains("draw")) throw Error(where + ": field 'draw' is required (a draw index, or null for the frame)");
    if (!j["draw"].is_null()) {
      if (!j["draw"].is_number_integer() || j["draw"].get<int64_t>() < 0)
        throw Error(where + ": field 'draw' must be a draw index >= 0 or null");
      e.draw = j["draw"].get<size_t>();
    }
    if (!j.contains("pixels") || !j["pixels"].is_number_integer() || j["pixels"].get<int64_t>() <= 0)
      throw Error(where + ": field 'pixels' must be a pixel count > 0");
    e.pixels = j["pixels"].get<uint64_t>();
    e.reason = str("reason");
    e.reproducer = str("reproducer");
    if (!e.reproducer.ends_with(".tframe") || std::filesystem::path(e.reproducer).is_absolute())
      throw Error(where + ": field 'reproducer' must be a repository-relative .tframe path");
    set.entries.push_back(std::move(e));
  }
  return set;
}

ExpectationSet loadExpectations(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path + ": cannot read the expectations file");
  std::stringstream text;
  text << in.rdbuf();
  nlohmann::json doc;
  try {
    doc = nlohmann::json::parse(text.str());
  } catch (const nlohmann::json::parse_error& e) {
    throw Error(path + ": not JSON (" + e.what() + ")");
  }
  return parseExpectations(doc, path);
}

namespace {

// The presented images of an oracle render of `list` cut after command `end` (exclusive).
std::vector<std::vector<uint8_t>> prefixImages(const CommandList& list, size_t end, int threads,
                                               const ResourceLimits& limits) {
  CommandList prefix = list;
  prefix.truncate(end);
  CpuBackend b(RenderOptions{threads, false, limits});
  b.execute(prefix, "expectation mask");
  std::vector<std::vector<uint8_t>> out;
  for (const PresentedImage& p : b.presented()) out.push_back(imagePixels(*b.texture(p.texture), p.level, p.layer));
  return out;
}

// Per image, 1 where draw `draw` changes the oracle's pixel; empty masks when the draw does not exist
// or the prefixes present other images than the frame (then nothing is covered).
std::vector<std::vector<uint8_t>> drawMasks(const std::vector<ImageVerdict>& images, const CommandList& list,
                                            size_t draw, int threads, const ResourceLimits& limits) {
  std::vector<std::vector<uint8_t>> masks(images.size());
  size_t seen = 0, command = list.commands().size();
  for (size_t i = 0; i < list.commands().size(); ++i)
    if (std::holds_alternative<Draw>(list.commands()[i]) && seen++ == draw) {
      command = i;
      break;
    }
  if (command == list.commands().size()) return masks;
  const auto before = prefixImages(list, command, threads, limits);
  const auto after = prefixImages(list, command + 1, threads, limits);
  for (size_t i = 0; i < images.size(); ++i) {
    const size_t pixels = images[i].judgement.failMap.size();
    if (i >= before.size() || i >= after.size() || !pixels || before[i].size() != after[i].size() ||
        after[i].size() != images[i].oracle.size() || after[i].size() % pixels)
      continue;
    const size_t bpp = after[i].size() / pixels;
    masks[i].assign(pixels, 0);
    for (size_t p = 0; p < pixels; ++p)
      masks[i][p] = !std::equal(before[i].begin() + p * bpp, before[i].begin() + (p + 1) * bpp, after[i].begin() + p * bpp);
  }
  return masks;
}

}  // namespace

std::vector<ExpectationUse> applyExpectations(std::vector<ImageVerdict>& images, const CommandList& list,
                                              const std::vector<const Expectation*>& entries, int threads,
                                              const ResourceLimits& limits) {
  std::vector<ExpectationUse> uses;
  for (const Expectation* e : entries) {
    ExpectationUse use;
    use.entry = e;
    std::vector<std::vector<uint8_t>> masks;
    if (e->draw) {
      masks = drawMasks(images, list, *e->draw, threads, limits);
    } else {
      for (const ImageVerdict& v : images) masks.emplace_back(v.judgement.failMap.size(), uint8_t(1));
    }
    for (size_t i = 0; i < images.size(); ++i) {
      const auto& fail = images[i].judgement.failMap;
      for (size_t p = 0; p < masks[i].size(); ++p) {
        use.maskPixels += masks[i][p];
        use.matched += masks[i][p] && fail[p] == 2;
      }
    }
    use.covered = use.matched <= e->pixels;
    if (use.covered && use.matched) {
      for (size_t i = 0; i < images.size(); ++i) {
        Judgement& j = images[i].judgement;
        for (size_t p = 0; p < masks[i].size(); ++p)
          if (masks[i][p] && j.failMap[p] == 2) {
            j.failMap[p] = 3;
            --j.unexplained;
            ++images[i].expectedDeviation;
          }
        std::erase_if(j.firstUnexplained, [&](const PixelRecord& r) {
          const size_t p = size_t(r.y) * size_t(j.width) + size_t(r.x);
          return p < j.failMap.size() && j.failMap[p] == 3;
        });
      }
    }
    uses.push_back(use);
  }
  return uses;
}

nlohmann::json toJson(const std::vector<ExpectationUse>& uses) {
  nlohmann::json a = nlohmann::json::array();
  for (const ExpectationUse& u : uses)
    a.push_back({{"id", u.entry->id},
                 {"frame", u.entry->frame},
                 {"draw", u.entry->draw ? nlohmann::json(*u.entry->draw) : nlohmann::json(nullptr)},
                 {"pixels_allowed", u.entry->pixels},
                 {"mask_pixels", u.maskPixels},
                 {"unexplained_in_mask", u.matched},
                 {"covered", u.covered},
                 {"reason", u.entry->reason},
                 {"reproducer", u.entry->reproducer}});
  return a;
}

}  // namespace tessera::verify
