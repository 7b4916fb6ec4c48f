// The run-time tests' atlas tree: a 12 x 12 wall of textured unit quads in the x-y plane, built with
// small atlases and a small d_min so the tree is several levels deep; built once per test process.
#pragma once

#include <memory>

#include "mta/build.h"
#include "mta/paging_file.h"
#include "mta_test_scene.h"

namespace tessera::mta::testing {

struct WallTreeFile {
  TempFile file{"wall.mta"};
  std::unique_ptr<PagingFile> tree;
  WallTreeFile() {
    BuildParams p;
    p.atlasSize = 64;
    p.border = 2;
    p.dMin = 1.5;
    p.screenWidth = 256;
    p.threads = 2;
    buildMta(gridScene(12, 12, 32, 2.0f), p, file.path);
    tree = std::make_unique<PagingFile>(file.path);
  }
};

inline WallTreeFile& fixture() {
  static WallTreeFile f;
  return f;
}

}  // namespace tessera::mta::testing
