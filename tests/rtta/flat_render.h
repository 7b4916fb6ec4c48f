// Test helper: renders triangles with `flat_color` on the oracle and reports which pixels they cover,
// so parameterization tests can compare regions against the pixels the pipeline really produces.
#pragma once

#include <cstdint>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <vector>

#include "raster/command_list.h"
#include "raster/cpu_backend.h"

namespace tessera::rtta::testing {

// Covered pixels of `triangles` (3 positions each) seen through `mvp` in a w x h viewport at (0, 0):
// mask[y * w + x] != 0 where some triangle wrote (no depth test, no culling).
inline std::vector<uint8_t> coveredPixels(const std::vector<glm::vec3>& triangles, const glm::mat4& mvp, int w, int h) {
  CommandList cl;
  TextureDesc d;
  d.width = uint32_t(w);
  d.height = uint32_t(h);
  RenderTarget rt;
  rt.color[0] = cl.createTexture(d);
  cl.setRenderTarget(rt);
  cl.setViewport({0, 0, w, h});
  cl.clearColor(0, {0, 0, 0, 0});
  const auto* bytes = reinterpret_cast<const uint8_t*>(triangles.data());
  cl.bindVertexBuffer(cl.createBuffer(BufferKind::Vertex, {bytes, triangles.size() * sizeof(glm::vec3)}));
  VertexLayout l;
  l.stride = sizeof(glm::vec3);
  l.attribs[0] = {0, 3, AttribType::F32, 0};
  cl.setVertexLayout(l);
  cl.useProgram(cl.createProgram("flat_color"));
  std::vector<float> u(20);
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) u[c * 4 + r] = mvp[c][r];
  u[16] = u[17] = u[18] = u[19] = 1.0f;
  cl.setUniforms(0, u);
  cl.draw(0, uint32_t(triangles.size()));
  CpuBackend be(RenderOptions{.threads = 2});
  be.execute(cl);
  const TextureData* t = be.texture(rt.color[0]);
  std::vector<uint8_t> mask(size_t(w) * h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) mask[size_t(y) * w + x] = t->texel(0, 0, x, y)[3];
  return mask;
}

// The 12 triangles of an axis-aligned box.
inline void addBox(std::vector<glm::vec3>& tris, glm::vec3 lo, glm::vec3 hi) {
  const glm::vec3 c[8] = {{lo.x, lo.y, lo.z}, {hi.x, lo.y, lo.z}, {lo.x, hi.y, lo.z}, {hi.x, hi.y, lo.z},
                          {lo.x, lo.y, hi.z}, {hi.x, lo.y, hi.z}, {lo.x, hi.y, hi.z}, {hi.x, hi.y, hi.z}};
  const int f[12][3] = {{0, 1, 3}, {0, 3, 2}, {4, 7, 5}, {4, 6, 7}, {0, 4, 5}, {0, 5, 1},
                        {2, 3, 7}, {2, 7, 6}, {0, 2, 6}, {0, 6, 4}, {1, 5, 7}, {1, 7, 3}};
  for (const auto& t : f)
    for (int k : t) tris.push_back(c[k]);
}

}  // namespace tessera::rtta::testing
