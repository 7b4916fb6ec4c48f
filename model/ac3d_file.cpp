#include "model/ac3d_file.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>

#include "base/error.h"

namespace tessera::model::detail::ac3d {

std::string shown(std::string_view t) {
  std::string s(t.substr(0, 40));
  for (char& c : s)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
  return t.size() > 40 ? s + "..." : s;
}

std::string Object::label() const { return "object '" + shown(name) + "' (line " + std::to_string(line) + ")"; }

namespace {

// One line split at blanks; a token in double quotes may hold blanks and is given without its quotes.
struct Line {
  size_t number = 0;
  std::vector<std::string_view> tokens;
  size_t size() const { return tokens.size(); }
  std::string_view operator[](size_t i) const { return i < tokens.size() ? tokens[i] : std::string_view(); }
};

class Reader {
 public:
  Reader(const std::string& path, std::string_view text) : path_(path), text_(text) {}

  // The next line that holds a token; false at the end of the file.
  bool next(Line& line) {
    while (pos_ < text_.size()) {
      size_t end = text_.find('\n', pos_);
      if (end == std::string_view::npos) end = text_.size();
      const std::string_view raw = text_.substr(pos_, end - pos_);
      pos_ = end < text_.size() ? end + 1 : end;
      ++lineNo_;
      split(raw, line.tokens);
      if (!line.tokens.empty()) {
        line.number = lineNo_;
        return true;
      }
    }
    return false;
  }

  // Bytes after the last line next() returned.
  uint64_t remaining() const { return text_.size() - pos_; }

  // Skips the `n` bytes of a `data` section that start after the data line, then the rest of the line
  // they end in, if they do not end with a line end. Returns false when that rest was not blank (the
  // count was short). Precondition: n <= remaining().
  bool skipData(uint64_t n) {
    if (n == 0) return true;
    const std::string_view data = text_.substr(pos_, n);
    lineNo_ += size_t(std::count(data.begin(), data.end(), '\n'));
    pos_ += n;
    if (text_[pos_ - 1] == '\n') return true;  // the count took the line end too
    size_t end = text_.find('\n', pos_);
    if (end == std::string_view::npos) end = text_.size();
    const std::string_view rest = text_.substr(pos_, end - pos_);
    pos_ = end < text_.size() ? end + 1 : end;
    ++lineNo_;
    return rest.find_first_not_of(" \t\r\v\f") == std::string_view::npos;
  }

  [[noreturn]] void fail(size_t line, const std::string& why) const {
    throw Error(path_ + ":" + std::to_string(line) + ": " + why);
  }

 private:
  void split(std::string_view s, std::vector<std::string_view>& out) const {
    out.clear();
    auto blank = [](char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; };
    size_t i = 0;
    while (i < s.size()) {
      if (blank(s[i])) {
        ++i;
      } else if (s[i] == '"') {
        const size_t close = s.find('"', i + 1);
        if (close == std::string_view::npos) fail(lineNo_, "a string opened with \" is not closed on its line");
        out.push_back(s.substr(i + 1, close - i - 1));
        i = close + 1;
      } else {
        const size_t start = i;
        while (i < s.size() && !blank(s[i])) ++i;
        out.push_back(s.substr(start, i - start));
      }
    }
  }

  const std::string& path_;
  std::string_view text_;
  size_t pos_ = 0, lineNo_ = 0;
};

class Parser {
 public:
  Parser(const std::string& path, std::string_view text, const ResourceLimits& limits, File& file)
      : materials_(file.materials),
        objects_(file.objects),
        path_(path),
        text_(text),
        r_(path, text),
        limits_(limits),
        tally_(file.tally) {}

