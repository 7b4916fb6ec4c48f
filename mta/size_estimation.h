// Texture size estimation and required atlas area (thesis §4.5.2, paper §5.2.1-5.2.2).
//
// Implements: the per-triangle minimum texture size w_tex = |s_world| · f_proj, h_tex = |t_world| · f_proj
// with s_world = P_T(Tex_T⁻¹((1,0))), t_world = P_T(Tex_T⁻¹((0,1))) and the thesis's degenerate cases;
// the per-texture requirement (max over its triangles); the required atlas area from the texcoord
// bounding rectangle A_tex (partial use and repetition) plus a border of b texels, and the source
// rectangle: A_tex scaled about its centre so that the border holds real texture content.
// Does not implement: packing (packing.h), critical triangles (critical.h).
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "mta/scene.h"

namespace tessera::mta {

// Required texels for one repetition (the unit square of texture space) for one triangle.
struct TexelSize {
  double w = 0.0, h = 0.0;
  bool constant = false;  // t0 = t1 = t2: one colour, fixed 1 x 1 (§4.5.2)
  bool ignored = false;   // world-degenerate (zero area): not relevant for rendering
};

// Degenerate cases (§4.5.2): world-degenerate -> ignored; t0 = t1 = t2 -> constant (1x1); texcoords
// collinear with a non-degenerate longest edge e = (ti, tj) -> |s_world| = |t_world| = |vi - vj| / |ti - tj|.
// World degeneracy uses a relative tolerance of 1e-12 on the doubled area; texture degeneracy 1e-3
// (|det(t1 - t0, t2 - t0)| <= 1e-3 · longest texture edge², a Tessera choice, docs/mta-build.md). Arithmetic is IEEE double (sqrt only).
TexelSize triangleTexelSize(const glm::vec3 v[3], const glm::vec2 t[3], double fProj);

// The texcoord bounding rectangle A_tex (texture space, unbounded: repetition kept).
struct TexRect {
  double u0 = 1e300, v0 = 1e300, u1 = -1e300, v1 = -1e300;
  void add(const glm::vec2& t);
  bool empty() const { return u0 > u1; }
  double width() const { return u1 - u0; }
  double height() const { return v1 - v0; }
};

// What one texture needs in one atlas: inner size (texels covering A_tex), total size with border,
// and the source rectangle (A_tex scaled about its centre by total/inner on each axis).
struct AreaRequirement {
  uint32_t innerW = 1, innerH = 1;
  uint32_t w = 1, h = 1;  // inner + 2 · border
  TexRect source;
};

// Largest inner extent considered; larger requirements are clamped (they are critical anyway).
constexpr double kMaxInnerExtent = double(1u << 30);

// inner = max(1, ceil(min(size, imageExtent) · extent(A_tex))) per axis; constant textures get 1 x 1.
// Capping at the image's own size is a Tessera choice (docs/mta-build.md): more atlas texels than the
// original has cannot add detail. uncappedW/H (optional) receive size · extent(A_tex) without the cap.
AreaRequirement requiredArea(const TexelSize& size, const TexRect& atex, uint32_t imageW, uint32_t imageH,
                             uint32_t border, double* uncappedW = nullptr, double* uncappedH = nullptr);

// Integer shift (du, dv) that moves a triangle's texcoords so their minimum lies in [0, 1) (REPEAT) or
// [0, 2) (MIRRORED_REPEAT); 0 for CLAMP_TO_EDGE. Sampling with the wrap mode is unchanged by it, and it
// keeps A_tex of a node small when its triangles use a repeated texture at different integer offsets
// (a Tessera choice, docs/mta-build.md). Atlas texcoords are computed from t - shift.
std::pair<double, double> repeatShift(const glm::vec2 t[3], model::Wrap wrapS, model::Wrap wrapT);

}  // namespace tessera::mta
