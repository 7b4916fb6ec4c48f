// Internal to the scenes library: the scene functions and the frame preamble they share.
#pragma once

#include <functional>

#include "tools/scenes/builder.h"

namespace tessera::scenes {

struct Frame {
  ResourceId color = kNone, depth = kNone;
};
// Creates an RGBA8 colour target (and a D32F depth target), binds it, sets the full viewport and
// clears colour (and depth to 1).
Frame beginFrame(CommandList& cl, int w, int h, bool withDepth, std::array<float, 4> clear);

void buildFillFan(CommandList& cl, int w, int h);
void buildMipTunnel(CommandList& cl, int w, int h);
void buildWrapFilter(CommandList& cl, int w, int h);
void buildTextureArray(CommandList& cl, int w, int h);
void buildLayeredTarget(CommandList& cl, int w, int h);
void buildClipPlanes(CommandList& cl, int w, int h);
// clip_planes' frame with `editMesh` applied to the disc and then the floor before they are bound
// (far_vertices moves vertices with it).
void buildClipPlanesWith(CommandList& cl, int w, int h, const std::function<void(Mesh&)>& editMesh);
void buildBlend(CommandList& cl, int w, int h);
void buildDepth(CommandList& cl, int w, int h);
void buildCityBlock(CommandList& cl, int w, int h);
void buildCityBlockTab(CommandList& cl, int w, int h);
void buildCityIds(CommandList& cl, int w, int h);
void buildProvokingVertex(CommandList& cl, int w, int h);
void buildArrayLayers(CommandList& cl, int w, int h);
void buildAtlasClip(CommandList& cl, int w, int h);
void buildLodLevels(CommandList& cl, int w, int h);
void buildS3tcBlocks(CommandList& cl, int w, int h);
void buildDepthTies(CommandList& cl, int w, int h);
void buildFarVertices(CommandList& cl, int w, int h);
void buildAlphaMask(CommandList& cl, int w, int h);
void buildAtlasCapture(CommandList& cl, int w, int h);
void buildAtlasCaptureTab(CommandList& cl, int w, int h);
void buildAtlasSprites(CommandList& cl, int w, int h);
void buildRttaFive(CommandList& cl, int w, int h);
void buildRttaFiveAtlas(CommandList& cl, int w, int h);
void buildRttaFiveTransparent(CommandList& cl, int w, int h);
void buildRttaFiveGhosted(CommandList& cl, int w, int h);
void buildRttaFiveGhostedAo(CommandList& cl, int w, int h);
void buildRttaFiveAoPost(CommandList& cl, int w, int h);
void buildLightMap(CommandList& cl, int w, int h);

}  // namespace tessera::scenes
