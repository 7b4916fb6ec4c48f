// Hard limits and fixed-point constants of the oracle, each with its derivation.
// One place for every number that decides a bit: a limit that is written twice drifts.
#pragma once

#include <cstdint>

namespace tessera {

// Texture units a frame may use (GL guarantees >= 16 combined fragment units; llvmpipe has 32).
constexpr int kMaxTextureUnits = 16;
// Render-target colour attachments (GL guarantees 8; the ID program needs 2).
constexpr int kMaxColorAttachments = 4;
// User clip distances (GL_MAX_CLIP_DISTANCES >= 8).
constexpr int kMaxClipDistances = 8;
// Float varyings per vertex and flat integer varyings per vertex.
constexpr int kMaxVaryings = 16;
constexpr int kMaxFlatVaryings = 4;
// Uniform storage: vec4 slots.
constexpr int kMaxUniformSlots = 64;

// Render-target and texture size limit: 16384 (= llvmpipe's MAX_TEXTURE_SIZE / MAX_VIEWPORT_DIMS).
constexpr int32_t kMaxTextureSize = 16384;
constexpr int32_t kMaxArrayLayers = 2048;  // llvmpipe's GL_MAX_ARRAY_TEXTURE_LAYERS
constexpr int32_t kMaxMipLevels = 15;      // log2(16384) + 1
// Buffer texture texel limit (llvmpipe: 134217728 texels).
constexpr uint32_t kMaxBufferTextureTexels = 1u << 27;

// Tile grid: 64x64 pixel tiles, the unit of parallel work (llvmpipe TILE_ORDER 6).
constexpr int kTileOrder = 6;
constexpr int kTileSize = 1 << kTileOrder;
// Blocks inside a tile for the trivial accept/reject fast path.
constexpr int kBlockSize = 8;

// Sub-pixel precision: 8 fractional bits (GL_SUBPIXEL_BITS of llvmpipe and D3D11/12).
constexpr int kSubpixelBits = 8;
constexpr int64_t kSubpixelOne = int64_t(1) << kSubpixelBits;
constexpr int64_t kSubpixelHalf = kSubpixelOne / 2;

// Guard band: x and y are clipped against |x_clip| <= kGuardBand * w_clip. With a viewport of at
// most 16384 px (half-extent 8192) at an offset of at most 16384 px, window coordinates stay within
// 16 * 8192 + 16384 + 8192 < 2^18 px = 2^26 sub-pixels. Edge deltas are then < 2^27 and every edge
// function product < 2^54, so int64 edge evaluation never overflows.
constexpr double kGuardBand = 16.0;

// LOD and sub-texel weights are quantized to 8 fractional bits (D3D11/12 MIP_LOD_FRACTIONAL_BIT_COUNT
// and SUBTEXEL_FRACTIONAL_BIT_COUNT; llvmpipe's AoS 8.8 path).
constexpr int kLodFracBits = 8;
constexpr int kSubtexelBits = 8;
// GL_MAX_TEXTURE_LOD_BIAS (llvmpipe reports 16).
constexpr float kMaxLodBias = 16.0f;

}  // namespace tessera
