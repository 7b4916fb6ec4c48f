// Algorithm 1 of texture-array batching (Trapp & Döllner 2015, §3), with the slips of the printed
// pseudo-code fixed (docs/tab.md lists each one):
// - one output batch and one geometry batch are open across meshes (line 3 opened a new one per mesh);
// - an array is full at d_max layers (line 6's `>` let it reach d_max + 1);
// - when a mesh needs more arrays than the open output batch has room for (a_max), the open batch is
//   emitted and the mesh starts a new one with a new array set and a new TAM (line 14 emitted without
//   starting over, so every later texture kept growing the same array set);
// - a mesh whose vertices would push the open geometry batch past b_max closes it; the next geometry
//   batch stays in the same output batch and shares its arrays and TAM (lines 18-21; the printed
//   algorithm emits a whole output batch there, while Table 1 and §5 count geometry batches per output
//   batch);
// - the last output batch is emitted (the printed loop never did).
// b counts vertices (3 per triangle, non-indexed as in the paper): the text says "primitives", but
// Table 1's b_average(B_O) equals #Vertex for data sets B-D.
//
// Implements: matchTextureArray (an array of the open output batch with the texture's key — resolution,
// format, wrap modes — and fewer than d_max layers; the earliest such array), addTexture (a texture
// already in the open output batch keeps its layer: a texture shared by meshes takes one layer), one
// TAM entry per mesh and texture unit (units(M_i) consecutive entries), and `update`: every vertex of the
// mesh gets i_TAE, its first entry, in texcoord z.
// Does not implement: reading the model (input_batches.h), files (tab_file.h), rendering (tab_record.h).
#pragma once

#include "batching/tab_scene.h"

namespace tessera::batching {

// Throws Error naming the parameter unless b_max > 3, 0 < d_max <= kMaxArrayLayers and
// 0 < a_max <= kMaxTabArrays. `where` prefixes the message (e.g. "tab build").
void validateParams(const TabParams& p, const std::string& where);

// Runs Algorithm 1 over scene.meshes (the Batched ones, in their order) and fills scene.arrays,
// scene.batches, each batched mesh's outputBatch / tamIndex and its vertices' i_TAM. Batched meshes must
// come first in scene.meshes and own consecutive vertices from 0. Throws Error when the parameters are
// invalid, when one mesh alone needs more than a_max arrays, or when a TAM would reach kMaxTamIndex
// entries.
void runAlgorithm1(TabScene& scene, const TabParams& params);

}  // namespace tessera::batching