  void run() {
    header();
    struct Frame {
      int32_t object;
      uint64_t kidsLeft;
    };
    std::vector<Frame> open;  // objects whose kids are being read, innermost last (at most graphDepth)
    Line l;
    while (r_.next(l)) {
      if (l[0] == "MATERIAL") {
        material(l);
      } else if (l[0] == "MAT") {
        materialBlock(l);
      } else if (l[0] == "OBJECT") {
        int32_t parent = -1;
        if (!open.empty()) {
          parent = open.back().object;
          if (--open.back().kidsLeft == 0) open.pop_back();
        }
        const uint64_t kids = object(l, parent);
        if (kids > 0) open.push_back({int32_t(objects_.size() - 1), kids});
      } else {
        unknown(l);
      }
    }
    if (!open.empty())
      throw Error(path_ + ": the file ends before the last " + std::to_string(open.back().kidsLeft) + " kids of " +
                  objects_[size_t(open.back().object)].label());
    if (objects_.empty()) throw Error(path_ + ": no OBJECT in the file");
  }

 private:
  void header() {
    if (text_.substr(0, 4) != "AC3D") throw Error(path_ + ": not an AC3D file (it does not start with AC3D)");
    const char v = text_.size() > 4 ? text_[4] : '\n';
    if (!std::isxdigit(static_cast<unsigned char>(v)))
      throw Error(path_ + ":1: the header needs a hex version digit after AC3D (AC3Db, AC3Dc), not '" +
                  shown(std::string_view(&v, 1)) + "'");
    const int version = std::isdigit(static_cast<unsigned char>(v)) ? v - '0' : std::tolower(v) - 'a' + 10;
    if (version > 12) tally_.newerVersion = version;
    Line l;
    r_.next(l);  // the header line; anything after the version is ignored
  }

  void material(const Line& l) {
    Material m;
    size_t i = 1;
    if (l.size() > 1 && l[1] != "rgb") m.name = std::string(l[1]), i = 2;
    bool rgb = false;
    while (i < l.size()) {
      const std::string_view key = l[i];
      if (key == "rgb" || key == "amb" || key == "emis" || key == "spec") {
        const glm::vec3 c{real(l, i + 1, key), real(l, i + 2, key), real(l, i + 3, key)};  // braces: read in order
        if (key == "rgb") m.rgb = c, rgb = true;
        i += 4;
      } else if (key == "shi" || key == "trans") {
        const float f = real(l, i + 1, key);
        if (key == "trans") m.trans = f;
        i += 2;
      } else {
        note("MATERIAL field '" + shown(key) + "' (the rest of its line)", l.number);
        break;
      }
    }
    if (!rgb) r_.fail(l.number, "MATERIAL '" + shown(m.name) + "' has no rgb colour");
    materials_.push_back(std::move(m));
  }

  // AC3Dc's block form: MAT name, then rgb / amb / emis / spec / shi / trans / data lines, then ENDMAT.
  void materialBlock(const Line& head) {
    Material m;
    m.name = std::string(head[1]);
    bool rgb = false;
    Line l;
    for (;;) {
      if (!r_.next(l)) r_.fail(head.number, "the file ends inside this MAT block (no ENDMAT)");
      const std::string_view key = l[0];
      if (key == "ENDMAT") break;
      if (key == "rgb" || key == "amb" || key == "emis" || key == "spec") {
        const glm::vec3 c{real(l, 1, key), real(l, 2, key), real(l, 3, key)};
        if (key == "rgb") m.rgb = c, rgb = true;
      } else if (key == "shi" || key == "trans") {
        const float f = real(l, 1, key);
        if (key == "trans") m.trans = f;
      } else if (key == "data") {
        data(l);
      } else {
        unknown(l);
      }
    }
    if (!rgb) r_.fail(head.number, "MAT '" + shown(m.name) + "' has no rgb colour");
    materials_.push_back(std::move(m));
  }

