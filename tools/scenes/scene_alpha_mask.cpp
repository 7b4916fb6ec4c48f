// alpha_mask: glTF materials (base-colour factor, alphaMode MASK / OPAQUE / BLEND, glTF 2.0 §3.9.4) in
// the baseline program "textured" (left column, one draw per material) and in "texarray_batch" with
// its materials TAM layout (right column, one draw for MASK + OPAQUE and one for BLEND, as BLEND meshes
// stay unbatched). Every quad samples one 32 x 32 RGBA8 texture whose alpha rises along the diagonal
// (texel (x, y): 4 + 4 x + 4 y, so the bilinear alpha is exactly 128 (s + t) / 255 inside; LINEAR,
// clamped), so the MASK row shows the cutoff as a diagonal boundary: below-left of it the fragments
// are discarded and the background stays; pixels whose legal alpha straddles the cutoff are
// ALPHA_TEST in the cross-check (docs/crosscheck.md). Rows, bottom to top:
// - MASK:   factor (1, 0.9, 0.7, 0.8), cutoff 0.5, opaque: written where 0.8 * 128 (s + t) >= 127.5;
// - OPAQUE: factor (0.6, 0.8, 1, 1), no cutoff, alpha forced to 1;
// - BLEND:  factor (1, 1, 1, 0.9), no cutoff, alpha kept, blended (SRC_ALPHA, ONE_MINUS_SRC_ALPHA).
#include "raster/texture.h"
#include "tools/scenes/scene_common.h"

namespace tessera::scenes {

namespace {
struct Material {
  glm::vec4 factor;
  float cutoff, opaque;
};
constexpr Material kMaterials[3] = {{{1.0f, 0.9f, 0.7f, 0.8f}, 0.5f, 1.0f},
                                    {{0.6f, 0.8f, 1.0f, 1.0f}, 0.0f, 1.0f},
                                    {{1.0f, 1.0f, 1.0f, 0.9f}, 0.0f, 0.0f}};

RgbaImage alphaGradient() {
  RgbaImage img = checker(32, 32, 32, {0, 0, 0, 0}, {0, 0, 0, 0});
  for (uint32_t y = 0; y < 32; ++y)
    for (uint32_t x = 0; x < 32; ++x) {
      uint8_t* p = &img.rgba[(size_t(y) * 32 + x) * 4];
      p[0] = uint8_t(250 - 6 * x), p[1] = uint8_t(60 + 6 * y), p[2] = uint8_t(((x / 4 + y / 4) % 2) ? 220 : 90);
      p[3] = uint8_t(4 + 4 * x + 4 * y);
    }
  return img;
}
}  // namespace

void buildAlphaMask(CommandList& cl, int w, int h) {
  beginFrame(cl, w, h, false, {0.11f, 0.15f, 0.2f, 1});  // no channel near a rounding tie
  const RgbaImage img = alphaGradient();
  SamplerState s;
  s.minFilter = Filter::Linear;
  s.wrapS = s.wrapT = Wrap::ClampToEdge;
  const ResourceId smp = cl.createSampler(s);
  // The scene spans 128 x 96 units (ortho), whatever the target size.
  Mesh m;
  for (int col = 0; col < 2; ++col)
    for (int row = 0; row < 3; ++row) {
      // The TAM entry arrives as row - 2^-10 on the right: the index rounds (floor(z + 1/2)) where the
      // paper's int() would truncate to the entry below (rows 1 and 2; row 0 survives truncation toward 0).
      const float x0 = float(4 + 64 * col), y0 = float(4 + 32 * row), z = float(row) - (col ? 1.0f / 1024.0f : 0.0f);
      m.quad({x0, y0, 0}, {x0 + 56, y0, 0}, {x0 + 56, y0 + 24, 0}, {x0, y0 + 24, 0}, {0, 0, z, 0}, {1, 0, z, 0},
             {1, 1, z, 0}, {0, 1, z, 0});
    }
  bindMesh(cl, m);
  BlendState blend;
  blend.enabled = true;
  blend.srcRgb = blend.srcAlpha = BlendFactor::SrcAlpha;
  blend.dstRgb = blend.dstAlpha = BlendFactor::OneMinusSrcAlpha;
  const glm::mat4 mvp = ortho(0, 128, 0, 96, -1, 1);

  // Baseline: "textured", the material in the tint (slot 7) and slot 8 = (bias, cutoff, opaque, 0).
  cl.useProgram(cl.createProgram("textured"));
  setMatrix(cl, 0, mvp);
  setTexturedDefaults(cl);
  cl.bindTexture(0, uploadTexture(cl, img, false));
  cl.bindSampler(0, smp);
  for (uint32_t i = 0; i < 3; ++i) {
    const Material& mat = kMaterials[i];
    setVec4(cl, 7, mat.factor);
    setVec4(cl, 8, {0.0f, mat.cutoff, mat.opaque, 0.0f});
    if (i == 2) cl.setBlendState(blend);
    cl.drawIndexed(6 * i, 6);
  }
  cl.setBlendState(BlendState{});

  // Batched: "texarray_batch", the same texture as layer 0 of an array, the materials in the TAM
  // (RGBA32F, two texels per entry: (array, layer, cutoff, opaque), factor).
  TextureDesc d;
  d.kind = TextureKind::Tex2DArray;
  d.width = d.height = 32;
  d.layers = 1;
  d.levels = 1;
  const ResourceId array = cl.createTexture(d);
  cl.uploadTexture(array, 0, 0, img.rgba);
  std::vector<float> tam;
  for (const Material& mat : kMaterials)
    tam.insert(tam.end(), {0.0f, 0.0f, mat.cutoff, mat.opaque, mat.factor.r, mat.factor.g, mat.factor.b, mat.factor.a});
  std::span<const uint8_t> tamBytes(reinterpret_cast<const uint8_t*>(tam.data()), tam.size() * sizeof(float));
  TextureDesc td;
  td.kind = TextureKind::Buffer;
  td.format = Format::RGBA32F;
  td.width = uint32_t(tam.size() / 4);
  td.buffer = cl.createBuffer(BufferKind::Texel, tamBytes);
  const ResourceId tamTex = cl.createTexture(td);
  cl.useProgram(cl.createProgram("texarray_batch"));
  setMatrix(cl, 0, mvp);
  setVec4(cl, 4, {1.0f, 0.0f, 0.0f, 0.0f});  // the materials layout
  cl.bindTexture(0, tamTex);
  cl.bindTexture(1, array);
  cl.bindSampler(1, smp);
  cl.drawIndexed(18, 12);  // MASK and OPAQUE: one draw
  cl.setBlendState(blend);
  cl.drawIndexed(30, 6);  // BLEND: drawn last, alone
}

}  // namespace tessera::scenes
