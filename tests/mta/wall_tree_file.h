// The run-time tests' atlas tree: a 12 x 12 wall of textured unit quads in the x-y plane, built with
// small atlases and a small d_min so the tree is several levels deep; built once per test process, with
// S3TC blocks (fixture(), as `mta build` stores them) and with raw blocks (rawFixture()).
#pragma once

#include <memory>

#include "mta/build.h"
#include "mta/paging_file.h"
#include "mta_test_scene.h"

namespace tessera::mta::testing {

struct WallTreeFile {
  TempFile file;
  std::unique_ptr<PagingFile> tree;
  explicit WallTreeFile(BlockEncoding encoding = BlockEncoding::S3tc) : file(encoding == BlockEncoding::Raw ? "wall_raw.mta" : "wall.mta") {
    BuildParams p = smallTreeParams();
    p.encoding = encoding;
    buildMta(gridScene(12, 12, 32, 2.0f), p, file.path);
    tree = std::make_unique<PagingFile>(file.path);
  }
};

inline WallTreeFile& fixture() {
  static WallTreeFile f;
  return f;
}

inline WallTreeFile& rawFixture() {
  static WallTreeFile f(BlockEncoding::Raw);
  return f;
}

}  // namespace tessera::mta::testing
