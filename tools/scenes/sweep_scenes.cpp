#include "tools/scenes/sweep_scenes.h"

#include <algorithm>
#include <cstdint>

#include "base/error.h"
#include "tools/scenes/scene_common.h"

namespace tessera::scenes {

namespace {

// A checkerboard with pseudo-random texel noise, so neighbouring texels differ (a flat texture would let
// a filter's fast path skip work that a real texture needs).
RgbaImage noisyChecker(uint32_t size) {
  RgbaImage img = checker(size, size, 16, {200, 180, 150, 255}, {60, 80, 110, 255});
  Rng rng{0x5eedf111u};
  for (size_t i = 0; i < img.rgba.size(); i += 4)
    for (size_t c = 0; c < 3; ++c) img.rgba[i + c] = uint8_t(std::min<uint32_t>(255, img.rgba[i + c] + rng.below(48)));
  return img;
}

}  // namespace

CommandList buildFillLayers(int w, int h, std::string_view variant) {
  const auto& known = fillVariants();
  if (std::find(known.begin(), known.end(), variant) == known.end())
    throw Error("fill_layers: unknown variant '" + std::string(variant) +
                "' (known: trilinear, flat_color, trilinear_depth, trilinear_blend)");
  const bool flat = variant == "flat_color", depth = variant == "trilinear_depth", blend = variant == "trilinear_blend";
  CommandList cl;
  beginFrame(cl, w, h, depth, {0, 0, 0, 1});
  // Pixel coordinates: x in [0, w], y in [0, h]. ortho(..., -1, 1) maps z to NDC -z, so the layers at
  // z = -0.1, 0.15, 0.4, 0.65 come nearer one after the other.
  const glm::mat4 mvp = ortho(0, double(w), 0, double(h), -1, 1);
  ResourceId tex = kNone;
  if (!flat) {
    constexpr uint32_t kSize = 256;
    tex = uploadTexture(cl, noisyChecker(kSize), true);
  }
  Mesh m;
  // 1.5 texels per pixel: s spans 1.5 * w / 256 repeats across the target, t likewise.
  const float sMax = float(1.5 * double(w) / 256.0), tMax = float(1.5 * double(h) / 256.0);
  for (int l = 0; l < kFillLayers; ++l) {
    const float z = -0.1f + 0.25f * float(l);
    // Each layer's texture is shifted by a fraction of a texel grid, so layers do not sample alike.
    const float ds = 0.37f * float(l), dt = 0.21f * float(l);
    m.quad({0, 0, z}, {float(w), 0, z}, {float(w), float(h), z}, {0, float(h), z}, {ds, dt, 0, 0},
           {ds + sMax, dt, 0, 0}, {ds + sMax, dt + tMax, 0, 0}, {ds, dt + tMax, 0, 0});
  }
  bindMesh(cl, m);
  cl.useProgram(cl.createProgram(flat ? "flat_color" : "textured"));
  setMatrix(cl, 0, mvp);
  if (!flat) {
    setTexturedDefaults(cl);
    if (blend) setVec4(cl, 7, {1, 1, 1, 0.5f});
    SamplerState s;
    s.minFilter = Filter::LinearMipmapLinear;
    s.magFilter = Filter::Linear;
    cl.bindTexture(0, tex);
    cl.bindSampler(0, cl.createSampler(s));
  }
  if (depth) {
    DepthState d;
    d.test = true;
    d.func = CompareFunc::Less;
    cl.setDepthState(d);
  }
  if (blend) {
    BlendState b;
    b.enabled = true;
    b.srcRgb = b.srcAlpha = BlendFactor::SrcAlpha;
    b.dstRgb = b.dstAlpha = BlendFactor::OneMinusSrcAlpha;
    cl.setBlendState(b);
  }
  for (int l = 0; l < kFillLayers; ++l) {
    if (flat) setVec4(cl, 4, {0.2f + 0.2f * float(l), 0.5f, 0.8f - 0.15f * float(l), 1.0f});
    cl.drawIndexed(uint32_t(6 * l), 6);
  }
  return cl;
}

CommandList buildTinyTris(int w, int h, int triangles) {
  if (triangles < 1) throw Error("tiny_tris: the triangle count must be at least 1");
  CommandList cl;
  beginFrame(cl, w, h, false, {0, 0, 0, 1});
  // A grid of cols x rows cells over the target with at least `triangles` cells; triangle i sits at a
  // pseudo-random sub-pixel position inside cell i.
  int cols = 1;  // the fewest columns whose square-ish cells (cols^2 * h >= triangles * w) hold them all
  while (int64_t(cols) * int64_t(cols) * int64_t(h) < int64_t(triangles) * int64_t(w)) ++cols;
  const int rows = std::max(1, (triangles + cols - 1) / cols);
  const double cw = double(w) / cols, ch = double(h) / rows;
  Rng rng{0x7121e5u};
  Mesh m;
  m.vertices.reserve(size_t(triangles) * 3);
  m.indices.reserve(size_t(triangles) * 3);
  constexpr float kLeg = 1.41421356f;  // area 1 px
  for (int i = 0; i < triangles; ++i) {
    const double x0 = (i % cols) * cw, y0 = (i / cols) * ch;
    const float x = float(x0 + double(rng.unit()) * std::max(0.0, cw - 1.5));
    const float y = float(y0 + double(rng.unit()) * std::max(0.0, ch - 1.5));
    m.triangle({{x, y, 0}, {}, 0}, {{x + kLeg, y, 0}, {}, 0}, {{x, y + kLeg, 0}, {}, 0});
  }
  const uint32_t n = bindMesh(cl, m);
  cl.useProgram(cl.createProgram("flat_color"));
  setMatrix(cl, 0, ortho(0, double(w), 0, double(h), -1, 1));
  setVec4(cl, 4, {0.9f, 0.8f, 0.3f, 1.0f});
  cl.drawIndexed(0, n);
  return cl;
}

}  // namespace tessera::scenes
