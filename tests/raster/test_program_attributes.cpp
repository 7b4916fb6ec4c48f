// Program::attributesRead (raster/program.h): the vertex stage fetches only the locations a program
// declares (cpu_backend.cpp, fetchGroup). A declaration that left out a location the program reads
// would shade that attribute as GL's default (0, 0, 0, 1) instead of its value, silently. So every
// built-in program is shaded twice over the same vertices, once with every location holding values and
// once with the undeclared locations at GL's default, and the two outputs must be the same bytes.
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "raster/program.h"

namespace tessera {
namespace {

constexpr size_t kProgramVertices = 70;  // more than one 64-vertex group of the vertex stage

// Deterministic values: small integers and quarters, so that a location a program reads as an id or a
// shift (object_id, atlas_sprite) holds a value it converts without saturating.
float programAttributeValue(size_t vertex, int location, int component) {
  const uint32_t h = uint32_t(vertex) * 2654435761u ^ uint32_t(location * 4 + component) * 40503u;
  return float(h >> 26) + 0.25f * float(h >> 8 & 3);
}

std::vector<VertexIn> programInputs(uint32_t keep) {
  std::vector<VertexIn> in(kProgramVertices);
  for (size_t v = 0; v < kProgramVertices; ++v) {
    in[v].vertexId = uint32_t(v);
    for (int l = 0; l < kMaxAttribs; ++l)
      for (int c = 0; c < 4; ++c)
        in[v].attr[l][size_t(c)] = (keep >> l & 1) ? programAttributeValue(v, l, c) : (c == 3 ? 1.0f : 0.0f);
  }
  return in;
}

std::vector<VertexOut> shadeProgram(const Program& p, const std::vector<VertexIn>& in) {
  std::vector<Vec4> uniforms(kMaxUniformSlots);
  for (int s = 0; s < kMaxUniformSlots; ++s)
    for (int c = 0; c < 4; ++c) uniforms[size_t(s)][size_t(c)] = 0.125f * float((s * 4 + c) % 11) - 0.5f;
  ShadeContext ctx;
  ctx.uniforms = uniforms.data();
  std::vector<VertexOut> out(in.size());
  std::memset(static_cast<void*>(out.data()), 0, out.size() * sizeof(VertexOut));  // as the vertex stage does
  p.shadeVertices(in, out, ctx);
  return out;
}

TEST(ProgramAttributes, EveryBuiltInProgramReadsOnlyTheLocationsItDeclares) {
  const std::vector<std::string_view> names = programNames();
  ASSERT_FALSE(names.empty());
  for (std::string_view name : names) {
    SCOPED_TRACE(std::string(name));
    const Program& p = *findProgram(name);
    const uint32_t declared = p.attributesRead();
    EXPECT_NE(declared & 1u, 0u) << "every built-in program reads its position from location 0";
    const std::vector<VertexOut> full = shadeProgram(p, programInputs(~0u));
    const std::vector<VertexOut> fetched = shadeProgram(p, programInputs(declared));
    for (size_t v = 0; v < kProgramVertices; ++v)
      ASSERT_EQ(std::memcmp(&full[v], &fetched[v], sizeof(VertexOut)), 0)
          << "vertex " << v << ": an attribute outside the declared mask 0x" << std::hex << declared
          << " changed the program's output";
  }
}

// The other direction: a declaration of more locations than the program reads passes the check above
// but fetches for nothing, so each declared location must change some output when reset to the default.
TEST(ProgramAttributes, EveryDeclaredLocationChangesSomeOutput) {
  for (std::string_view name : programNames()) {
    SCOPED_TRACE(std::string(name));
    const Program& p = *findProgram(name);
    const uint32_t declared = p.attributesRead();
    const std::vector<VertexOut> full = shadeProgram(p, programInputs(declared));
    for (int l = 0; l < kMaxAttribs; ++l) {
      if (!(declared >> l & 1)) continue;
      const std::vector<VertexOut> without = shadeProgram(p, programInputs(declared & ~(1u << l)));
      bool differs = false;
      for (size_t v = 0; v < kProgramVertices && !differs; ++v)
        differs = std::memcmp(&full[v], &without[v], sizeof(VertexOut)) != 0;
      EXPECT_TRUE(differs) << "location " << l << " is declared, but the program's outputs do not depend on it";
    }
  }
}

}  // namespace
}  // namespace tessera
