#include "mta/camera_path.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <bit>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <glm/geometric.hpp>

#include "base/atomic_file.h"
#include "base/det_math.h"
#include "base/resource_limits.h"
#include "mta/params.h"
#include "raster/command_list.h"

namespace tessera::mta {

namespace {

constexpr double kTwoPi = 2.0 * kPi;

glm::dvec3 lerp(const glm::dvec3& a, const glm::dvec3& b, double s) {
  // (1 - s)·a + s·b rather than a + s·(b - a): s = 1 gives exactly b, so consecutive segments meet
  // in the same bits at their shared keyframe.
  return (1.0 - s) * a + s * b;
}
double smoothstep(double t) { return t * t * (3.0 - 2.0 * t); }

// The box a built-in path is laid out over, in the terms the paths are described in: the ground is at
// min y, u is the long horizontal axis, v the short one, E the long horizontal extent.
struct Layout {
  double cx, cz, minY, maxY;
  glm::dvec3 u, v;  // unit horizontal axes (x / z)
  double E, S;      // long and short horizontal extent (E > 0)
  double near, far;
  double ped;   // pedestrian eye height (absolute y)
  double look;  // distance of a horizontal look-at target ahead of the eye

  glm::dvec3 at(double du, double y, double dv) const {
    return {(cx + du * u.x) + dv * v.x, y, (cz + du * u.z) + dv * v.z};
  }
  glm::dvec3 ahead(const glm::dvec3& eye, const glm::dvec3& dir) const { return eye + look * dir; }
  Camera camera(const glm::dvec3& eye, const glm::dvec3& target) const {
    Camera c;
    c.eye = eye;
    c.target = target;
    c.nearPlane = near;
    c.farPlane = far;
    return c;
  }
};

Layout layoutOf(std::string_view name, const std::array<float, 6>& b) {
  for (int k = 0; k < 3; ++k)
    if (!std::isfinite(b[k]) || !std::isfinite(b[k + 3]) || !(b[k] <= b[k + 3]))
      throw Error("camera path '" + std::string(name) +
                  "': the scene bounds must be finite with min <= max on every axis");
  Layout l;
  const double ex = double(b[3]) - b[0], ey = double(b[4]) - b[1], ez = double(b[5]) - b[2];
  l.cx = 0.5 * (double(b[0]) + b[3]);
  l.cz = 0.5 * (double(b[2]) + b[5]);
  l.minY = b[1];
  l.maxY = b[4];
  const bool xLong = ex >= ez;
  l.u = xLong ? glm::dvec3{1, 0, 0} : glm::dvec3{0, 0, 1};
  l.v = xLong ? glm::dvec3{0, 0, 1} : glm::dvec3{1, 0, 0};
  l.E = xLong ? ex : ez;
  l.S = xLong ? ez : ex;
  // A scene without horizontal extent (a tower, a point) still needs a path of some size.
  if (!(l.E > 0.0)) l.E = ey > 0.0 ? ey : 1.0;
  double D = std::sqrt((ex * ex + ey * ey) + ez * ez);
  if (!(D > 0.0)) D = l.E;
  l.near = 1e-4 * D;
  l.far = 4.0 * D;  // beyond the farthest box corner from every eye position below (tested)
  // Eye height: 1/2000 of the horizontal extent (2 m over a 4 km city), but well clear of the near plane
  // so that the ground right below the eye is not clipped.
  l.ped = l.minY + std::max(l.E / 2000.0, 2.0 * l.near);
  l.look = 0.05 * l.E;
  return l;
}

// ---- "thesis": keyframed, smoothstep between keyframes -------------------------------------------------

// A segment moves eye and target from one keyframe to the next (Move), or keeps the eye and turns the
// horizontal view direction from yaw0 to yaw1 (Turn; yaw 0 = +u, π/2 = +v). Times are frame numbers of
// the 300-frame original; segment i ends where segment i + 1 starts.
struct Segment {
  double t0, t1;
  bool turn;
  glm::dvec3 eye0, target0, eye1, target1;  // Move
  double yaw0, yaw1;                        // Turn (eye0 is the eye)
};

// The smallest distance R at which a camera at mid + R·back (back a unit vector), looking at mid, sees all
// eight corners of the box: a corner p (relative to mid) at depth R + p·f is in view iff |p·s| <= tx·depth
// and |p·t| <= ty·depth (s, t the view's right and up axes), i.e. R >= |p·s| / tx - p·f and likewise for t.
// 5% margin.
double overviewDistance(const Layout& l, const glm::dvec3& back) {
  const double tx = Camera{}.tanHalfFovX, ty = tx * 0.75;
  const glm::dvec3 f = -back;
  // glm::cross and glm::dot ((x·x' + y·y') + z·z') in their usual orders; s / |s| rather than GLM's
  // normalize, which multiplies by an inverse square root.
  const glm::dvec3 side = glm::cross(f, glm::dvec3{0, 1, 0});
  const glm::dvec3 s = side / glm::length(side);
  const glm::dvec3 t = glm::cross(s, f);
  double R = 0.0;
  for (int k = 0; k < 8; ++k) {
    const double du = (k & 1 ? 0.5 : -0.5) * l.E, dv = (k & 2 ? 0.5 : -0.5) * l.S;
    const double dy = (k & 4 ? 0.5 : -0.5) * (l.maxY - l.minY);
    const glm::dvec3 p = {du * l.u.x + dv * l.v.x, dy, du * l.u.z + dv * l.v.z};
    const double pf = glm::dot(p, f);
    R = std::max(R, std::max(std::abs(glm::dot(p, s)) / tx - pf, std::abs(glm::dot(p, t)) / ty - pf));
  }
  return 1.05 * std::max(R, 0.1 * l.E);  // never closer than 0.1 E, e.g. for a box without extent
}

constexpr double kThesisLength = 299.0;  // frames 0..299

std::vector<Segment> thesisSegments(const Layout& l) {
  // A "low flythrough" just over typical roofs: a quarter of the box height, but at least 1% of the
  // extent for flat scenes.
  const double roof = l.minY + std::max(0.25 * (l.maxY - l.minY), 0.01 * l.E);
  // The full overviews look at the box centre from 45° above the horizon (along +u, then along +v), from
  // the nearest distance at which every box corner is in view for the default 60° horizontal fov at the
  // CLI's default 4:3 frame (overviewDistance); for a flat city that is ~0.9 E above the ground.
  const glm::dvec3 mid = {l.cx, 0.5 * (l.minY + l.maxY), l.cz};
  const double c45 = std::sqrt(0.5);
  const glm::dvec3 back1 = {-c45 * l.u.x, c45, -c45 * l.u.z}, back2 = {-c45 * l.v.x, c45, -c45 * l.v.z};
  const double R1 = overviewDistance(l, back1), R2 = overviewDistance(l, back2);
  const glm::dvec3 over1 = mid + R1 * back1;  // looks along +u
  const glm::dvec3 over2 = mid + R2 * back2;  // looks along +v
  const glm::dvec3 walkA = l.at(-0.35 * l.E, l.ped, 0), walkB = l.at(-0.05 * l.E, l.ped, 0);
  const glm::dvec3 roof1 = l.at(-0.1 * l.E, roof, 0.1 * l.S), roof2 = l.at(0.25 * l.E, roof, 0.1 * l.S);
  const glm::dvec3 spot = l.at(0.3 * l.E, l.ped, 0);
  // Every pair of consecutive view directions has horizontal parts with a positive dot product, so the
  // interpolated direction never becomes vertical (parallel to up) and eye and target never meet.
  const double turnEnd = kTwoPi + 0.5 * kPi;  // 450°: ends looking along +v, towards over2's view
  const glm::dvec3 endTurn = l.ahead(spot, l.v);
  return {
      {0, 60, false, walkA, l.ahead(walkA, l.u), walkB, l.ahead(walkB, l.u), 0, 0},     // pedestrian walk
      {60, 120, false, walkB, l.ahead(walkB, l.u), over1, mid, 0, 0},                   // rapid rise to the overview
      {120, 150, false, over1, mid, roof1, l.ahead(roof1, l.u), 0, 0},                  // dive to the roofs
      {150, 180, false, roof1, l.ahead(roof1, l.u), roof2, l.ahead(roof2, l.u), 0, 0},  // low flythrough
      {180, 195, false, roof2, l.ahead(roof2, l.u), spot, l.ahead(spot, l.u), 0, 0},    // drop to the street
      {195, 240, true, spot, {}, spot, {}, 0, turnEnd},                                 // fast turn on the spot
      {240, kThesisLength, false, spot, endTurn, over2, mid, 0, 0},                     // climb to the full overview
  };
}

Camera thesisFrame(const Layout& l, const std::vector<Segment>& segs, double t) {
  size_t i = 0;
  while (i + 1 < segs.size() && t >= segs[i].t1) ++i;
  const Segment& s = segs[i];
  const double local = std::min(1.0, std::max(0.0, (t - s.t0) / (s.t1 - s.t0)));
  const double w = smoothstep(local);
  if (!s.turn) return l.camera(lerp(s.eye0, s.eye1, w), lerp(s.target0, s.target1, w));
  const double yaw = (1.0 - w) * s.yaw0 + w * s.yaw1;
  const double c = detCos(yaw), sn = detSin(yaw);
  const glm::dvec3 dir = {c * l.u.x + sn * l.v.x, 0.0, c * l.u.z + sn * l.v.z};  // y: +0, not c·0 + sn·0
  return l.camera(s.eye0, l.ahead(s.eye0, dir));
}

CameraPath thesisPath(const Layout& l, uint32_t n) {
  const std::vector<Segment> segs = thesisSegments(l);
  CameraPath p{"thesis", {}};
  p.frames.reserve(n);
  for (uint32_t i = 0; i < n; ++i) {
    // n = 300 gives t = i exactly (i · 299 / 299); other counts resample the same keyframes.
    const double t = n == 1 ? 0.0 : double(i) * kThesisLength / double(n - 1);
    p.frames.push_back(thesisFrame(l, segs, t));
  }
  return p;
}

CameraPath orbitPath(const Layout& l, uint32_t n) {
  CameraPath p{"orbit", {}};
  const double r = 0.6 * l.E, y = l.minY + 0.35 * l.E;
  const glm::dvec3 centre = {l.cx, 0.5 * (l.minY + l.maxY), l.cz};
  for (uint32_t i = 0; i < n; ++i) {
    const double a = kTwoPi * double(i) / double(n);  // a closed loop: frame n would repeat frame 0
    p.frames.push_back(l.camera({l.cx + r * detCos(a), y, l.cz + r * detSin(a)}, centre));
  }
  return p;
}

CameraPath streetPath(const Layout& l, uint32_t n) {
  CameraPath p{"street", {}};
  for (uint32_t i = 0; i < n; ++i) {
    const double t = n == 1 ? 0.0 : double(i) / double(n - 1);
    const glm::dvec3 eye = l.at((t - 0.5) * 0.9 * l.E, l.ped, 0);  // constant walking speed from -0.45 E to 0.45 E
    p.frames.push_back(l.camera(eye, l.ahead(eye, l.u)));
  }
  return p;
}

// ---- the path file -------------------------------------------------------------------------------------

std::string fmt(double v) {
  char buf[64];
  // Shortest decimal that parses back to the same double: exact round trip, and locale-independent
  // (unlike printf, whose decimal point follows LC_NUMERIC).
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

bool sameBits(double a, double b) { return std::bit_cast<uint64_t>(a) == std::bit_cast<uint64_t>(b); }

bool isSpace(char c) { return c == ' ' || c == '\t' || c == '\r'; }

std::string_view trim(std::string_view s) {
  while (!s.empty() && isSpace(s.front())) s.remove_prefix(1);
  while (!s.empty() && isSpace(s.back())) s.remove_suffix(1);
  return s;
}

std::vector<std::string_view> split(std::string_view s) {
  std::vector<std::string_view> t;
  size_t i = 0;
  while (i < s.size()) {
    while (i < s.size() && isSpace(s[i])) ++i;
    const size_t b = i;
    while (i < s.size() && !isSpace(s[i])) ++i;
    if (i > b) t.push_back(s.substr(b, i - b));
  }
  return t;
}

// Length of the UTF-8 sequence starting at s[i] (RFC 3629: no overlong forms, no surrogates, at most
// U+10FFFF), or 0 if it is not one.
size_t utf8Length(std::string_view s, size_t i) {
  const auto at = [&](size_t k) { return k < s.size() ? uint8_t(s[k]) : uint8_t(0); };
  const uint8_t c = at(i);
  if (c < 0x80) return 1;
  size_t n = 0;
  uint8_t lo = 0x80, hi = 0xBF;  // range of the second byte
  if (c >= 0xC2 && c <= 0xDF)
    n = 2;
  else if (c == 0xE0)
    n = 3, lo = 0xA0;
  else if ((c >= 0xE1 && c <= 0xEC) || c == 0xEE || c == 0xEF)
    n = 3;
  else if (c == 0xED)
    n = 3, hi = 0x9F;
  else if (c == 0xF0)
    n = 4, lo = 0x90;
  else if (c >= 0xF1 && c <= 0xF3)
    n = 4;
  else if (c == 0xF4)
    n = 4, hi = 0x8F;
  else
    return 0;
  if (at(i + 1) < lo || at(i + 1) > hi) return 0;
  for (size_t k = 2; k < n; ++k)
    if (at(i + k) < 0x80 || at(i + k) > 0xBF) return 0;
  return n;
}

// "" if `s` is UTF-8 text without control characters other than tab and CR, else why not.
std::string textProblem(std::string_view s) {
  for (size_t i = 0; i < s.size();) {
    const uint8_t c = uint8_t(s[i]);
    if ((c < 0x20 && c != '\t' && c != '\r') || c == 0x7f) {
      char hex[8];
      std::snprintf(hex, sizeof hex, "0x%02x", c);
      return std::string("byte ") + hex + " at column " + std::to_string(i + 1) +
             " is a control character (a camera path file is text)";
    }
    const size_t n = utf8Length(s, i);
    if (n == 0) return "invalid UTF-8 at column " + std::to_string(i + 1);
    i += n;
  }
  return "";
}

// A token as an error message quotes it: at most 40 bytes, cut at a character boundary.
std::string quote(std::string_view t) {
  size_t n = t.size();
  if (n > 40) {
    n = 40;
    while (n > 0 && (uint8_t(t[n]) & 0xC0) == 0x80) --n;
  }
  std::string q = "'";  // appended piecewise: GCC 12 warns falsely (-Wrestrict) on the chained operator+
  q.append(t.substr(0, n)).append(n < t.size() ? "...'" : "'");
  return q;
}

// The file name without its extension, the default path name; bytes that are not UTF-8 become '?' so
// that the name can go into JSON.
std::string stemOf(const std::string& path) {
  const std::string stem = std::filesystem::path(path).stem().string();
  std::string out;
  for (size_t i = 0; i < stem.size();) {
    const size_t n = utf8Length(stem, i);
    if (n == 0 || uint8_t(stem[i]) < 0x20 || stem[i] == 0x7f) {
      out += '?';
      ++i;
    } else {
      out.append(stem, i, n);
      i += n;
    }
  }
  return out;
}

// The rules every camera of a path file obeys beyond mta::validate (docs/mta-camera-path.md): with them
// the float view-projection of every frame the renderer accepts stays finite.
std::string rangeProblem(const Camera& c) {
  auto big = [](const glm::dvec3& v) {
    return !(std::abs(v.x) <= kMaxPathCoordinate && std::abs(v.y) <= kMaxPathCoordinate &&
             std::abs(v.z) <= kMaxPathCoordinate);
  };
  const std::string limit = fmt(kMaxPathCoordinate);
  if (big(c.eye)) return "eye: a coordinate's magnitude exceeds " + limit;
  if (big(c.target)) return "target: a coordinate's magnitude exceeds " + limit;
  if (big(c.up)) return "up: a component's magnitude exceeds " + limit;
  if (!(c.nearPlane <= kMaxPathCoordinate)) return "near: exceeds " + limit;
  if (!(c.farPlane <= kMaxPathCoordinate)) return "far: exceeds " + limit;
  if (!(c.tanHalfFovX >= kMinTanHalfFov && c.tanHalfFovX <= kMaxTanHalfFov))
    return "tan_half_fov: " + fmt(c.tanHalfFovX) + " is outside [" + fmt(kMinTanHalfFov) + ", " + fmt(kMaxTanHalfFov) +
           "]";
  return "";
}

// The reader's state: one call per line, then finish().
class PathParser {
 public:
  explicit PathParser(const std::string& path) : path_(path) {}

  void line(std::string_view line) {
    ++lineNo_;
    where_ = path_ + ":" + std::to_string(lineNo_);
    if (line.size() > kMaxPathLineBytes)
      fail("the line is " + std::to_string(line.size()) + " bytes long, over the limit of " +
           std::to_string(kMaxPathLineBytes));
    if (lineNo_ == 1 && line.substr(0, 3) == "\xEF\xBB\xBF") line.remove_prefix(3);  // a byte order mark is not content
    if (const std::string why = textProblem(line); !why.empty()) fail(why);
    if (const size_t hash = line.find('#'); hash != std::string_view::npos) line = line.substr(0, hash);
    const std::vector<std::string_view> t = split(line);
    if (t.empty()) return;
    if (!header_) {
      if (t[0] == "tessera-camera-path" && t.size() == 2 && t[1] != "1")
        fail("unsupported format version " + quote(t[1]) + " (this reader knows version 1)");
      if (t.size() != 2 || t[0] != "tessera-camera-path" || t[1] != "1")
        fail("expected the header 'tessera-camera-path 1' as the first non-comment line");
      header_ = true;
      return;
    }
    const std::string_view k = t[0];
    const bool directive = k == "name" || k == "fov" || k == "tan_half_fov" || k == "near" || k == "far" || k == "up";
    // Six fields or a leading number make a frame, so that "nan 0 0 1 0 0" says "not finite" rather than
    // "unknown directive".
    const bool frameLine =
        !directive && (t.size() == 6 || k[0] == '-' || k[0] == '+' || k[0] == '.' || (k[0] >= '0' && k[0] <= '9'));
    if (frameLine) {
      frame(t);
      return;
    }
    pendingDirective_ = lineNo_;
    if (k == "name") {
      if (named_) fail("'name' is given twice");
      const std::string_view rest = trim(line.substr(size_t(k.data() + k.size() - line.data())));
      if (rest.empty()) fail("'name' needs a value");
      p_.name = std::string(rest);
      named_ = true;
      pendingDirective_ = 0;  // applies to the whole path, not to the frames that follow
    } else if (k == "fov") {
      expectArgs(t, 1);
      const double deg = number(t[1]);
      if (!(deg > 0.0 && deg < 180.0)) fail("fov " + quote(t[1]) + ": must be in (0, 180) degrees");
      // The same formula as BuildParams::effectiveTanHalfFov, so equal degrees give equal bits.
      const double half = deg * kPi / 360.0;
      const double tan = detSin(half) / detCos(half);
      if (!(tan >= kMinTanHalfFov && tan <= kMaxTanHalfFov))
        fail("fov " + quote(t[1]) + ": tan(fov / 2) = " + fmt(tan) + " is outside [" + fmt(kMinTanHalfFov) + ", " +
             fmt(kMaxTanHalfFov) + "]");
      state_.tanHalfFovX = tan;
    } else if (k == "tan_half_fov") {
      expectArgs(t, 1);
      state_.tanHalfFovX = number(t[1]);
      if (!(state_.tanHalfFovX >= kMinTanHalfFov && state_.tanHalfFovX <= kMaxTanHalfFov))
        fail("tan_half_fov " + quote(t[1]) + ": must be in [" + fmt(kMinTanHalfFov) + ", " + fmt(kMaxTanHalfFov) + "]");
    } else if (k == "near") {
      expectArgs(t, 1);
      state_.nearPlane = number(t[1]);
      if (!(state_.nearPlane > 0.0)) fail("near " + quote(t[1]) + ": must be > 0");
    } else if (k == "far") {
      expectArgs(t, 1);
      state_.farPlane = number(t[1]);
      if (!(state_.farPlane > 0.0)) fail("far " + quote(t[1]) + ": must be > 0");
    } else if (k == "up") {
      expectArgs(t, 3);
      for (int i = 0; i < 3; ++i) state_.up[i] = number(t[1 + size_t(i)]);
      if (state_.up[0] == 0.0 && state_.up[1] == 0.0 && state_.up[2] == 0.0) fail("up: must not be the zero vector");
    } else {
      fail("unknown directive " + quote(k) + " (known: name, fov, tan_half_fov, near, far, up)");
    }
  }

  // The line after the last complete one is longer than the limit (`bytes` read of it so far).
  [[noreturn]] void tooLong(uint64_t bytes) const {
    throw Error(path_ + ":" + std::to_string(lineNo_ + 1) + ": the line is longer than " +
                std::to_string(kMaxPathLineBytes) + " bytes (" + std::to_string(bytes) + " read without a line end)");
  }
  [[noreturn]] void tooLarge(uint64_t bytes) const {
    throw Error(path_ + ":" + std::to_string(lineNo_ + 1) + ": the file is larger than " +
                formatBytes(kMaxPathFileBytes) + " (" + std::to_string(bytes) +
                " bytes read), the limit for a camera path file");
  }
  CameraPath finish() {
    if (!header_)
      throw Error(path_ + ":" + std::to_string(std::max<size_t>(lineNo_, 1)) +
                  ": expected the header 'tessera-camera-path 1'; the file has no content");
    if (pendingDirective_)
      throw Error(path_ + ":" + std::to_string(pendingDirective_) + ": directive has no effect: no frame follows it");
    if (p_.frames.empty()) throw Error(path_ + ":" + std::to_string(lineNo_) + ": the file has no frames");
    if (!named_) p_.name = stemOf(path_);
    return std::move(p_);
  }

 private:
  [[noreturn]] void fail(const std::string& why) const { throw Error(where_ + ": " + why); }

  double number(std::string_view field) const {
    // from_chars takes no leading '+', people write one.
    const std::string_view tok =
        field.size() > 1 && field[0] == '+' && field[1] != '-' && field[1] != '+' ? field.substr(1) : field;
    double v = 0.0;
    const auto r = std::from_chars(tok.data(), tok.data() + tok.size(), v);
    if (r.ec == std::errc::result_out_of_range) fail(quote(tok) + " is out of the range of a double");
    if (r.ec != std::errc() || r.ptr != tok.data() + tok.size()) fail(quote(tok) + " is not a number");
    if (!std::isfinite(v)) fail(quote(tok) + " is not finite");
    if (!(std::abs(v) <= kMaxPathCoordinate))
      fail(quote(tok) + " exceeds " + fmt(kMaxPathCoordinate) +
           " in magnitude, the largest number a camera path accepts");
    return v;
  }

  void expectArgs(const std::vector<std::string_view>& t, size_t n) const {
    if (t.size() == n + 1) return;
    std::string why = "'";  // appended piecewise: GCC 12 warns falsely (-Wrestrict) on the chained operator+
    why.append(t[0]).append("' takes ").append(std::to_string(n)).append(n == 1 ? " number" : " numbers");
    why.append(", got ").append(std::to_string(t.size() - 1));
    fail(why);
  }

  void frame(const std::vector<std::string_view>& t) {
    if (t.size() != 6) fail("a frame needs 6 numbers (eye x y z, target x y z), got " + std::to_string(t.size()));
    Camera c = state_;
    for (size_t i = 0; i < 3; ++i) c.eye[int(i)] = number(t[i]), c.target[int(i)] = number(t[3 + i]);
    validate(c, where_);
    if (p_.frames.size() >= kMaxPathFrames)
      fail("more than " + std::to_string(kMaxPathFrames) + " frames, the limit for a camera path");
    p_.frames.push_back(c);
    pendingDirective_ = 0;
  }

  const std::string& path_;
  std::string where_;
  size_t lineNo_ = 0, pendingDirective_ = 0;  // pendingDirective_: line of a directive no frame has used yet
  bool header_ = false, named_ = false;
  Camera state_;  // the directives' current values, applied to each frame
  CameraPath p_;
};

}  // namespace

std::vector<std::string> builtinPathNames() { return {"thesis", "orbit", "street"}; }

CameraPath builtinPath(std::string_view name, const std::array<float, 6>& sceneBounds, uint32_t frames) {
  const auto names = builtinPathNames();
  if (std::find(names.begin(), names.end(), name) == names.end()) {
    std::string known;
    for (const auto& n : names) known += (known.empty() ? "" : ", ") + n;
    throw Error("camera path '" + std::string(name) + "': not a built-in path (known: " + known + ")");
  }
  if (frames > kMaxPathFrames)
    throw Error("camera path '" + std::string(name) + "': " + std::to_string(frames) + " frames requested, at most " +
                std::to_string(kMaxPathFrames));
  const Layout l = layoutOf(name, sceneBounds);
  if (name == "thesis") return thesisPath(l, frames ? frames : 300);
  if (name == "orbit") return orbitPath(l, frames ? frames : 120);
  return streetPath(l, frames ? frames : 120);
}

CameraPath readPathFile(const std::string& path) {
  // Read with POSIX calls in chunks, line by line: a FIFO or a device (/dev/zero) is read only as far as
  // the limits allow, and the file is never held whole in memory.
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) throw Error(path + ": cannot open: " + std::strerror(errno));
  struct Closer {
    int fd;
    ~Closer() { ::close(fd); }
  } closer{fd};
  struct stat st {};
  if (::fstat(fd, &st) == 0 && S_ISDIR(st.st_mode)) throw Error(path + ": is a directory, not a camera path file");
  PathParser parser(path);
  std::string pending;
  std::vector<char> chunk(64 * 1024);
  uint64_t total = 0;
  for (;;) {
    const ssize_t r = ::read(fd, chunk.data(), chunk.size());
    if (r < 0 && errno == EINTR) continue;
    if (r < 0) throw Error(path + ": read failed: " + std::strerror(errno));
    if (r == 0) break;
    total += uint64_t(r);
    if (total > kMaxPathFileBytes) parser.tooLarge(total);
    pending.append(chunk.data(), size_t(r));
    size_t start = 0;
    for (size_t nl; (nl = pending.find('\n', start)) != std::string::npos; start = nl + 1)
      parser.line(std::string_view(pending).substr(start, nl - start));
    pending.erase(0, start);
    if (pending.size() > kMaxPathLineBytes) parser.tooLong(pending.size());
  }
  if (!pending.empty()) parser.line(pending);
  return parser.finish();
}

void writePathFile(const CameraPath& p, const std::string& path) {
  // Everything the reader refuses is refused here, so that a written file always reads back.
  for (unsigned char ch : p.name)
    if (ch < 0x20 || ch == 0x7f || ch == '#')
      throw Error(path + ": path name '" + p.name +
                  "' contains a control character or '#', which the file cannot hold");
  if (trim(p.name).size() != p.name.size())
    throw Error(path + ": path name '" + p.name + "' has surrounding spaces, which the file cannot hold");
  if (!textProblem(p.name).empty()) throw Error(path + ": path name is not UTF-8 text, which the file cannot hold");
  if (5 + p.name.size() > kMaxPathLineBytes)
    throw Error(path + ": path name is " + std::to_string(p.name.size()) + " bytes long; its line would exceed " +
                std::to_string(kMaxPathLineBytes) + " bytes");
  if (p.frames.empty()) throw Error(path + ": the camera path has no frames");
  if (p.frames.size() > kMaxPathFrames)
    throw Error(path + ": " + std::to_string(p.frames.size()) + " frames, more than the " +
                std::to_string(kMaxPathFrames) + " a camera path file may hold");
  for (size_t i = 0; i < p.frames.size(); ++i) {
    const std::string where = path + ": frame " + std::to_string(i);
    validate(p.frames[i], where);
    if (const std::string why = rangeProblem(p.frames[i]); !why.empty()) throw Error(where + ": camera " + why);
  }

  std::string out = "tessera-camera-path 1\n# docs/mta-camera-path.md; one frame per line: eye x y z, target x y z\n";
  if (!p.name.empty()) out += "name " + p.name + "\n";
  Camera state;  // the reader's defaults
  for (const Camera& c : p.frames) {
    if (!sameBits(c.tanHalfFovX, state.tanHalfFovX)) out += "tan_half_fov " + fmt(c.tanHalfFovX) + "\n";
    if (!sameBits(c.nearPlane, state.nearPlane)) out += "near " + fmt(c.nearPlane) + "\n";
    if (!sameBits(c.farPlane, state.farPlane)) out += "far " + fmt(c.farPlane) + "\n";
    if (!sameBits(c.up[0], state.up[0]) || !sameBits(c.up[1], state.up[1]) || !sameBits(c.up[2], state.up[2]))
      out += "up " + fmt(c.up[0]) + " " + fmt(c.up[1]) + " " + fmt(c.up[2]) + "\n";
    state = c;
    out += fmt(c.eye[0]) + " " + fmt(c.eye[1]) + " " + fmt(c.eye[2]) + "  " + fmt(c.target[0]) + " " +
           fmt(c.target[1]) + " " + fmt(c.target[2]) + "\n";
  }
  if (out.size() > kMaxPathFileBytes)
    throw Error(path + ": the path would take " + formatBytes(out.size()) + ", more than the " +
                formatBytes(kMaxPathFileBytes) + " a camera path file may hold");
  writeFileAtomically(path, out);
}

CameraPath builtinPathOverTree(std::string_view name, const MtaMeta& meta, uint32_t frames) {
  std::array<float, 6> b{1e30f, 1e30f, 1e30f, -1e30f, -1e30f, -1e30f};
  for (const Tree& t : meta.trees) {
    if (t.nodes.empty()) continue;
    for (int k = 0; k < 3; ++k) {
      b[k] = std::min(b[k], t.nodes[0].bounds[k]);
      b[k + 3] = std::max(b[k + 3], t.nodes[0].bounds[k + 3]);
    }
  }
  if (b[0] > b[3]) throw Error("the tree has no triangles: no camera path can be laid out over it");
  CameraPath p = builtinPath(name, b, frames);
  for (Camera& c : p.frames) c.tanHalfFovX = meta.params.tanHalfFov;
  return p;
}

}  // namespace tessera::mta
