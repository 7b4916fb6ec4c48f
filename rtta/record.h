// The per-object record of render-to-texture-atlas (Trapp & Döllner 2010, §2.1):
// R_ID = (B_world, B_viewport, B_atlas, l, T), plus the rectangles and the 2D transform they use.
// Conventions, fixed here once:
// - Pixel rectangles are half-open [x0, x1) x [y0, y1) in GL window coordinates (y up, origin at the
//   lower left of the viewport's target), so a region's pixel (x, y) has its centre at (x + ½, y + ½).
// - B_viewport and B_atlas include the border; both have the same size, and B_atlas - B_viewport is a
//   whole-pixel shift (computeTransform, transform.h).
// - T maps screen NDC to atlas NDC: x' = a x + b y + tx, y' = c x + d y + ty (b = c = 0 here: the
//   paper's T is "a translation and viewport scaling").
// Does not implement: computing records (parameterize.h), packing (packing.h), encoding (record_buffer.h).
#pragma once

#include <cstdint>
#include <glm/vec3.hpp>

namespace tessera::rtta {

// A world-space axis-aligned box; lo > hi on some axis means "no geometry".
struct Box3 {
  glm::dvec3 lo{0.0}, hi{-1.0};
  bool empty() const { return !(lo.x <= hi.x && lo.y <= hi.y && lo.z <= hi.z); }
};

struct PixelRect {
  int32_t x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  int32_t width() const { return x1 - x0; }
  int32_t height() const { return y1 - y0; }
  bool empty() const { return x1 <= x0 || y1 <= y0; }
  bool contains(int32_t x, int32_t y) const { return x >= x0 && x < x1 && y >= y0 && y < y1; }
  bool operator==(const PixelRect&) const = default;
};

// The 2D affine map of screen NDC to atlas NDC, as the program applies it (floats).
struct Affine2 {
  float a = 1, b = 0, c = 0, d = 1, tx = 0, ty = 0;
  bool operator==(const Affine2&) const = default;
};

// Why an object has no atlas region.
enum class Culled : uint8_t {
  No = 0,
  Empty,      // no geometry (empty B_world)
  Frustum,    // conservatively outside the view frustum
  OffScreen,  // its projected box misses the viewport after clipping to [-1, 1]²
};
const char* culledName(Culled c);

struct Record {
  uint32_t id = 0;          // the object id (index into the object list, < 2^24)
  Box3 world;               // B_world
  Culled culled = Culled::No;
  bool nearClipped = false;     // the box crossed the near plane and was clipped there
  bool wholeViewport = false;   // the projection fell back to the whole viewport (see parameterize.h)
  PixelRect viewport;       // B_viewport with its border, window pixels of the screen viewport
  PixelRect inner;          // B_viewport before addBorder (the clipped, outward-rounded projection)
  PixelRect atlas;          // B_atlas with its border, atlas pixels
  int32_t layer = -1;       // l; -1 = no layer (culled): the capture program drops the object
  Affine2 T;                // screen NDC -> atlas NDC
  bool visible() const { return culled == Culled::No; }
};

}  // namespace tessera::rtta
