// blend: a grey-to-colour gradient background, then a 5 x 4 grid of half-transparent quads:
// columns ADD, SUBTRACT, REVERSE_SUBTRACT, MIN, MAX; rows: (SRC_ALPHA, ONE_MINUS_SRC_ALPHA),
// (ONE, ONE), (DST_COLOR, ZERO), (CONSTANT_COLOR, ONE_MINUS_CONSTANT_ALPHA) with alpha factors
// (SRC_ALPHA_SATURATE, ONE).
#include "tools/scenes/scene_common.h"

namespace tessera::scenes {

void buildBlend(CommandList& cl, int w, int h) {
  beginFrame(cl, w, h, false, {0, 0, 0, 1});
  cl.useProgram(cl.createProgram("vertex_color"));
  setMatrix(cl, 0, ortho(0, 5, 0, 4, -1, 1));
  Mesh m;
  m.quad({0, 0, 0}, {5, 0, 0}, {5, 4, 0}, {0, 4, 0}, {0.1f, 0.1f, 0.1f, 0.2f}, {0.9f, 0.2f, 0.1f, 1.0f},
         {0.1f, 0.8f, 0.9f, 0.6f}, {0.5f, 0.5f, 0.5f, 0.0f});
  for (int i = 0; i < 20; ++i) {
    const float x = float(i % 5) + 0.1f, y = float(i / 5) + 0.1f;
    m.quad({x, y, 0}, {x + 0.8f, y, 0}, {x + 0.8f, y + 0.8f, 0}, {x, y + 0.8f, 0}, {0.9f, 0.1f, 0.3f, 0.25f},
           {0.2f, 0.9f, 0.3f, 0.5f}, {0.2f, 0.3f, 1.0f, 0.75f}, {1.0f, 1.0f, 0.2f, 1.0f});
  }
  bindMesh(cl, m);
  cl.drawIndexed(0, 6);
  const BlendEq eqs[5] = {BlendEq::Add, BlendEq::Subtract, BlendEq::ReverseSubtract, BlendEq::Min, BlendEq::Max};
  const BlendFactor src[4] = {BlendFactor::SrcAlpha, BlendFactor::One, BlendFactor::DstColor, BlendFactor::ConstantColor};
  const BlendFactor dst[4] = {BlendFactor::OneMinusSrcAlpha, BlendFactor::One, BlendFactor::Zero,
                              BlendFactor::OneMinusConstantAlpha};
  for (int i = 0; i < 20; ++i) {
    BlendState b;
    b.enabled = true;
    b.eqRgb = b.eqAlpha = eqs[i % 5];
    b.srcRgb = src[i / 5];
    b.dstRgb = dst[i / 5];
    b.srcAlpha = i / 5 == 3 ? BlendFactor::SrcAlphaSaturate : src[i / 5];
    b.dstAlpha = i / 5 == 3 ? BlendFactor::One : dst[i / 5];
    b.constant = {0.25f, 0.5f, 0.75f, 0.4f};
    cl.setBlendState(b);
    cl.drawIndexed(uint32_t(6 + 6 * i), 6);
  }
}

}  // namespace tessera::scenes
