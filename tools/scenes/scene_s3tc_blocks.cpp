// s3tc_blocks: textures uploaded as S3TC blocks (TextureDesc::compression), sampled through GL's own
// decoder and the oracle's documented one (raster/bc_decode.h, spec-choices C1-C4). Left column BC1 (an
// opaque pattern: gradients, stripes and noise, so that most texels are interpolants), right column BC3 (the
// same colours with an alpha ramp, shown in the target's alpha). Top row: the lower-left 16x16 texels of 32x32
// textures magnified twice over 32 px with NEAREST (lambda = -1; pixel centres at a quarter of a texel from its
// edges), so GL's decoded texels reach the image unfiltered and only BC_INTERPOLANT can explain a difference
// (FILTER_PRECISION would hide it in a filtered lookup); bottom row: 64x64 textures minified over 22 px
// (LINEAR_MIPMAP_LINEAR, lambda = log2(64/22) = 1.54, levels 1 and 2 blended; no integer within 0.45). Every level is the box filter's
// (texture.h) encoded by stb_dxt (bc_encode.h), as the atlas tree stores them. Where GL rounds an
// interpolant the other way, the pixel is BC_INTERPOLANT (docs/crosscheck.md).
#include "raster/bc_encode.h"
#include "raster/texture.h"
#include "tools/scenes/scene_common.h"

namespace tessera::scenes {

namespace {

std::vector<uint8_t> pattern(uint32_t size, bool alpha) {
  std::vector<uint8_t> px(size_t(size) * size * 4);
  uint32_t state = 2463534242u;
  for (uint32_t y = 0; y < size; ++y)
    for (uint32_t x = 0; x < size; ++x) {
      state ^= state << 13, state ^= state >> 17, state ^= state << 5;  // xorshift32: fixed noise
      uint8_t* p = &px[(size_t(y) * size + x) * 4];
      p[0] = uint8_t(x * 255 / (size - 1));
      p[1] = uint8_t(((x + y) / 3 % 2) ? 200 : 60);
      p[2] = uint8_t(y * 255 / (size - 1) / 2 + (state >> 27));
      p[3] = alpha ? uint8_t(40 + (x + 2 * y) * 200 / (3 * (size - 1))) : 255;
    }
  return px;
}

ResourceId compressedTexture(CommandList& cl, uint32_t size, bool alpha) {
  TextureDesc d;
  d.width = d.height = size;
  d.levels = fullMipCount(size, size);
  d.compression = alpha ? BcFormat::BC3 : BcFormat::BC1;
  const ResourceId tex = cl.createTexture(d);
  const std::vector<std::vector<uint8_t>> chain = buildMipChainRGBA8(size, size, pattern(size, alpha));
  for (uint32_t l = 0; l < d.levels; ++l) {
    const uint32_t s = levelWidth(d, l);
    cl.uploadTexture(tex, l, 0, encodeBcLevel(d.compression, s, s, chain[l]));
  }
  return tex;
}

}  // namespace

void buildS3tcBlocks(CommandList& cl, int w, int h) {
  beginFrame(cl, w, h, false, {0, 0, 0, 1});
  // Cells of 64 x 64 px: top quads 32 px over 16 texels (s, t in [0, 1/2]), bottom quads 22 px over 64 texels.
  Mesh m;
  for (int row = 0; row < 2; ++row)
    for (int col = 0; col < 2; ++col) {
      const float side = row == 1 ? 32.0f : 22.0f, st = row == 1 ? 0.5f : 1.0f;
      const float x0 = float(col * 64 + 16), y0 = float(row * 64 + 16);
      m.quad({x0, y0, 0}, {x0 + side, y0, 0}, {x0 + side, y0 + side, 0}, {x0, y0 + side, 0}, {0, 0, 0, 0},
             {st, 0, 0, 0}, {st, st, 0, 0}, {0, st, 0, 0});
    }
  bindMesh(cl, m);
  cl.useProgram(cl.createProgram("textured"));
  setMatrix(cl, 0, ortho(0, w, 0, h, -1, 1));
  setTexturedDefaults(cl);
  SamplerState tri;
  tri.minFilter = Filter::LinearMipmapLinear;
  SamplerState nearest;
  nearest.minFilter = Filter::Nearest;
  nearest.magFilter = Filter::Nearest;
  const ResourceId samplers[2] = {cl.createSampler(tri), cl.createSampler(nearest)};
  // Quads in order: (row 0: minified, trilinear) BC1, BC3; (row 1: magnified, nearest) BC1, BC3; six indices each.
  const ResourceId small[2] = {compressedTexture(cl, 32, false), compressedTexture(cl, 32, true)};
  const ResourceId large[2] = {compressedTexture(cl, 64, false), compressedTexture(cl, 64, true)};
  for (int q = 0; q < 4; ++q) {
    if (q % 2 == 0) cl.bindSampler(0, samplers[q / 2]);
    cl.bindTexture(0, q < 2 ? large[q] : small[q - 2]);
    cl.drawIndexed(uint32_t(q * 6), 6);
  }
}

}  // namespace tessera::scenes
