// Preprocessing of texture-array batching (Trapp & Döllner 2015, §3 "Preparation of Input Data",
// Fig. 3 A): from a loaded model, the input batches B_I = (M_i, {T_t}) in a documented order, in one
// vertex format, with every texture decoded once.
//
// Implements: one input batch per model::Mesh; the split into batched meshes (textured, alpha mode
// OPAQUE or MASK), untextured meshes (drawn as one flat-colour draw, counted apart; a mesh whose
// material names a texture but which has no texcoords is untextured, with a note) and BLEND meshes
// (textured or not: never batched, drawn last); the conversion to non-indexed vertices
// (x, y, z, s, t, i_TAM = 0); the texture list (one TabTexture per distinct (image, wrapS, wrapT):
// a texture shared by meshes is decoded and stored once), decoded in parallel with full mip chains
// (raster/texture.h box filter); and the sort of the batched meshes by the key
//   (format, width, height, wrapS, wrapT, model texture index, model mesh index),
// so that meshes sharing an array key, and then a texture, are adjacent (docs/tab.md).
// Units: the importer gives every textured mesh one texture unit (the base colour). Algorithm 1
// (batcher.h) handles any number of units per mesh; the tests build two-unit inputs by hand.
// Does not implement: Algorithm 1 (batcher.h).
#pragma once

#include <functional>
#include <string>

#include "batching/tab_scene.h"
#include "model/model.h"

namespace tessera::batching {

struct InputOptions {
  // Called with (textures decoded so far, total) while decoding; may be empty.
  std::function<void(size_t, size_t)> progress;
};

// A TabScene with textures, meshes (batched in sort order, then untextured, then BLEND, each in model
// order) and vertices filled in; arrays and batches empty, every i_TAM 0. Throws Error naming the model
// and texture when a texture cannot be decoded, or when the vertex count exceeds uint32.
TabScene prepareInput(const model::Model& model, const InputOptions& options = {});

}  // namespace tessera::batching