  // Reads an OBJECT up to and including its kids line, appends it, and returns its kid count.
  uint64_t object(const Line& head, int32_t parent) {
    if (objects_.size() >= size_t(INT32_MAX)) r_.fail(head.number, "more than 2^31 - 1 objects");
    Object o;
    o.line = head.number;
    o.parent = parent;
    o.depth = parent < 0 ? 1 : objects_[size_t(parent)].depth + 1;
    std::string type(head[1]);
    std::transform(type.begin(), type.end(), type.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    if (type.empty()) r_.fail(head.number, "OBJECT needs a type (world, poly, group or light)");
    if (type == "light") ++tally_.lights;
    if (type != "world" && type != "poly" && type != "group" && type != "light") ++tally_.unknownObjectTypes;
    Line l;
    for (;;) {
      if (!r_.next(l)) r_.fail(o.line, "the file ends inside this OBJECT, before its kids line");
      const std::string_view key = l[0];
      if (key == "kids") {
        const uint64_t kids = count(l, 1, "kids");
        fits(l, kids, "kids");
        if (kids > 0 && o.depth >= limits_.graphDepth)
          r_.fail(l.number, "kids nest deeper than " + std::to_string(limits_.graphDepth) +
                                " levels (the graph depth limit, docs/limits.md)");
        if (o.normals.size() != o.vertices.size()) o.normals.clear();
        if (o.mixedNormals) ++tally_.mixedNormals;
        objects_.push_back(std::move(o));
        return kids;
      } else if (key == "name") {
        o.name = std::string(text(l, 1, "name"));
      } else if (key == "data") {
        data(l);
      } else if (key == "texture") {
        texture(l, o);
      } else if (key == "texrep") {
        o.texRep = {real(l, 1, key), real(l, 2, key)};
      } else if (key == "texoff") {
        o.texOff = {real(l, 1, key), real(l, 2, key)};
      } else if (key == "rot") {
        for (int k = 0; k < 9; ++k) o.rot[k % 3][k / 3] = real(l, size_t(k) + 1, key);
      } else if (key == "loc") {
        o.loc = {real(l, 1, key), real(l, 2, key), real(l, 3, key)};
      } else if (key == "crease") {
        real(l, 1, key);  // a smoothing angle; no normals are made here
      } else if (key == "subdiv") {
        if (count(l, 1, key) > 0) ++tally_.subdiv;
      } else if (key == "url" || key == "hidden" || key == "locked" || key == "folded") {
        // editor state and a link: nothing to render
      } else if (key == "numvert") {
        vertices(l, o);
      } else if (key == "numsurf") {
        surfaces(l, o);
      } else if (key == "OBJECT" || key == "MATERIAL" || key == "MAT") {
        r_.fail(o.line,
                "this OBJECT has no kids line before the " + std::string(key) + " at line " + std::to_string(l.number));
      } else {
        unknown(l);
      }
    }
  }

  // TORCS writes `texture "x" base` and then the layers `tiled`, `skids` and `shad`; only the base is a
  // colour texture. A plain texture line (AC3D) is the base too; the last one given wins.
  void texture(const Line& l, Object& o) {
    const std::string_view file = text(l, 1, "texture"), kind = l[2];
    if (kind.empty() || kind == "base") {
      o.texture = file == "empty_texture_no_mapping" ? std::string() : std::string(file);  // TORCS: no texture
      o.textureLine = l.number;
    } else if (kind == "tiled" || kind == "skids" || kind == "shad") {
      ++tally_.layers;
    } else {
      note("texture kind '" + shown(kind) + "'", l.number);
    }
  }

  void vertices(const Line& l, Object& o) {
    if (o.sawNumvert) r_.fail(l.number, "a second numvert in " + o.label());
    o.sawNumvert = true;
    const uint64_t n = count(l, 1, "numvert");
    fits(l, n, "numvert");
    if (n > UINT32_MAX) r_.fail(l.number, "numvert " + std::to_string(n) + " is more than 2^32 - 1 vertices");
    o.vertices.reserve(size_t(n));
    Line v;
    for (uint64_t i = 0; i < n; ++i) {
      if (!r_.next(v))
        r_.fail(l.number, "the file ends after " + std::to_string(i) + " of these " + std::to_string(n) + " vertices");
      if (v.size() != 3 && v.size() != 6)
        r_.fail(v.number, "a vertex line holds 3 numbers (6 with a normal), not " + std::to_string(v.size()) +
                              " (vertex " + std::to_string(i) + " of numvert " + std::to_string(n) + " at line " +
                              std::to_string(l.number) + ")");
      o.vertices.push_back(glm::vec3{real(v, 0, "vertex x"), real(v, 1, "vertex y"), real(v, 2, "vertex z")});
      if (v.size() == 6 && o.normals.size() == i)
        o.normals.push_back(glm::vec3{real(v, 3, "normal x"), real(v, 4, "normal y"), real(v, 5, "normal z")});
      else if (v.size() == 6 || !o.normals.empty())
        o.mixedNormals = true;
    }
  }

  void surfaces(const Line& l, Object& o) {
    const uint64_t n = count(l, 1, "numsurf");
    fits(l, n, "numsurf");
    Line s, x;
    for (uint64_t i = 0; i < n; ++i) {
      if (!r_.next(s))
        r_.fail(l.number, "the file ends after " + std::to_string(i) + " of these " + std::to_string(n) + " surfaces");
      if (s[0] != "SURF")
        r_.fail(s.number, "expected SURF (surface " + std::to_string(i) + " of numsurf " + std::to_string(n) +
                              " at line " + std::to_string(l.number) + "), not '" + shown(s[0]) + "'");
      Surface sf;
      sf.line = s.number;
      sf.flags = flags(s);
      for (;;) {
        if (!r_.next(x)) r_.fail(sf.line, "the file ends inside this SURF, before its refs line");
        const std::string_view key = x[0];
        if (key == "mat") {
          sf.mat = count(x, 1, "mat");
          sf.matLine = x.number;
        } else if (key == "refs") {
          refs(x, o, sf);
          break;
        } else if (key == "SURF" || key == "kids" || key == "OBJECT" || key == "numvert" || key == "numsurf") {
          r_.fail(sf.line,
                  "this SURF has no refs line before the " + std::string(key) + " at line " + std::to_string(x.number));
        } else {
          unknown(x);
        }
      }
      if (!sf.isLine() && sf.refCount >= 3) o.triangles += sf.refCount - 2;
      o.surfaces.push_back(sf);
    }
  }

  // refs n, then n lines "vertex u v" (TORCS: further u v pairs, one per texture layer; the first is
  // the base texture's). A line with the index alone has texcoord (0, 0).
  void refs(const Line& l, Object& o, Surface& sf) {
    const uint64_t n = count(l, 1, "refs");
    fits(l, n, "refs");
    sf.firstRef = o.refs.size();
    sf.refCount = size_t(n);
    Line x;
    for (uint64_t i = 0; i < n; ++i) {
      if (!r_.next(x))
        r_.fail(l.number, "the file ends after " + std::to_string(i) + " of these " + std::to_string(n) + " refs");
      if (x.size() % 2 == 0)
        r_.fail(x.number,
                "a refs line holds a vertex index and u v pairs, not " + std::to_string(x.size()) + " numbers");
      const uint64_t index = count(x, 0, "refs vertex index");
      if (index >= o.vertices.size())
        r_.fail(x.number, "refs index " + std::to_string(index) + " is past the " + std::to_string(o.vertices.size()) +
                              " vertices of " + o.label());
      Ref r;
      r.vertex = uint32_t(index);
      if (x.size() >= 3) r.u = real(x, 1, "u"), r.v = real(x, 2, "v");
      for (size_t k = 3; k < x.size(); ++k) real(x, k, "layer texcoord");
      o.refs.push_back(r);
    }
  }

  void data(const Line& l) {
    const uint64_t n = count(l, 1, "data");
    if (n > r_.remaining())
      r_.fail(l.number, "data " + std::to_string(n) + " is longer than the " + std::to_string(r_.remaining()) +
                            " bytes that follow");
    if (!r_.skipData(n)) ++tally_.shortData;
  }

  // A count that announces lines must fit in the rest of the file, at 2 bytes a line at least; this
  // is checked before anything is reserved for them.
  void fits(const Line& l, uint64_t n, std::string_view what) {
    if (n > r_.remaining() / 2)
      r_.fail(l.number, std::string(what) + " " + std::to_string(n) + " cannot fit in the " +
                            std::to_string(r_.remaining()) + " bytes that follow (a line takes 2 at least)");
  }

  std::string_view text(const Line& l, size_t i, std::string_view what) {
    if (i >= l.size()) r_.fail(l.number, std::string(what) + " needs a value");
    return l[i];
  }

  float real(const Line& l, size_t i, std::string_view what) {
    const std::string_view t = text(l, i, what);
    const char* b = t.data();
    const char* e = b + t.size();
    if (b != e && *b == '+' && b + 1 != e && (std::isdigit(static_cast<unsigned char>(b[1])) || b[1] == '.')) ++b;
    float v = 0.0f;
    auto res = std::from_chars(b, e, v);
    if (res.ec == std::errc::result_out_of_range) {  // too large for float, or below its smallest normal
      double d = 0.0;
      const auto dres = std::from_chars(b, e, d);
      if (dres.ec != std::errc() || dres.ptr != e || !(std::fabs(d) < 1.0))
        r_.fail(l.number, std::string(what) + ": '" + shown(t) + "' is outside the range of a float");
      v = float(d), res.ptr = e, res.ec = std::errc();
    }
    if (res.ec != std::errc() || res.ptr != e)
      r_.fail(l.number, std::string(what) + ": '" + shown(t) + "' is not a number");
    if (!std::isfinite(v)) r_.fail(l.number, std::string(what) + ": '" + shown(t) + "' is not a finite number");
    return v;
  }

  uint64_t count(const Line& l, size_t i, std::string_view what) {
    const std::string_view t = text(l, i, what);
    uint64_t v = 0;
    const auto res = std::from_chars(t.data(), t.data() + t.size(), v);
    if (res.ec == std::errc::result_out_of_range)
      r_.fail(l.number, std::string(what) + " " + shown(t) + " is too large");
    if (res.ec != std::errc() || res.ptr != t.data() + t.size())
      r_.fail(l.number, std::string(what) + ": '" + shown(t) + "' is not a whole number >= 0");
    return v;
  }

  // SURF flags as C writes integers (0x hex, leading 0 octal, else decimal), as AC3D readers parse them.
  uint32_t flags(const Line& l) {
    std::string_view t = text(l, 1, "SURF");
    int base = 10;
    if (t.size() > 2 && t[0] == '0' && (t[1] == 'x' || t[1] == 'X'))
      t.remove_prefix(2), base = 16;
    else if (t.size() > 1 && t[0] == '0')
      t.remove_prefix(1), base = 8;
    uint64_t v = 0;
    const auto res = std::from_chars(t.data(), t.data() + t.size(), v, base);
    if (res.ec != std::errc() || res.ptr != t.data() + t.size() || v > UINT32_MAX)
      r_.fail(l.number, "SURF: '" + shown(l[1]) + "' is not a flag word (such as 0x10)");
    return uint32_t(v);
  }

  void unknown(const Line& l) { note("unknown token '" + shown(l[0]) + "'", l.number); }

  void note(const std::string& what, size_t line) {
    auto it = tally_.unknown.find(what);
    if (it != tally_.unknown.end()) {
      ++it->second.first;
    } else if (tally_.unknown.size() < 16) {
      tally_.unknown.emplace(what, std::make_pair(size_t(1), line));
    } else {
      ++tally_.unknownKinds;
    }
  }

  std::vector<Material>& materials_;
  std::vector<Object>& objects_;  // parents before their kids
  const std::string& path_;
  std::string_view text_;
  Reader r_;
  const ResourceLimits& limits_;
  Tally& tally_;
};

}  // namespace

File parse(const std::string& path, std::string_view text, const ResourceLimits& limits) {
  File file;
  Parser(path, text, limits, file).run();
  return file;
}

}  // namespace tessera::model::detail::ac3d
