// Small programmatic scenes for the mta tests: quads with generated textures and repeating texcoords.
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <string>

#include "mta/build.h"
#include "mta/scene.h"

namespace tessera::mta::testing {

// The run-time tests' small trees: 64 x 64 atlases with 2-texel borders, sized for a 256-pixel screen and
// built on 2 threads, so that a dozen unit quads make a tree several levels deep.
inline BuildParams smallTreeParams(double dMin = 1.5) {
  BuildParams p;
  p.atlasSize = 64;
  p.border = 2;
  p.dMin = dMin;
  p.screenWidth = 256;
  p.threads = 2;
  return p;
}

// Appends the square [x0, x0 + size] x [y0, y0 + size] at height z to `g` as two opaque triangles
// (corners 0,1,2 and 0,2,3, counter-clockwise seen from +z), each its own source triangle. Layer l gets
// texture textures[l] (-1: none) and texcoords (0,0) .. (1,1) plus uvOffsets[l] (zero when not given);
// `textures` names every layer of g.
inline void addSquare(Geometry& g, float x0, float y0, float size, float z, std::initializer_list<int32_t> textures,
                      std::initializer_list<glm::vec2> uvOffsets = {}) {
  const glm::vec3 p[4] = {{x0, y0, z}, {x0 + size, y0, z}, {x0 + size, y0 + size, z}, {x0, y0 + size, z}};
  const glm::vec2 t[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  const int tri[2][3] = {{0, 1, 2}, {0, 2, 3}};
  EXPECT_EQ(textures.size(), g.layers.size()) << "addSquare names every layer's texture";
  for (int k = 0; k < 2; ++k) {
    for (int i = 0; i < 3; ++i) g.positions.push_back(p[tri[k][i]]);
    size_t l = 0;
    for (const int32_t texture : textures) {
      const glm::vec2 off = l < uvOffsets.size() ? uvOffsets.begin()[l] : glm::vec2(0.0f);
      for (int i = 0; i < 3; ++i) g.layers[l].uv.push_back(t[tri[k][i]] + off);
      g.layers[l].texture.push_back(texture);
      ++l;
    }
    g.source.push_back(uint32_t(g.source.size()));
    g.alpha.push_back(0);
  }
}

// A grid of nx x ny unit quads (2 triangles each) in the x-y plane, each with its own size x size texture
// repeated `repeats` times, texcoords offset by the quad index (so integer offsets differ). Optionally a
// second layer (a clamped texture per quad over the whole quad, texcoords (0,0) to (1,1): each quad maps it
// the same way through both triangles, as layer_maps.h requires) and RGBA quads every 5th.
inline Scene gridScene(int nx, int ny, uint32_t size = 32, float repeats = 2.0f, bool secondLayer = false, bool someAlpha = false) {
  Scene s;
  s.name = "grid";
  Geometry& g = s.geometry;
  g.layers.resize(secondLayer ? 2 : 1);
  const int quads = nx * ny;
  for (int q = 0; q < quads; ++q) {
    s.images.push_back(SceneImage{size, size, "img" + std::to_string(q)});
    s.textures.push_back(SceneTexture{uint32_t(q), model::Wrap::Repeat, model::Wrap::Repeat});
  }
  const int layer1Base = int(s.textures.size());
  for (int q = 0; q < quads; ++q) {
    const float x = float(q % nx), y = float(q / nx), off = float(q);
    const glm::vec3 p[4] = {{x, y, 0}, {x + 1, y, 0}, {x + 1, y + 1, 0}, {x, y + 1, 0}};
    const glm::vec2 t[4] = {{off, 0}, {off + repeats, 0}, {off + repeats, repeats}, {off, repeats}};
    const int tri[2][3] = {{0, 1, 2}, {0, 2, 3}};
    for (int k = 0; k < 2; ++k) {
      for (int i = 0; i < 3; ++i) {
        g.positions.push_back(p[tri[k][i]]);
        g.layers[0].uv.push_back(t[tri[k][i]]);
      }
      g.layers[0].texture.push_back(q);
      g.source.push_back(uint32_t(g.source.size()));
      g.alpha.push_back(someAlpha && q % 5 == 0 ? 1 : 0);
      if (secondLayer) {
        if (k == 0) {
          const uint32_t img = uint32_t(s.images.size());
          s.images.push_back(SceneImage{16, 16, "layer1_" + std::to_string(img)});
          s.textures.push_back(SceneTexture{img, model::Wrap::ClampToEdge, model::Wrap::ClampToEdge});
        }
        g.layers[1].texture.push_back(layer1Base + q);
        const glm::vec2 l1[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
        for (int i = 0; i < 3; ++i) g.layers[1].uv.push_back(l1[tri[k][i]]);
      }
    }
  }
  const std::vector<SceneImage> images = s.images;
  s.loadImage = [images](uint32_t i) {
    model::Image img;
    img.width = images[i].width, img.height = images[i].height;
    img.rgba.resize(size_t(img.width) * img.height * 4);
    for (uint32_t y = 0; y < img.height; ++y)
      for (uint32_t x = 0; x < img.width; ++x) {
        uint8_t* p = &img.rgba[(size_t(y) * img.width + x) * 4];
        p[0] = uint8_t(x * 7 + i * 31), p[1] = uint8_t(y * 5 + i * 17), p[2] = uint8_t((x ^ y) * 3 + i), p[3] = uint8_t(255 - (i % 7));
      }
    return img;
  };
  return s;
}

struct TempFile {
  std::string path;
  explicit TempFile(const std::string& name) {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path = (std::filesystem::temp_directory_path() /
            ("tessera_mta_" + std::to_string(::getpid()) + "_" + info->name() + "_" + name)).string();
  }
  ~TempFile() {
    std::error_code ec;
    std::filesystem::remove(path, ec);
  }
};

// Writes `text` to `path` byte for byte (binary, truncating).
inline void writeText(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary | std::ios::trunc) << text;
}

}  // namespace tessera::mta::testing
