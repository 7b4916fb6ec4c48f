// The paging file the validation tests edit: an 8 x 8 grid of textured quads with a second layer and
// RGBA quads (two trees, RGB and RGBA; inner nodes with 2 and 4 children; 32 x 32 facades and 16 x 16
// layer-1 images, each far smaller than a block, so each original block holds one image in format
// version 2), built once per test process. And the message a PagingFile opening a path throws, and the check
// that an edit of it is refused.
#pragma once

#include <gtest/gtest.h>

#include <functional>
#include <string>

#include "base/error.h"
#include "base/resource_limits.h"
#include "mta/build.h"
#include "mta/paging_file.h"
#include "mta_file_edit.h"
#include "mta_test_scene.h"

namespace tessera::mta::testing {

struct GridTreeFile {
  TempFile file{"good.mta"};
  GridTreeFile() {
    BuildParams p;
    p.atlasSize = 64;
    p.border = 2;
    p.tanHalfFov = 0.5;
    p.screenWidth = 256;
    p.dMin = 2.0;
    p.encoding = BlockEncoding::Raw;  // the edits assume raw block sizes and row pieces
    buildMta(gridScene(8, 8, 32, 2.0f, true, true), p, file.path);
  }
  const MtaMeta& meta() const {
    static const PagingFile f(file.path);
    return f.meta();
  }
};

inline const GridTreeFile& good() {
  static const GridTreeFile g;
  return g;
}

// The Error opening `path` throws, or "" when it opens.
inline std::string errorOf(const std::string& path, const ResourceLimits& limits = {}) {
  try {
    const PagingFile f(path, limits);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

// Opens `good` with `edit` applied (mta_file_edit.h) and expects an Error that names the file, contains
// `field` (the record, index and field) and `reason`.
inline void expectRefused(const std::function<void(MtaMeta&)>& edit, const std::string& field,
                          const std::string& reason) {
  TempFile bad("bad.mta");
  rewriteMetadata(good().file.path, bad.path, edit);
  const std::string m = errorOf(bad.path);
  ASSERT_FALSE(m.empty()) << "accepted; expected an error about " << field;
  EXPECT_EQ(m.rfind(bad.path + ": ", 0), 0u) << m;
  EXPECT_NE(m.find(": " + field + ": "), std::string::npos) << m;
  EXPECT_NE(m.find(reason), std::string::npos) << m;
}

}  // namespace tessera::mta::testing
