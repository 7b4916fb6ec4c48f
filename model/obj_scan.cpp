#include "model/obj_scan.h"

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <set>
#include <string_view>

#include "base/error.h"
#include "model/loaders.h"

namespace tessera::model::detail {

namespace {

namespace fs = std::filesystem;

bool isSpace(char c) { return c == ' ' || c == '\t'; }                  // tinyobjloader's IS_SPACE
bool isNewLine(char c) { return c == '\r' || c == '\n' || c == '\0'; }  // tinyobjloader's IS_NEW_LINE

// Calls f(lineNumber, line) for every line, split as tinyobjloader's safeGetline splits them (at "\n",
// "\r\n" or "\r"). A line is cut at a NUL byte, as tinyobjloader reads it through c_str().
template <class F>
void forEachLine(std::string_view text, F&& f) {
  size_t line = 0, at = 0;
  while (at < text.size()) {
    size_t end = at;
    while (end < text.size() && text[end] != '\n' && text[end] != '\r') ++end;
    std::string_view l = text.substr(at, end - at);
    if (const size_t nul = l.find('\0'); nul != std::string_view::npos) l = l.substr(0, nul);
    f(++line, l);
    if (end == text.size()) break;
    at = end + 1;
    if (text[end] == '\r' && at < text.size() && text[at] == '\n') ++at;
  }
}

// The statement keyword of a line, as tinyobjloader recognizes it: `word` followed by a space or tab
// after the leading blanks. Returns the rest after that one blank, or nullptr.
const char* statement(const char* token, const char* word) {
  const size_t n = std::strlen(word);
  if (std::strncmp(token, word, n) != 0 || !isSpace(token[n])) return nullptr;
  return token + n + 1;
}

class Scanner {
 public:
  Scanner(const std::string& path, ObjScan& out) : path_(path), out_(out) {}

  [[noreturn]] void fail(size_t line, const std::string& why) const {
    throw Error(path_ + ":" + std::to_string(line) + ": " + why);
  }

  void line(size_t number, std::string_view text) {
    const std::string copy(text);  // NUL-terminated, as tinyobjloader parses it
    const char* token = copy.c_str() + std::strspn(copy.c_str(), " \t");
    if (token[0] == 'v' && isSpace(token[1])) {
      ++count_[0];
    } else if (token[0] == 'v' && token[1] == 't' && isSpace(token[2])) {
      ++count_[1];
    } else if (token[0] == 'v' && token[1] == 'n' && isSpace(token[2])) {
      ++count_[2];
    } else if (const char* l = statement(token, "l")) {
      corners(number, "l", l);
    } else if (const char* p = statement(token, "p")) {
      corners(number, "p", p);
    } else if (const char* f = statement(token, "f")) {
      const uint64_t k = corners(number, "f", f + std::strspn(f, " \t"));
      if (k >= 3) out_.triangles = saturatingAdd(out_.triangles, k - 2);
      if (k > 4) {
        work_ = saturatingAdd(work_, saturatingMul(k, k));
        if (work_ > kTriangulationWork)
          fail(number, "f: a face of " + std::to_string(k) +
                           " corners; triangulating the file's polygons would take more than " +
                           std::to_string(kTriangulationWork) + " steps (about k^2 per face of k corners)");
      }
    } else if (const char* names = statement(token, "mtllib")) {
      mtllib(number, names);
    }
  }

  // Indices past the end of the file's v / vt / vn, found once every line is counted.
  void finish() const {
    for (int kind = 0; kind < 3; ++kind)
      for (const Forward& f : forward_[kind])
        if (f.index > count_[kind])
          fail(f.line, std::string(f.statement) + ": " + kKind[kind] + " index " + std::to_string(f.index) +
                           " does not exist: the file has " + std::to_string(count_[kind]) + " " + kStatement[kind]);
  }

 private:
  static constexpr const char* kKind[3] = {"vertex", "texcoord", "normal"};
  static constexpr const char* kStatement[3] = {"v", "vt", "vn"};

