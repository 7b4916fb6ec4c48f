// The GPU resources of a batched scene as CommandList recordings, shared by TAB's own frames
// (tab_record.h) and every other technique that draws batched geometry (RTTA's `--texturing tab`
// capture, rtta/rtta_record.h), so both bind the same texels, samplers and TAM layout.
// - a 2D texture: one scene texture with its mip chain;
// - a texture array: TextureKind::Tex2DArray of the array key's size and format with a full mip
//   chain, layer l = the scene texture of TextureArray::layers[l];
// - a TAM: texarray_batch's materials layout, an RGBA32F buffer texture with two texels per entry:
//   (arrayID, layer, alpha cutoff, opaque), then the base-colour factor;
// - the sampler of a wrap-mode pair: trilinear (LINEAR_MIPMAP_LINEAR, mag LINEAR).
// Does not implement: binding or drawing (the recorders decide the order).
#pragma once

#include "batching/tab_scene.h"
#include "raster/command_list.h"

namespace tessera::batching {

SamplerState tabSampler(WrapMode s, WrapMode t);
// A 2D texture with the scene texture's full mip chain.
ResourceId recordTexture2D(CommandList& cl, const TabScene& s, uint32_t texture);
ResourceId recordTextureArray(CommandList& cl, const TabScene& s, uint32_t array);
// `opaqueMaterials`: every entry with cutoff 0 and opaque 1 (RTTA captures one opaque surface per object).
ResourceId recordTam(CommandList& cl, const OutputBatch& b, bool opaqueMaterials = false);

}  // namespace tessera::batching
