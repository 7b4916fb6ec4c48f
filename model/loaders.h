// Internal to tessera_model: the per-format loaders behind loadModel() and what they share (paths,
// URIs, the double-precision node transform). Not a public interface.
#pragma once

#include <array>
#include <cmath>
#include <string>
#include <string_view>

#include "model/model.h"

namespace tessera::model::detail {

Model loadGltf(const std::string& path);    // load_gltf.cpp; hands glTF 1.0 to loadAssimp
Model loadObj(const std::string& path);     // load_obj.cpp
Model loadAssimp(const std::string& path);  // load_assimp.cpp

// Percent-decoding of a relative URI reference ("a%20b.png" -> "a b.png"); a "file://" prefix is dropped.
std::string uriDecode(std::string_view uri);
// `relative` (already decoded) resolved against the directory of `modelPath`; absolute paths pass.
std::string resolveBeside(const std::string& modelPath, const std::string& relative);
// Throws Error("<model>: <what>: texture file '<resolved>' (written as '<uri>') does not exist")
// unless `resolved` is a regular file.
void requireTextureFile(const std::string& modelPath, const std::string& what, const std::string& uri,
                        const std::string& resolved);

// A column-major 4x4 affine transform in double (m[c * 4 + r]), as glTF and Assimp store them.
struct Transform {
  std::array<double, 16> m{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  Transform operator*(const Transform& b) const {
    Transform r;
    for (int c = 0; c < 4; ++c)
      for (int row = 0; row < 4; ++row) {
        double s = 0.0;
        for (int k = 0; k < 4; ++k) s = s + m[k * 4 + row] * b.m[c * 4 + k];
        r.m[c * 4 + row] = s;
      }
    return r;
  }
  bool isIdentity() const { return *this == Transform{}; }
  bool operator==(const Transform&) const = default;
  Float3 point(const Float3& p) const {
    const double x = p.x, y = p.y, z = p.z;
    return {float(m[0] * x + m[4] * y + m[8] * z + m[12]), float(m[1] * x + m[5] * y + m[9] * z + m[13]),
            float(m[2] * x + m[6] * y + m[10] * z + m[14])};
  }
  double det3() const {
    return m[0] * (m[5] * m[10] - m[9] * m[6]) - m[4] * (m[1] * m[10] - m[9] * m[2]) +
           m[8] * (m[1] * m[6] - m[5] * m[2]);
  }
  // Transforms a normal by the inverse transpose of the upper 3x3 (the cofactor matrix; the
  // determinant's scale is removed by normalizing) and normalizes it (sqrt is correctly rounded).
  Float3 normal(const Float3& n) const {
    const double a = m[0], b = m[4], c = m[8], d = m[1], e = m[5], f = m[9], g = m[2], h = m[6], i = m[10];
    const double cof[9] = {e * i - f * h,    -(d * i - f * g), d * h - e * g,    -(b * i - c * h), a * i - c * g,
                           -(a * h - b * g), b * f - c * e,    -(a * f - c * d), a * e - b * d};
    const double x = cof[0] * n.x + cof[1] * n.y + cof[2] * n.z;  // cof is row-major: C[r][c] = cof[r * 3 + c]
    const double y = cof[3] * n.x + cof[4] * n.y + cof[5] * n.z;
    const double z = cof[6] * n.x + cof[7] * n.y + cof[8] * n.z;
    const double sign = det3() < 0.0 ? -1.0 : 1.0, len = std::sqrt(x * x + y * y + z * z);
    if (!(len > 0.0)) return n;
    return {float(sign * x / len), float(sign * y / len), float(sign * z / len)};
  }
};

}  // namespace tessera::model::detail