  // One index as tinyobjloader reads it: atoi at `token` (blanks, a sign, digits), then `token` moves
  // to the next '/', blank or '\r'. Checked here; `kind` 0 = v, 1 = vt, 2 = vn.
  void index(size_t number, const char* stmt, const char*& token, int kind) {
    const char* p = token;
    while (*p == ' ' || (*p >= '\t' && *p <= '\r')) ++p;  // atoi skips isspace
    const char* sign = p;
    const bool negative = *p == '-';
    if (*p == '+' || *p == '-') ++p;
    const char* digits = p;
    uint64_t v = 0;
    for (; *p >= '0' && *p <= '9'; ++p) v = std::min<uint64_t>(v * 10 + uint64_t(*p - '0'), uint64_t(1) << 32);
    token += std::strcspn(token, "/ \t\r");
    const std::string what = std::string(stmt) + ": " + kKind[kind] + " index ";
    if (p == digits) {
      const std::string written(sign, size_t(std::max(token, sign) - sign));
      fail(number, what + "missing" + (written.empty() ? "" : " ('" + shorten(written) + "' is not a number)"));
    }
    const std::string written(sign, size_t(p - sign));
    if (v > uint64_t(INT32_MAX)) fail(number, what + shorten(written) + " does not fit in 32 bits");
    if (v == 0) fail(number, what + "0 (OBJ indices start at 1)");
    if (negative) {  // relative to the elements defined so far
      if (v > count_[kind])
        fail(number, what + written + " reaches before the first " + kStatement[kind] + " (" +
                         std::to_string(count_[kind]) + " defined so far)");
    } else if (v > count_[kind]) {  // may be defined further down
      forward_[kind].push_back({number, stmt, v});
    }
  }

  // The corners of an f / l / p statement, parsed as tinyobjloader's parseTriple does: i, i/j, i//k, i/j/k.
  uint64_t corners(size_t number, const char* stmt, const char* token) {
    uint64_t k = 0;
    while (!isNewLine(token[0])) {
      index(number, stmt, token, 0);
      if (token[0] == '/') {
        ++token;
        if (token[0] == '/') {
          ++token;
          index(number, stmt, token, 2);
        } else {
          index(number, stmt, token, 1);
          if (token[0] == '/') {
            ++token;
            index(number, stmt, token, 2);
          }
        }
      }
      ++k;
      token += std::strspn(token, " \t\r");
    }
    return k;
  }

  // mtllib: the names as tinyobjloader splits them (at spaces, '\' escaping the next character), each
  // resolved beside the OBJ, and read.
  void mtllib(size_t number, const char* rest) {
    std::vector<std::string> names;
    std::string name;
    bool escaping = false;
    for (const char* p = rest; *p; ++p) {
      if (escaping) {
        escaping = false;
      } else if (*p == '\\') {
        escaping = true;
        continue;
      } else if (*p == ' ') {
        names.push_back(name), name.clear();
        continue;
      }
      name += *p;
    }
    names.push_back(name);
    bool any = false;
    for (std::string& n : names) {
      n.erase(0, n.find_first_not_of(" \t"));
      n.erase(n.find_last_not_of(" \t") + 1);
      if (n.empty()) continue;
      any = true;
      const std::string resolved = resolveBeside(path_, n);
      std::error_code ec;
      if (fs::exists(resolved, ec) && fs::equivalent(resolved, path_, ec))
        fail(number, "mtllib '" + shorten(n) + "' names this OBJ file itself, not a material library");
      if (!fs::is_regular_file(resolved, ec))
        fail(number, "mtllib '" + shorten(n) + "': material library '" + resolved + "' " +
                         (fs::exists(resolved, ec) ? "is not a regular file" : "does not exist"));
      const std::string key = fs::weakly_canonical(resolved, ec).string();
      if (!seen_.insert(key.empty() ? resolved : key).second) continue;
      out_.libraries.push_back({resolved, readLibrary(resolved)});
    }
    if (!any) fail(number, "mtllib names no file");
  }

  static std::string readLibrary(const std::string& path) {
    std::ifstream f(path, std::ios::binary);
    if (!f) throw Error(path + ": cannot open the material library for reading");
    std::string text((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
    // Material libraries have no include statement; an OBJ statement there is a mistake, and a library
    // naming itself or another one would be expected to be read, which tinyobjloader (rightly) does not.
    forEachLine(text, [&](size_t number, std::string_view l) {
      const std::string s(l);
      if (statement(s.c_str() + std::strspn(s.c_str(), " \t"), "mtllib"))
        throw Error(path + ":" + std::to_string(number) +
                    ": mtllib inside a material library (an MTL file cannot include other files)");
    });
    return text;
  }

  static std::string shorten(const std::string& s) { return s.size() <= 40 ? s : s.substr(0, 37) + "..."; }

  struct Forward {
    size_t line;
    const char* statement;
    uint64_t index;
  };
  const std::string& path_;
  ObjScan& out_;
  uint64_t count_[3] = {0, 0, 0};    // v, vt, vn so far
  std::vector<Forward> forward_[3];  // positive indices past the count at their line
  uint64_t work_ = 0;
  std::set<std::string> seen_;
};

}  // namespace

ObjScan scanObj(const std::string& path, const std::string& text) {
  ObjScan out;
  Scanner s(path, out);
  forEachLine(text, [&](size_t number, std::string_view l) { s.line(number, l); });
  s.finish();
  return out;
}

}  // namespace tessera::model::detail
