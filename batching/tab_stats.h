// The figures of a batched scene that Trapp & Döllner's Table 1 and §5.1 report, computed from a
// TabScene: sizes (#Vertex, #Texture, |B_I|, b_average), output and geometry batches, arrays, the TAM's
// memory O_TAM and the texture memory of originals versus arrays.
//
// O_TAM(n) = Σ p · units(M_i) (§5.1), reported in bytes with p = 36: 4 bytes for i_TAM in texcoord z per
// mesh unit and 32 for its TAM entry (two RGBA32F texels: arrayID, layer, alpha cutoff, opaque flag;
// base-colour factor). The paper's p counts values (its Table 1 has O_TAM = 3 · #Texture: the index and
// the entry's two values), reported as o_tam_paper_values.
// Texture bytes: `originals` is every distinct texture the batched meshes use, mip chains included;
// `arrays` what the arrays hold (a texture used in two output batches is a layer in both), so
// arrays - originals is what batching duplicates. Untextured and BLEND meshes are counted apart.
// Does not implement: frame counters (raster/counters.h), timing.
#pragma once

#include <nlohmann/json.hpp>

#include "batching/tab_scene.h"

namespace tessera::batching {

nlohmann::json tableOneJson(const TabScene& scene);

}  // namespace tessera::batching
