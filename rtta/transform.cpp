#include "rtta/transform.h"

namespace tessera::rtta {

TransformInfo computeTransform(const Record& r, const AtlasSize& ta, const Rect& vp) {
  const double sx = double(r.atlas.x0) - r.viewport.x0, sy = double(r.atlas.y0) - r.viewport.y0;
  const double a = double(vp.w) / ta.width, d = double(vp.h) / ta.height;
  const double tx = (double(vp.w) + 2.0 * (vp.x + sx)) / ta.width - 1.0;
  const double ty = (double(vp.h) + 2.0 * (vp.y + sy)) / ta.height - 1.0;
  TransformInfo info;
  info.T = {float(a), 0.0f, 0.0f, float(d), float(tx), float(ty)};
  // Exact iff each float times the atlas size gives back the integer numerator the formula divides.
  info.exact = double(info.T.a) * ta.width == double(vp.w) && double(info.T.d) * ta.height == double(vp.h) &&
               (double(info.T.tx) + 1.0) * ta.width == double(vp.w) + 2.0 * (vp.x + sx) &&
               (double(info.T.ty) + 1.0) * ta.height == double(vp.h) + 2.0 * (vp.y + sy);
  return info;
}

size_t computeTransforms(std::span<Record> records, const AtlasSize& ta, const Rect& vp) {
  size_t inexact = 0;
  for (Record& r : records) {
    if (r.layer < 0) continue;
    const TransformInfo info = computeTransform(r, ta, vp);
    r.T = info.T;
    inexact += info.exact ? 0 : 1;
  }
  return inexact;
}

void inverseApply(const Affine2& T, double xAtlas, double yAtlas, double& xScreen, double& yScreen) {
  xScreen = (xAtlas - double(T.tx)) / double(T.a);
  yScreen = (yAtlas - double(T.ty)) / double(T.d);
}

}  // namespace tessera::rtta
