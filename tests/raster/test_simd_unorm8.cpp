// The unorm8 conversion kernel of the colour write (raster/fragops_simd.h) on every SIMD target this
// build compiled and this CPU runs: toUnorm8's bytes for every kind of float (random bit patterns, so
// NaNs, infinities, denormals and huge values; the floats nearest to every rounding tie (k + 1/2) / 255;
// 0, 1 and their neighbours).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "raster/fragops.h"
#include "raster/fragops_simd.h"
#include "raster/simd_targets.h"

namespace tessera {
namespace {

std::vector<float> unorm8TestValues() {
  std::vector<float> v;
  std::mt19937 rng(8);
  for (int i = 0; i < 40000; ++i) {
    const uint32_t bits = rng();
    float f;
    std::memcpy(&f, &bits, sizeof f);
    v.push_back(f);
  }
  for (int k = 0; k <= 255; ++k) {
    const float tie = float((k + 0.5) / 255.0);
    v.push_back(tie);
    v.push_back(std::nextafter(tie, 0.0f));
    v.push_back(std::nextafter(tie, 2.0f));
    v.push_back(float(k) / 255.0f);
  }
  for (float f : {0.0f, -0.0f, 1.0f, std::nextafter(1.0f, 0.0f), std::nextafter(1.0f, 2.0f), std::nextafter(0.0f, 1.0f),
                  -std::nextafter(0.0f, 1.0f), std::numeric_limits<float>::infinity(),
                  -std::numeric_limits<float>::infinity(), std::numeric_limits<float>::quiet_NaN(),
                  std::numeric_limits<float>::max()})
    v.push_back(f);
  while (v.size() % 16 != 0) v.push_back(0.5f);
  return v;
}

TEST(SimdUnorm8, EveryTargetGivesToUnorm8sBytesForEveryKindOfFloat) {
  const std::vector<float> values = unorm8TestValues();
  std::vector<uint8_t> expect(values.size());
  for (size_t i = 0; i < values.size(); ++i) expect[i] = detail::toUnorm8(values[i]);
  for (const std::string& target : simd::availableTargets()) {
    simd::forceTarget(target);
    const detail::Unorm8QuadFn kernel = detail::unorm8QuadKernel();
    std::vector<uint8_t> got(values.size());
    for (size_t i = 0; i < values.size(); i += 16) kernel(values.data() + i, got.data() + i);
    for (size_t i = 0; i < values.size(); ++i)
      ASSERT_EQ(int(got[i]), int(expect[i])) << "target " << target << ", value " << values[i] << " (index " << i << ")";
  }
  simd::forceTarget("best");
}

}  // namespace
}  // namespace tessera
