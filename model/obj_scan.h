// Internal to tessera_model: the checks of an OBJ file's text before tinyobjloader reads it
// (load_obj.cpp).
//
// Implements: one pass over the OBJ text, split into lines and statements exactly as tinyobjloader 2.0rc10
// splits them, that throws Error("<file>:<line>: <reason>") for what tinyobjloader would silently
// accept, wrap or read out of bounds:
// - an `f` / `l` / `p` index that is missing or 0, that does not fit in 32 bits (tinyobjloader's atoi
//   wraps 99999999999999999999 to -1, the last vertex), or that names a `v` / `vt` / `vn` that does not
//   exist: a positive index past the file's count (tinyobjloader keeps it, and reads outside its
//   arrays when it triangulates), a negative one reaching before the first;
// - faces whose triangulation would take more than kTriangulationWork steps (tinyobjloader's ear
//   clipping costs about k^2 for a face of k corners: a million-corner face would run for hours);
// - an `mtllib` naming no file, a missing file, something that is not a regular file, or the OBJ itself
//   (tinyobjloader warns and goes on with a default material, or reads the OBJ as a material library);
// - an `mtllib` statement inside a material library (MTL files cannot include others).
// It also counts the triangles the faces will make (k - 2 per face of k >= 3 corners), so that the
// triangle budget is checked before tinyobjloader allocates anything, and reads every material library
// once, in the order the file names them.
// Does not implement: parsing numbers or materials (tinyobjloader does, from the same text).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace tessera::model::detail {

// Ear-clipping steps (the sum of k^2 over faces of k > 4 corners) one OBJ file may ask for: about a
// second of tinyobjloader's work. Real files need a tiny fraction of it.
constexpr uint64_t kTriangulationWork = uint64_t(1) << 28;

struct MaterialLibrary {
  std::string path;  // resolved beside the OBJ
  std::string text;
};

struct ObjScan {
  uint64_t triangles = 0;                  // k - 2 per face of k >= 3 corners (tinyobjloader makes at most that)
  std::vector<MaterialLibrary> libraries;  // every library the mtllib statements name, once, in order
};

// `text` is the whole OBJ file `path`.
ObjScan scanObj(const std::string& path, const std::string& text);

}  // namespace tessera::model::detail
