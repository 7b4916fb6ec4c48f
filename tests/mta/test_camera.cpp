// The renderer's camera (matrices, frustum, box tests, validation) and camera paths (built-in paths and
// the path file).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <functional>

#include "mta/camera.h"
#include "mta/camera_path.h"
#include "mta_test_scene.h"
#include "base/error.h"

namespace tessera::mta {
namespace {

// Eye at the origin looking down -z (GL's default view), 90° horizontal fov, square window.
Camera lookingDownMinusZ() {
  Camera c;
  c.eye = {0, 0, 0};
  c.target = {0, 0, -1};
  c.tanHalfFovX = 1.0;
  c.nearPlane = 0.5;
  c.farPlane = 100.0;
  return c;
}

glm::dvec4 clipOf(const glm::dmat4& m, const glm::dvec3& p) {
  glm::dvec4 r;
  for (int i = 0; i < 4; ++i) r[i] = m[0][i] * p[0] + m[1][i] * p[1] + m[2][i] * p[2] + m[3][i];
  return r;
}

std::string messageOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "(no Error thrown)";
}

bool sameBytes(const CameraPath& a, const CameraPath& b) {
  return a.name == b.name && a.frames.size() == b.frames.size() &&
         std::memcmp(a.frames.data(), b.frames.data(), a.frames.size() * sizeof(Camera)) == 0;
}

// A Berlin-like city: 4 km x 3 km, buildings up to 40 m, shifted away from the origin.
const std::array<float, 6> kCity = {1000, -5, 2000, 5000, 35, 5000};

TEST(Camera, BoxInFrontOfTheCameraIsInsideTheFrustum) {
  const Frustum f = frustumOf(lookingDownMinusZ(), 640, 480);
  EXPECT_FALSE(outsideFrustum(f, {-1, -1, -11, 1, 1, -9}));
  // A box around the eye straddles the near plane: not outside.
  EXPECT_FALSE(outsideFrustum(f, {-1, -1, -1, 1, 1, 1}));
}

TEST(Camera, BoxBehindTheCameraIsOutsideTheFrustum) {
  const Frustum f = frustumOf(lookingDownMinusZ(), 640, 480);
  EXPECT_TRUE(outsideFrustum(f, {-1, -1, 9, 1, 1, 11}));
}

TEST(Camera, BoxFarToTheLeftIsOutsideTheFrustum) {
  const Frustum f = frustumOf(lookingDownMinusZ(), 640, 480);
  // At depth d the 90° view spans x in [-d, d]: at depth 11 (the box's far side) the box ends at x = -12.
  EXPECT_TRUE(outsideFrustum(f, {-14, -1, -11, -12, 1, -9}));
  EXPECT_FALSE(outsideFrustum(f, {-10.5f, -1, -11, -9.5f, 1, -9}));
}

TEST(Camera, BoxBeyondTheFarPlaneIsOutsideTheFrustum) {
  const Frustum f = frustumOf(lookingDownMinusZ(), 640, 480);
  EXPECT_TRUE(outsideFrustum(f, {-1, -1, -120, 1, 1, -101}));
  EXPECT_FALSE(outsideFrustum(f, {-1, -1, -120, 1, 1, -99}));
}

TEST(Camera, TheVerticalFieldOfViewFollowsTheAspectRatio) {
  // 640 x 320: tan(fovY/2) = 1 / 2, so at depth 10 the view spans y in [-5, 5] but x in [-10, 10].
  const Frustum f = frustumOf(lookingDownMinusZ(), 640, 320);
  EXPECT_TRUE(outsideFrustum(f, {-1, 6, -11, 1, 7, -9}));
  EXPECT_FALSE(outsideFrustum(f, {8, -1, -11, 9, 1, -9}));
}

TEST(Camera, FrustumPlanesAreNormalisedDistances) {
  const Frustum f = frustumOf(lookingDownMinusZ(), 640, 480);
  for (const Plane& p : f.planes) EXPECT_NEAR(p.a * p.a + p.b * p.b + p.c * p.c, 1.0, 1e-12);
  // The near plane (index 4) is z = -0.5 facing -z: the origin is 0.5 outside it.
  EXPECT_NEAR(f.planes[4].d, -0.5, 1e-12);
  EXPECT_NEAR(f.planes[4].c, -1.0, 1e-12);
}

TEST(Camera, DistanceToABoxContainingTheEyeIsZero) {
  EXPECT_EQ(distanceToBox({1, 2, 3}, {0, 0, 0, 4, 4, 4}), 0.0);
  EXPECT_EQ(distanceToBox({4, 4, 4}, {0, 0, 0, 4, 4, 4}), 0.0);
}

TEST(Camera, DistanceToABoxIsTheDistanceToItsClosestPoint) {
  EXPECT_EQ(distanceToBox({0, 0, 0}, {3, 4, -1, 5, 6, 1}), 5.0);  // closest point (3, 4, 0)
  EXPECT_EQ(distanceToBox({10, 2, 0}, {0, 0, 0, 4, 4, 4}), 6.0);  // closest point (4, 2, 0)
  EXPECT_EQ(distanceToBox({-2, 7, 10}, {0, 0, 0, 4, 4, 4}), std::sqrt(4.0 + 9.0 + 36.0));
}

TEST(Camera, ThePointAtTheViewCentreProjectsToTheNdcOrigin) {
  Camera c;
  c.eye = {12.5, 3.25, -7};
  c.target = {-30, 1, 44};
  c.nearPlane = 0.01;
  c.farPlane = 500;
  const auto clip = clipOf(viewProjectionD(c, 1024, 768), c.target);
  EXPECT_NEAR(clip[0] / clip[3], 0.0, 1e-12);
  EXPECT_NEAR(clip[1] / clip[3], 0.0, 1e-12);
  EXPECT_GT(clip[3], 0.0);
  const glm::dmat4 md(viewProjection(c, 1024, 768));
  const auto cf = clipOf(md, c.target);
  EXPECT_NEAR(cf[0] / cf[3], 0.0, 1e-5);
  EXPECT_NEAR(cf[1] / cf[3], 0.0, 1e-5);
}

TEST(Camera, TheEdgesOfTheHorizontalFovAndTheNearAndFarPlanesMapToTheNdcBounds) {
  const Camera c = lookingDownMinusZ();
  const auto m = viewProjectionD(c, 640, 320);
  const auto right = clipOf(m, {10, 0, -10});  // tan = 1: x = depth is the right edge
  EXPECT_NEAR(right[0] / right[3], 1.0, 1e-12);
  const auto top = clipOf(m, {0, 5, -10});  // tan(fovY/2) = 1/2
  EXPECT_NEAR(top[1] / top[3], 1.0, 1e-12);
  const auto nearP = clipOf(m, {0, 0, -0.5}), farP = clipOf(m, {0, 0, -100});
  EXPECT_NEAR(nearP[2] / nearP[3], -1.0, 1e-12);
  EXPECT_NEAR(farP[2] / farP[3], 1.0, 1e-12);
}

TEST(Camera, TheFloatMatricesAreTheDoubleMatricesRoundedOnce) {
  Camera c;
  c.eye = {1, 2, 3};
  c.target = {4, -5, 6};
  const auto d = viewProjectionD(c, 800, 600);
  const auto f = viewProjection(c, 800, 600);
  for (int i = 0; i < 16; ++i) EXPECT_EQ(f[i / 4][i % 4], float(d[i / 4][i % 4])) << i;
  const auto v = viewMatrix(c);
  const auto vd = viewMatrixD(c);
  const auto p = projectionMatrix(c, 800, 600);
  const auto pd = projectionMatrixD(c, 800, 600);
  for (int i = 0; i < 16; ++i) {
    EXPECT_EQ(v[i / 4][i % 4], float(vd[i / 4][i % 4])) << i;
    EXPECT_EQ(p[i / 4][i % 4], float(pd[i / 4][i % 4])) << i;
  }
}

TEST(Camera, InvalidCamerasAreRejectedNamingWhereAndTheField) {
  const Camera ok = lookingDownMinusZ();
  EXPECT_NO_THROW(validate(ok, "here"));
  auto expectBad = [&](Camera c, const std::string& field) {
    const std::string m = messageOf([&] { validate(c, "frame 7"); });
    EXPECT_NE(m.find("frame 7"), std::string::npos) << m;
    EXPECT_NE(m.find(field), std::string::npos) << m;
  };
  Camera c = ok;
  c.target = c.eye;
  expectBad(c, "target");
  c = ok, c.up = {0, 0, 2};
  expectBad(c, "up");
  c = ok, c.up = {0, 0, 0};
  expectBad(c, "up");
  c = ok, c.eye[1] = std::nan("");
  expectBad(c, "eye");
  c = ok, c.nearPlane = 0;
  expectBad(c, "near");
  c = ok, c.farPlane = c.nearPlane;
  expectBad(c, "far");
  c = ok, c.tanHalfFovX = 0;
  expectBad(c, "tan_half_fov");
  c = ok, c.tanHalfFovX = INFINITY;
  expectBad(c, "tan_half_fov");
}

TEST(CameraPath, BuiltinPathsHaveTheirDefaultFrameCounts) {
  EXPECT_EQ(builtinPathNames(), (std::vector<std::string>{"thesis", "orbit", "street"}));
  EXPECT_EQ(builtinPath("thesis", kCity).frames.size(), 300u);
  EXPECT_EQ(builtinPath("orbit", kCity).frames.size(), 120u);
  EXPECT_EQ(builtinPath("street", kCity).frames.size(), 120u);
  for (const auto& n : builtinPathNames()) {
    EXPECT_EQ(builtinPath(n, kCity).name, n);
    EXPECT_EQ(builtinPath(n, kCity, 17).frames.size(), 17u) << n;
    EXPECT_EQ(builtinPath(n, kCity, 1).frames.size(), 1u) << n;
  }
}

TEST(CameraPath, EveryFrameOfEveryBuiltinPathIsAValidCamera) {
  const std::array<float, 6> boxes[] = {
      kCity,
      {0, 0, 0, 1, 1, 1},        // unit cube
      {-5, 0, -500, 5, 2, 500},  // long along z
      {0, 0, 0, 10, 300, 10},    // a tower: taller than wide
      {0, 0, 0, 100, 0, 100},    // flat
      {3, 4, 5, 3, 4, 5},        // a single point
      {-1e6f, 0, -1e6f, 1e6f, 400, 1e6f},
  };
  for (const auto& b : boxes)
    for (const auto& n : builtinPathNames())
      for (uint32_t frames : {0u, 2u, 1000u}) {
        const CameraPath p = builtinPath(n, b, frames);
        for (size_t i = 0; i < p.frames.size(); ++i) {
          const Camera& c = p.frames[i];
          ASSERT_NO_THROW(validate(c, n + " frame " + std::to_string(i))) << n << " frame " << i;
          // The far plane reaches every corner of the box.
          for (int k = 0; k < 8; ++k) {
            const double x = b[(k & 1) ? 3 : 0] - c.eye[0], y = b[(k & 2) ? 4 : 1] - c.eye[1],
                         z = b[(k & 4) ? 5 : 2] - c.eye[2];
            ASSERT_LT(std::sqrt(x * x + y * y + z * z), c.farPlane) << n << " frame " << i;
          }
        }
      }
}

TEST(CameraPath, BuiltinPathsAreDeterministic) {
  for (const auto& n : builtinPathNames()) {
    EXPECT_TRUE(sameBytes(builtinPath(n, kCity), builtinPath(n, kCity))) << n;
    EXPECT_TRUE(sameBytes(builtinPath(n, kCity, 77), builtinPath(n, kCity, 77))) << n;
  }
}

TEST(CameraPath, ResamplingTheThesisPathKeepsItsKeyframes) {
  // 599 frames put frame 2i at the original frame i.
  const CameraPath a = builtinPath("thesis", kCity), b = builtinPath("thesis", kCity, 599);
  for (size_t i : {0, 60, 120, 150, 180, 195, 240, 299})
    EXPECT_EQ(std::memcmp(&a.frames[i], &b.frames[2 * i], sizeof(Camera)), 0) << i;
}

TEST(CameraPath, TheThesisPathHasPedestrianAndOverviewFrames) {
  const CameraPath p = builtinPath("thesis", kCity);
  const double width = 4000.0;  // the long horizontal extent
  int pedestrian = 0, overview = 0;
  for (const Camera& c : p.frames) {
    if (c.eye[1] - kCity[1] < 0.001 * width) ++pedestrian;  // a few metres above the ground
    if (c.eye[1] > kCity[4] + 0.5 * width) ++overview;
  }
  EXPECT_GE(pedestrian, 60);  // the walk and the turn on the spot
  EXPECT_GE(overview, 10);
  // Frame 120 and the last frame are full overviews: every corner of the city is in view.
  for (size_t i : {size_t(120), p.frames.size() - 1}) {
    const Camera& c = p.frames[i];
    EXPECT_GT(c.eye[1], kCity[4] + 0.5 * width) << i;
    const Frustum f = frustumOf(c, 1024, 768);
    for (int k = 0; k < 8; ++k) {
      const float x = kCity[(k & 1) ? 3 : 0], y = kCity[(k & 2) ? 4 : 1], z = kCity[(k & 4) ? 5 : 2];
      EXPECT_FALSE(outsideFrustum(f, {x, y, z, x, y, z})) << "frame " << i << " corner " << k;
    }
  }
  // Pedestrian frames look horizontally.
  EXPECT_EQ(p.frames[30].eye[1], p.frames[30].target[1]);
  EXPECT_EQ(p.frames[210].eye[1], p.frames[210].target[1]);
}

TEST(CameraPath, UnknownBuiltinPathNamesAndBadBoundsAreRejected) {
  const std::string m = messageOf([] { builtinPath("spiral", kCity); });
  EXPECT_NE(m.find("spiral"), std::string::npos) << m;
  EXPECT_NE(m.find("thesis, orbit, street"), std::string::npos) << m;
  EXPECT_THROW(builtinPath("orbit", {1, 0, 0, 0, 1, 1}), Error);
  EXPECT_THROW(builtinPath("orbit", {0, 0, 0, INFINITY, 1, 1}), Error);
}

TEST(CameraPath, PathFileRoundTripIsExact) {
  CameraPath p = builtinPath("thesis", kCity, 40);
  p.name = "my thesis path";
  // Values that need all 17 digits, per-frame changes of every directive, a negative zero, and the
  // largest magnitude a path file accepts.
  p.frames[3].tanHalfFovX = 0.1 + 0.2;
  p.frames[4].nearPlane = 1.0 / 3.0;
  p.frames[5].farPlane = kMaxPathCoordinate;
  p.frames[6].up = {1e-310, 1, -0.0};
  p.frames[7].eye = {-0.0, 5e-324, 1.2345678901234567e14};
  p.frames[8].target = {std::nextafter(1.0, 2.0), 123456789.125, -7};
  testing::TempFile f("path.txt");
  writePathFile(p, f.path);
  const CameraPath q = readPathFile(f.path);
  EXPECT_TRUE(sameBytes(p, q));
  EXPECT_FALSE(std::filesystem::exists(f.path + ".tmp-" + std::to_string(::getpid())));
  // Written again, the file is byte-identical.
  testing::TempFile g("again.txt");
  writePathFile(q, g.path);
  std::ifstream a(f.path), b(g.path);
  EXPECT_EQ(std::string(std::istreambuf_iterator<char>(a), {}), std::string(std::istreambuf_iterator<char>(b), {}));
}

TEST(CameraPath, PathFileDirectivesApplyToTheFramesThatFollow) {
  testing::TempFile f("directives.path");
  testing::writeText(f.path,
                     "\xEF\xBB\xBF# a comment\r\n"
                     "\n"
                     "tessera-camera-path 1   # trailing comment\r\n"
                     "fov 90\n"
                     "near 0.25\n"
                     "far 2e3\n"
                     "0 1.5 0   +10 1.5 0\n"
                     "up 0 0 1\n"
                     "\t1 2 3 4 5 6\n");
  const CameraPath p = readPathFile(f.path);
  EXPECT_EQ(p.name, std::filesystem::path(f.path).stem().string());  // no name directive: the file name's stem
  EXPECT_NE(p.name.find("directives"), std::string::npos);
  ASSERT_EQ(p.frames.size(), 2u);
  EXPECT_NEAR(p.frames[0].tanHalfFovX, 1.0, 1e-15);
  EXPECT_EQ(p.frames[0].nearPlane, 0.25);
  EXPECT_EQ(p.frames[0].farPlane, 2000.0);
  EXPECT_EQ(p.frames[0].up, (glm::dvec3{0, 1, 0}));
  EXPECT_EQ(p.frames[0].target, (glm::dvec3{10, 1.5, 0}));
  EXPECT_EQ(p.frames[1].up, (glm::dvec3{0, 0, 1}));
  EXPECT_EQ(p.frames[1].nearPlane, 0.25);
  EXPECT_EQ(p.frames[1].eye, (glm::dvec3{1, 2, 3}));
}

TEST(CameraPath, MalformedPathFilesThrowNamingTheFileAndTheLine) {
  struct Case {
    std::string text;
    int line;
    std::string reason;
  };
  const std::string h = "tessera-camera-path 1\n";
  const Case cases[] = {
      {"", 1, "header"},
      {"# only a comment\n", 1, "header"},
      {"0 0 0 1 1 1\n", 1, "header"},
      {"tessera-camera-path 2\n0 0 0 1 0 0\n", 1, "version"},
      {h, 1, "no frames"},
      {h + "fov 60\n", 2, "no frame follows"},
      {h + "0 0 0 1 0 0\nnear 2\n", 3, "no frame follows"},
      {h + "zoom 2\n0 0 0 1 0 0\n", 2, "unknown directive 'zoom'"},
      {h + "fov\n0 0 0 1 0 0\n", 2, "takes 1 number"},
      {h + "up 0 1\n0 0 0 1 0 0\n", 2, "takes 3 numbers"},
      {h + "fov 180\n0 0 0 1 0 0\n", 2, "(0, 180)"},
      {h + "near -1\n0 0 0 1 0 0\n", 2, "near"},
      {h + "up 0 0 0\n0 0 0 1 0 0\n", 2, "zero vector"},
      {h + "0 0 0 1 0 0\n0 0 0 1 0\n", 3, "6 numbers"},
      {h + "0 0 0 1 0 0 7\n", 2, "6 numbers"},
      {h + "0 0 0 1 0 x\n", 2, "'x' is not a number"},
      {h + "0 0 0 1 0 1,5\n", 2, "'1,5' is not a number"},
      {h + "0 0 0 1 0 1e999\n", 2, "out of the range"},
      {h + "nan 0 0 1 0 0\n", 2, "not finite"},
      {h + "0 0 0 inf 0 0\n", 2, "not finite"},
      {h + "\n# c\n1 2 3 1 2 3\n", 4, "equals the eye"},
      {h + "near 5\nfar 1\n0 0 0 1 0 0\n", 4, "far"},
      {h + "0 0 0 0 5 0\n", 2, "parallel"},
      {h + "name a\nname b\n0 0 0 1 0 0\n", 3, "twice"},
  };
  for (size_t i = 0; i < std::size(cases); ++i) {
    testing::TempFile f("bad" + std::to_string(i) + ".path");
    testing::writeText(f.path, cases[i].text);
    const std::string m = messageOf([&] { readPathFile(f.path); });
    EXPECT_NE(m.find(f.path + ":" + std::to_string(cases[i].line) + ":"), std::string::npos)
        << "case " << i << ": " << m;
    EXPECT_NE(m.find(cases[i].reason), std::string::npos) << "case " << i << ": " << m;
  }
}

TEST(CameraPath, MissingPathFilesAndUnwritablePathsThrowNamingTheFile) {
  const std::string m = messageOf([] { readPathFile("/nonexistent/dir/x.path"); });
  EXPECT_NE(m.find("/nonexistent/dir/x.path"), std::string::npos) << m;
  const std::string w = messageOf([] { writePathFile(builtinPath("orbit", kCity, 3), "/nonexistent/dir/x.path"); });
  EXPECT_NE(w.find("/nonexistent/dir/x.path"), std::string::npos) << w;
  CameraPath bad = builtinPath("orbit", kCity, 3);
  bad.name = "a#b";
  EXPECT_THROW(writePathFile(bad, "/tmp/unused.path"), Error);
}

}  // namespace
}  // namespace tessera::mta
