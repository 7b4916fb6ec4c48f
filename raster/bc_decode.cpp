// The S3TC decoder of the oracle (bc_decode.h). EXT_texture_compression_s3tc gives the interpolants as
// real-valued formulas ("(2*color0 + color1) / 3") and leaves their rounding to the implementation; the
// choices below are rows C1-C4 of docs/spec-choices.md.
#include "raster/bc_decode.h"

#include <cstring>
#include <string>

#include "base/error.h"

namespace tessera {

namespace {

struct Rgb {
  uint32_t r, g, b;
};

// Bit replication maps 0 -> 0 and the largest code -> 255 exactly, which the extension implies by
// calling the endpoints "RGB565 colours" to be converted to the texture's [0, 1] range.
Rgb expand565(uint16_t c) {
  const uint32_t r = (c >> 11) & 31u, g = (c >> 5) & 63u, b = c & 31u;
  return {(r << 3) | (r >> 2), (g << 2) | (g >> 4), (b << 3) | (b >> 2)};
}

// Round to nearest of (wa*a + wb*b) / d; d odd (3, 5, 7), so the exact quotient is never a half.
uint32_t lerpNearest(uint32_t a, uint32_t wa, uint32_t b, uint32_t wb, uint32_t d) {
  return (wa * a + wb * b + d / 2) / d;
}

// The colour half of a block (8 bytes). threeColourAllowed: BC1 honours color0 <= color1, BC3 never does.
void decodeColour(const uint8_t* p, bool threeColourAllowed, uint8_t* out) {
  const uint16_t c0 = uint16_t(p[0] | (p[1] << 8)), c1 = uint16_t(p[2] | (p[3] << 8));
  const uint32_t codes = uint32_t(p[4]) | (uint32_t(p[5]) << 8) | (uint32_t(p[6]) << 16) | (uint32_t(p[7]) << 24);
  const Rgb e0 = expand565(c0), e1 = expand565(c1);
  uint8_t palette[4][4];
  auto set = [&](int i, uint32_t r, uint32_t g, uint32_t b, uint32_t a) {
    palette[i][0] = uint8_t(r), palette[i][1] = uint8_t(g), palette[i][2] = uint8_t(b), palette[i][3] = uint8_t(a);
  };
  set(0, e0.r, e0.g, e0.b, 255);
  set(1, e1.r, e1.g, e1.b, 255);
  if (c0 > c1 || !threeColourAllowed) {
    set(2, lerpNearest(e0.r, 2, e1.r, 1, 3), lerpNearest(e0.g, 2, e1.g, 1, 3), lerpNearest(e0.b, 2, e1.b, 1, 3), 255);
    set(3, lerpNearest(e0.r, 1, e1.r, 2, 3), lerpNearest(e0.g, 1, e1.g, 2, 3), lerpNearest(e0.b, 1, e1.b, 2, 3), 255);
  } else {
    // A half can be a tie here: rounded up, as (c0 + c1 + 1) / 2 (spec-choices C2).
    set(2, (e0.r + e1.r + 1) / 2, (e0.g + e1.g + 1) / 2, (e0.b + e1.b + 1) / 2, 255);
    // GL_COMPRESSED_RGB_S3TC_DXT1_EXT: black, and the RGB format's alpha is 1.
    set(3, 0, 0, 0, 255);
  }
  for (uint32_t t = 0; t < 16; ++t) std::memcpy(out + 4 * t, palette[(codes >> (2 * t)) & 3u], 4);
}

// The alpha half of a BC3 block (8 bytes); writes alpha only.
void decodeAlpha(const uint8_t* p, uint8_t* out) {
  const uint32_t a0 = p[0], a1 = p[1];
  uint64_t codes = 0;
  for (int i = 0; i < 6; ++i) codes |= uint64_t(p[2 + i]) << (8 * i);
  uint32_t values[8] = {a0, a1, 0, 0, 0, 0, 0, 0};
  if (a0 > a1) {
    for (uint32_t i = 2; i < 8; ++i) values[i] = lerpNearest(a0, 8 - i, a1, i - 1, 7);
  } else {
    for (uint32_t i = 2; i < 6; ++i) values[i] = lerpNearest(a0, 6 - i, a1, i - 1, 5);
    values[6] = 0;
    values[7] = 255;
  }
  for (uint32_t t = 0; t < 16; ++t) out[4 * t + 3] = uint8_t(values[(codes >> (3 * t)) & 7u]);
}

uint32_t colourCodes(const uint8_t* p) {
  return uint32_t(p[4]) | (uint32_t(p[5]) << 8) | (uint32_t(p[6]) << 16) | (uint32_t(p[7]) << 24);
}

void checkLevel(const char* who, BcFormat f, uint32_t w, uint32_t h, std::span<const uint8_t> blocks) {
  if (f != BcFormat::BC1 && f != BcFormat::BC3)
    throw Error(std::string(who) + ": block format " + std::to_string(int(f)) + " is neither BC1 (1) nor BC3 (2)");
  if (w == 0 || h == 0 || blocks.size() != bcLevelBytes(f, w, h))
    throw Error(std::string(who) + ": " + bcFormatName(f) + " level of " + std::to_string(w) + "x" + std::to_string(h) +
                " needs " + std::to_string(bcLevelBytes(f, w, h)) + " bytes, got " + std::to_string(blocks.size()));
}

}  // namespace

const char* bcFormatName(BcFormat f) {
  return f == BcFormat::BC1 ? "BC1" : f == BcFormat::BC3 ? "BC3" : f == BcFormat::None ? "none" : "?";
}

void decodeBc1Block(const uint8_t* block, uint8_t* out) { decodeColour(block, true, out); }

void decodeBc3Block(const uint8_t* block, uint8_t* out) {
  decodeColour(block + 8, false, out);
  decodeAlpha(block, out);
}

void decodeBcLevelInto(BcFormat f, uint32_t w, uint32_t h, std::span<const uint8_t> blocks, std::span<uint8_t> out) {
  checkLevel("decodeBcLevel", f, w, h, blocks);
  if (out.size() != size_t(w) * h * 4)
    throw Error("decodeBcLevel: a " + std::to_string(w) + "x" + std::to_string(h) + " level decodes to " +
                std::to_string(size_t(w) * h * 4) + " bytes, but the output holds " + std::to_string(out.size()));
  const uint32_t bw = (w + 3) / 4, bh = (h + 3) / 4, bytes = bcBlockBytes(f);
  uint8_t texels[64];
  for (uint32_t by = 0; by < bh; ++by)
    for (uint32_t bx = 0; bx < bw; ++bx) {
      const uint8_t* block = blocks.data() + (size_t(by) * bw + bx) * bytes;
      if (f == BcFormat::BC1) decodeBc1Block(block, texels);
      else decodeBc3Block(block, texels);
      for (uint32_t y = 0; y < 4 && 4 * by + y < h; ++y)
        for (uint32_t x = 0; x < 4 && 4 * bx + x < w; ++x)
          std::memcpy(out.data() + ((size_t(4 * by + y) * w) + 4 * bx + x) * 4, texels + 4 * (4 * y + x), 4);
    }
}

std::vector<uint8_t> decodeBcLevel(BcFormat f, uint32_t w, uint32_t h, std::span<const uint8_t> blocks) {
  checkLevel("decodeBcLevel", f, w, h, blocks);
  std::vector<uint8_t> out(size_t(w) * h * 4);
  decodeBcLevelInto(f, w, h, blocks, out);
  return out;
}

std::vector<uint8_t> bcInterpolantChannels(BcFormat f, uint32_t w, uint32_t h, std::span<const uint8_t> blocks) {
  checkLevel("bcInterpolantChannels", f, w, h, blocks);
  std::vector<uint8_t> out(size_t(w) * h, 0);
  const uint32_t bw = (w + 3) / 4, bh = (h + 3) / 4, bytes = bcBlockBytes(f);
  for (uint32_t by = 0; by < bh; ++by)
    for (uint32_t bx = 0; bx < bw; ++bx) {
      const uint8_t* block = blocks.data() + (size_t(by) * bw + bx) * bytes;
      const uint8_t* colour = f == BcFormat::BC3 ? block + 8 : block;
      const uint16_t c0 = uint16_t(colour[0] | (colour[1] << 8)), c1 = uint16_t(colour[2] | (colour[3] << 8));
      const bool four = f == BcFormat::BC3 || c0 > c1;
      const uint32_t codes = colourCodes(colour);
      uint64_t alphaCodes = 0;
      if (f == BcFormat::BC3)
        for (int i = 0; i < 6; ++i) alphaCodes |= uint64_t(block[2 + i]) << (8 * i);
      const bool eightAlphas = f == BcFormat::BC3 && block[0] > block[1];
      for (uint32_t y = 0; y < 4 && 4 * by + y < h; ++y)
        for (uint32_t x = 0; x < 4 && 4 * bx + x < w; ++x) {
          const uint32_t t = 4 * y + x, code = (codes >> (2 * t)) & 3u;
          uint8_t mask = (code == 2 || (code == 3 && four)) ? 7 : 0;
          if (f == BcFormat::BC3) {
            const uint32_t a = uint32_t(alphaCodes >> (3 * t)) & 7u;
            if (a >= 2 && (eightAlphas || a <= 5)) mask |= 8;
          }
          out[size_t(4 * by + y) * w + 4 * bx + x] = mask;
        }
    }
  return out;
}

}  // namespace tessera
