// Validation of a paging file's metadata (docs/mta-format.md, "Validation", lists every rule).
//
// Implements: validateMetadata, run by PagingFile on open (so by `mta info` and every reader): every
// numeric field finite and in its documented range, every index in range, and the structure that the
// consumers rely on without further checks: the node table is a tree in depth-first pre-order within the
// format's depth, whose leaves partition the triangles (runtime_geometry.h writes one vertex record per
// triangle and leaf); the block directory is the gap-free sequence of blocks the writer appends, with
// exactly one atlas block per (tree, node, layer) and original-texture blocks exactly tiled by their
// image pieces, so no image, atlas or block read goes past its data (texture_cache.h, residency.h); each
// leaf lists exactly the images its triangles use, so the memory manager loads what a leaf drawn with
// its original textures samples (traversal.h). The rules are those the builder (build.cpp) follows, so
// every file it writes passes.
// Does not implement: decoding the metadata (paging_file.cpp: counts and array lengths against the
// metadata size, the layer count, wrap modes), block payload checksums (PagingFile::readBlock).
#pragma once

#include <cstdint>
#include <string>

#include "base/resource_limits.h"
#include "mta/paging_file.h"

namespace tessera::mta {

// Throws Error("<path>: <record>[<index>].<field>: <reason>") for the first violation found.
// metaOffset: where the metadata starts (the block area is [128, metaOffset)).
void validateMetadata(const MtaMeta& meta, const std::string& path, uint64_t metaOffset, const ResourceLimits& limits);

}  // namespace tessera::mta
