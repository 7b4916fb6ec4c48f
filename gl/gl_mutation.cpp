#include "gl/gl_mutation.h"

#include <type_traits>
#include <utility>

#include "base/error.h"
#include "gl/gl_api.h"
#include "gl/gl_enums.h"

namespace tessera::gl {
namespace {

// GLSL pieces shared by several mutants.

// 4 instead of 8 sub-pixel bits: the window position of every vertex in front of the eye rounded to
// 1/16 pixel in the last vertex stage. GL then snaps to its own 1/256 grid, which keeps the 1/16
// grid points (the round trip NDC -> window -> NDC in float lands within 1/256 of them).
constexpr std::string_view kSnap16 =
    "uniform vec4 tessera_mutViewport;\n"
    "vec4 tessera_snap16(vec4 p) {\n"
    "  if (!(p.w > 0.0)) return p;\n"
    "  const vec2 halfSize = 0.5 * tessera_mutViewport.zw;\n"
    "  const vec2 centre = tessera_mutViewport.xy + halfSize;\n"
    "  vec2 win = (p.xy / p.w) * halfSize + centre;\n"
    "  win = floor(win * 16.0 + 0.5) / 16.0;\n"
    "  return vec4(((win - centre) / halfSize) * p.w, p.zw);\n"
    "}\n";

constexpr std::string_view kMulMat4 = "vec4 mulMat4(int base, vec4 v) {";
constexpr std::string_view kVsPosition = "gl_Position = mulMat4(0, a_position);";
// Why a unorm result one step below round-to-nearest is legal (blend_truncate, unorm_truncate).
constexpr std::string_view kTruncationIsConforming =
    "GL 4.6 §2.3.5.2 converts a float r to unorm with convert_float_uint, which returns one of the two b-bit "
    "values closest to r, rounding to nearest being only preferred; blending (§17.3.6.1) is done at no less than "
    "the destination's precision and converted the same way. The mutant only ever moves a value by less than "
    "half an LSB before that conversion, so every stored value is one of the two neighbours of the exact one: "
    "a conforming GL may store it, and a verdict that kills this mutant rejects a conforming GL";
constexpr std::string_view kTexturedLookup = "const vec4 texel = texture(tex0, v_st, u[8].x);";

std::vector<Mutation> build() {
  std::vector<Mutation> m;
  auto add = [&](Mutation x) { m.push_back(std::move(x)); };

  // --- rasterization ---------------------------------------------------------------------------
  add({"fill_rule_flipped",
       "the rasterizer's tie rule for sample points on an edge reversed (bottom-right instead of top-left)",
       "state",
       "glViewportIndexedf moves every viewport by one sub-pixel step (+1/256, -1/256): a sample exactly on an edge "
       "is decided by that shift, i.e. included on right and bottom edges instead of left and top ones",
       "GL 4.6 §14.6.1 fixes no fill convention: it only demands that a sample on an edge shared by two "
       "polygons be produced by exactly one of them, which a consistently reversed rule (and a one-sub-pixel "
       "shift of every vertex) keeps. The shift is also within the EDGE_TIE derivation of docs/crosscheck.md "
       "(an implementation may round each vertex to any neighbouring 1/256 grid point). A scene killing it "
       "shows the verdict rejecting a conforming GL",
       {},
       StateFault::FillRuleFlipped});
  {
    Mutation x{"subpixel_bits_4",
               "a rasterizer that snaps to 4 sub-pixel bits while it reports GL_SUBPIXEL_BITS = 8",
               "source",
               "the last vertex stage of every twin rounds the window position of each vertex to 1/16 px "
               "(viewport read from GL through a mutant uniform)",
               "",
               {},
               StateFault::None};
    for (std::string_view p : {"flat_color", "object_id", "texarray_batch", "textured", "vertex_color"}) {
      x.edits.push_back({p, kMulMat4, "@SNAP@"});
      x.edits.push_back({p, kVsPosition, "gl_Position = tessera_snap16(mulMat4(0, a_position));"});
    }
    x.edits.push_back({"atlas_displace", "float clipDistance(int i, float d)", "@SNAP@"});
    x.edits.push_back({"atlas_displace", "gl_Position = vec4(px, py, p.z, w);",
                       "gl_Position = tessera_snap16(vec4(px, py, p.z, w));"});
    add(std::move(x));
  }
  add({"viewport_off_by_one",
       "a viewport origin off by one pixel (y flipped with H - y instead of H - y - 1)",
       "state",
       "every SetViewport is issued with y + 1",
       "",
       {},
       StateFault::ViewportOffByOne});
  add({"scissor_off_by_one",
       "an inclusive scissor right edge",
       "state",
       "every SetScissor is issued with width + 1",
       "",
       {},
       StateFault::ScissorOffByOne});
  add({"varyings_noperspective",
       "perspective-incorrect varyings (screen-space interpolation)",
       "source",
       "the fragment inputs of textured and vertex_color are declared noperspective",
       "",
       {{"textured", "layout(location = 0) in vec2 v_st;", "layout(location = 0) noperspective in vec2 v_st;"},
        {"vertex_color", "layout(location = 0) in vec4 v_color;",
         "layout(location = 0) noperspective in vec4 v_color;"}},
       StateFault::None});
  add({"provoking_vertex_first",
       "the wrong provoking vertex (first instead of last) for flat varyings",
       "state",
       "glProvokingVertex(GL_FIRST_VERTEX_CONVENTION) after every UseProgram",
       "",
       {},
       StateFault::ProvokingFirst});
  add({"front_face_flipped",
       "the front-face winding inverted (CW taken for CCW), so culling removes the wrong faces",
       "state",
       "every SetRasterState is issued with glFrontFace(CW) for CCW and the reverse",
       "",
       {},
       StateFault::FrontFaceFlipped});
  add({"clip_planes_ignored",
       "enabled user clip distances ignored by the clipper",
       "source",
       "vertex_color writes 0 (inside) to every gl_ClipDistance",
       "",
       {{"vertex_color", "gl_ClipDistance[c] = ((tessera_clipMask >> uint(c)) & 1u) != 0u ? d : 0.0;",
         "gl_ClipDistance[c] = 0.0;"}},
       StateFault::None});
  add({"clip_from_displaced",
       "clip distances computed from the displaced position instead of the undisplaced one",
       "source",
       "atlas_displace's geometry stage takes clip distances 0-3 from x' = (a x + b y) + tx w, y' = (c x + d y) + ty w",
       "",
       {{"atlas_displace", "precise float c0 = w + x, c1 = w - x, c2 = w + y, c3 = w - y;",
         "precise float dx = (m.x * x + m.y * y) + tr.x * w, dy = (m.z * x + m.w * y) + tr.y * w;\n"
         "    precise float c0 = w + dx, c1 = w - dx, c2 = w + dy, c3 = w - dy;"}},
       StateFault::None});

  add({"ao_crease_sign_flipped",
       "a sign slip in a post-process comparison: convex edges taken for concave creases",
       "source",
       "atlas_sprite_ao counts a pair as occluding when its second difference is below +bias instead of -bias",
       "",
       {{"atlas_sprite_ao", "second < -u[8].x", "second < u[8].x"}},
       StateFault::None});

  // --- per-fragment operations -----------------------------------------------------------------
  add({"depth_strict_swapped",
       "depth comparison strictness swapped (LESS <-> LEQUAL, GREATER <-> GEQUAL)",
       "state",
       "every SetDepthState is issued with the strict and non-strict functions exchanged",
       "",
       {},
       StateFault::DepthStrictSwapped});
  add({"blend_subtract_swapped",
       "blend equations SUBTRACT and REVERSE_SUBTRACT exchanged (operand order)",
       "state",
       "every SetBlendState is issued with SUBTRACT <-> REVERSE_SUBTRACT",
       "",
       {},
       StateFault::BlendSubtractSwapped});
  {
    Mutation x{"blend_truncate",
               "a blend unit that truncates its result to 8 bits instead of rounding it",
               "source",
               "while GL_BLEND is on, flat_color, vertex_color and textured lower their RGB output by 0.49 LSB before "
               "blending, so a blend with source factor ONE stores floor(x) for every x at least 0.01 LSB above a "
               "step; other factors lower the result by factor x 0.49 LSB: always less than half an LSB",
               kTruncationIsConforming,
               {},
               StateFault::None};
    x.edits.push_back({"flat_color", "void main() { o_color = u[4]; }",
                       "uniform float tessera_mutBlend;\n"
                       "void main() { o_color = u[4] - vec4(vec3(tessera_mutBlend * (0.49 / 255.0)), 0.0); }"});
    x.edits.push_back({"vertex_color", "void main() { o_color = v_color; }",
                       "uniform float tessera_mutBlend;\n"
                       "void main() { o_color = v_color - vec4(vec3(tessera_mutBlend * (0.49 / 255.0)), 0.0); }"});
    x.edits.push_back({"textured", "layout(binding = 0) uniform sampler2D tex0;",
                       "layout(binding = 0) uniform sampler2D tex0;\nuniform float tessera_mutBlend;"});
    x.edits.push_back({"textured", "o_color = texel * u[7];",
                       "o_color = texel * u[7] - vec4(vec3(tessera_mutBlend * (0.49 / 255.0)), 0.0);"});
    add(std::move(x));
  }
  add({"unorm_truncate",
       "float to unorm8 conversion of colour outputs truncating instead of rounding to nearest",
       "source",
       "flat_color, vertex_color and textured lower their RGB output by 0.49 LSB, blended or not: every stored "
       "value becomes floor(255 x) unless 255 x is within 0.01 of the next step, and always one of the two "
       "representable neighbours of the exact value",
       kTruncationIsConforming,
       {{"flat_color", "void main() { o_color = u[4]; }",
         "void main() { o_color = u[4] - vec4(vec3(0.49 / 255.0), 0.0); }"},
        {"vertex_color", "void main() { o_color = v_color; }",
         "void main() { o_color = v_color - vec4(vec3(0.49 / 255.0), 0.0); }"},
        {"textured", "o_color = texel * u[7];", "o_color = texel * u[7] - vec4(vec3(0.49 / 255.0), 0.0);"}},
       StateFault::None,
       "OUTPUT_ROUNDING: float to unorm rounds to nearest (GL 4.6 section 2.3.5.2 only prefers it; both Mesa "
       "rasterizers do it, and accepting either neighbour at every unorm pixel would hide one-LSB faults)"});
  add({"rb_swap",
       "red and blue exchanged (an RGBA8 texture taken as BGRA8)",
       "source",
       "textured reads its texture through .bgra",
       "",
       {{"textured", kTexturedLookup, "const vec4 texel = texture(tex0, v_st, u[8].x).bgra;"}},
       StateFault::None});

  add({"layer_texcoord_swapped",
       "a second texture layer sampled at the first layer's texcoords (a varying or attribute location mix-up)",
       "source",
       "textured_layers looks its light map up at v_st0 instead of v_st1",
       "",
       {{"textured_layers", "const vec4 layer = texture(tex1, v_st1, u[8].x);",
         "const vec4 layer = texture(tex1, v_st0, u[8].x);"}},
       StateFault::None});

  // --- texture sampling --------------------------------------------------------------------------
  add({"texel_centre_1_64",
       "texel centres off by 1/64 texel (a fixed-point texel coordinate rounded wrongly)",
       "source",
       "textured adds 1/64 of a level-0 texel to (s, t) before the lookup",
       "",
       {{"textured", kTexturedLookup,
         "const vec4 texel = texture(tex0, v_st + vec2(1.0 / 64.0) / vec2(textureSize(tex0, 0)), u[8].x);"}},
       StateFault::None});
  add({"lod_bias_plus_1_8",
       "a LOD computed 1/8 too high",
       "source",
       "textured adds 1/8 to its shader LOD bias",
       "",
       {{"textured", kTexturedLookup, "const vec4 texel = texture(tex0, v_st, u[8].x + 0.125);"}},
       StateFault::None});
  add({"lod_bias_minus_1_8",
       "a LOD computed 1/8 too low",
       "source",
       "textured subtracts 1/8 from its shader LOD bias",
       "",
       {{"textured", kTexturedLookup, "const vec4 texel = texture(tex0, v_st, u[8].x - 0.125);"}},
       StateFault::None});
  add({"lambda_truncated",
       "the mip level for NEAREST_MIPMAP_* chosen by truncating lambda instead of rounding it",
       "source",
       "textured samples with textureLod(trunc(lambda)), lambda = textureQueryLod(...).y + shader bias: under "
       "NEAREST_MIPMAP_* that picks level floor(lambda) where GL picks ceil(lambda + 1/2) - 1",
       "",
       {{"textured", kTexturedLookup,
         "const vec4 texel = textureLod(tex0, v_st, trunc(textureQueryLod(tex0, v_st).y + u[8].x));"}},
       StateFault::None});
  add({"mag_min_switch_0_5",
       "the magnification/minification switch point at lambda = 0.5 where GL demands 0",
       "source",
       "textured magnifies (textureLod(..., 0)) where 0 < lambda <= 0.5, whatever the filters; GL 4.6 §8.15 "
       "puts the switch at c = 0.5 only for a LINEAR mag filter with a NEAREST_MIPMAP_* min filter, else at 0",
       "",
       {{"textured", kTexturedLookup,
         "const vec4 minified = texture(tex0, v_st, u[8].x);\n"
         "  const vec4 magnified = textureLod(tex0, v_st, 0.0);\n"
         "  const float lambda = textureQueryLod(tex0, v_st).y + u[8].x;\n"
         "  const vec4 texel = (lambda > 0.0 && lambda <= 0.5) ? magnified : minified;"}},
       StateFault::None});
  add({"wrap_repeat_mirrored",
       "wrap modes REPEAT and MIRRORED_REPEAT exchanged in the driver's enum table",
       "state",
       "every sampler is created with REPEAT <-> MIRRORED_REPEAT",
       "",
       {},
       StateFault::WrapRepeatMirrored});
  add({"wrap_edge_border",
       "wrap modes CLAMP_TO_EDGE and CLAMP_TO_BORDER exchanged",
       "state",
       "every sampler is created with CLAMP_TO_EDGE <-> CLAMP_TO_BORDER",
       "",
       {},
       StateFault::WrapEdgeBorder});
  add({"border_color_ignored",
       "the sampler's border colour never uploaded (transparent black)",
       "state",
       "every sampler is created with border colour (0, 0, 0, 0)",
       "",
       {},
       StateFault::BorderColorIgnored});
  add({"bc1_endpoints_swapped",
       "a driver that reads the two RGB565 endpoints of a DXT1 block in the wrong order",
       "state",
       "every BC1 block is uploaded with color0 and color1 exchanged and its codes unchanged: codes 0 and 1 swap "
       "colours, and a four-colour block (color0 > color1) becomes a three-colour one (midpoint and black)",
       "",
       {},
       StateFault::Bc1EndpointsSwapped});
  add({"filter_nearest_linear",
       "texel filters NEAREST and LINEAR exchanged",
       "state",
       "every sampler is created with NEAREST <-> LINEAR in the mag filter and in the texel part of the min filter",
       "",
       {},
       StateFault::FilterNearestLinear});
  add({"mipmap_linear_as_nearest",
       "the mip filter *_MIPMAP_LINEAR done as *_MIPMAP_NEAREST (no blend between levels)",
       "state",
       "every sampler is created with *_MIPMAP_LINEAR replaced by *_MIPMAP_NEAREST",
       "",
       {},
       StateFault::MipmapLinearNearest});
  add({"sampler_lod_bias_ignored",
       "the sampler's TEXTURE_LOD_BIAS ignored",
       "state",
       "every sampler is created with LOD bias 0",
       "",
       {},
       StateFault::SamplerLodBiasIgnored});
  add({"derivatives_fine",
       "fine derivatives where the shader asks for coarse ones",
       "source",
       "texarray_batch uses dFdxFine / dFdyFine instead of dFdxCoarse / dFdyCoarse",
       "GLSL 4.50 §8.14.1 lets dFdxCoarse / dFdyCoarse be computed from the current fragment's own neighbours "
       "(\"possibly, but not necessarily\" coarser than dFdxFine), so an implementation that answers every coarse "
       "derivative with the fine one conforms; the oracle's HELPER_DERIV class accepts both LODs for that reason",
       {{"texarray_batch", "dFdxCoarse(st)", "dFdxFine(st)"}, {"texarray_batch", "dFdyCoarse(st)", "dFdyFine(st)"}},
       StateFault::None});

  // --- texture arrays and batching ---------------------------------------------------------------
  add({"layer_floor",
       "the array layer chosen by floor(r) instead of floor(r + 1/2)",
       "source",
       "texarray_batch passes r - 1/2 as the layer coordinate, so GL's floor(r' + 1/2) is floor(r)",
       "",
       {{"texarray_batch", "const vec3 p = vec3(st, tae.y);", "const vec3 p = vec3(st, tae.y - 0.5);"}},
       StateFault::None});
  add({"tam_index_truncated",
       "the texture-array mapping index truncated instead of rounded",
       "source",
       "texarray_batch computes the TAM index as floor(z) instead of floor(z + 1/2)",
       "",
       {{"texarray_batch", "floor(double(v_str.z) + 0.5lf)", "floor(double(v_str.z))"}},
       StateFault::None});
  return m;
}

std::string replaceAll(std::string s, std::string_view find, std::string_view repl, size_t& count) {
  for (size_t pos = s.find(find); pos != std::string::npos; pos = s.find(find, pos + repl.size())) {
    s.replace(pos, find.size(), repl);
    ++count;
  }
  return s;
}

// Placeholders for the long shared pieces (so the catalogue above stays readable).
std::string expand(std::string_view replace, std::string_view find) {
  if (replace == "@SNAP@") return std::string(kSnap16) + std::string(find);
  if (replace == "@SNAP@") return std::string(kSnap16) + std::string(find);
  return std::string(replace);
}

Wrap swapWrap(Wrap w, Wrap a, Wrap b) { return w == a ? b : w == b ? a : w; }

Filter swapTexelFilter(Filter f) {
  switch (f) {
    case Filter::Nearest:
      return Filter::Linear;
    case Filter::Linear:
      return Filter::Nearest;
    case Filter::NearestMipmapNearest:
      return Filter::LinearMipmapNearest;
    case Filter::LinearMipmapNearest:
      return Filter::NearestMipmapNearest;
    case Filter::NearestMipmapLinear:
      return Filter::LinearMipmapLinear;
    case Filter::LinearMipmapLinear:
      return Filter::NearestMipmapLinear;
    default:
      return f;
  }
}

GLenum swapStrict(CompareFunc f) {
  switch (f) {
    case CompareFunc::Less:
      return GL_LEQUAL;
    case CompareFunc::LEqual:
      return GL_LESS;
    case CompareFunc::Greater:
      return GL_GEQUAL;
    case CompareFunc::GEqual:
      return GL_GREATER;
    default:
      return glCompareFunc(f);
  }
}

GLenum swapSubtract(BlendEq e) {
  if (e == BlendEq::Subtract) return GL_FUNC_REVERSE_SUBTRACT;
  if (e == BlendEq::ReverseSubtract) return GL_FUNC_SUBTRACT;
  return glBlendEquation(e);
}

// Sets the mutant uniforms of the current program from GL's current state.
void setMutationUniforms() {
  GLint program = 0;
  glGetIntegerv(GL_CURRENT_PROGRAM, &program);
  if (program == 0) return;
  if (const GLint loc = glGetUniformLocation(GLuint(program), kMutationViewportUniform); loc >= 0) {
    GLint v[4];
    glGetIntegerv(GL_VIEWPORT, v);
    glProgramUniform4f(GLuint(program), loc, float(v[0]), float(v[1]), float(v[2]), float(v[3]));
  }
  if (const GLint loc = glGetUniformLocation(GLuint(program), kMutationBlendUniform); loc >= 0)
    glProgramUniform1f(GLuint(program), loc, glIsEnabled(GL_BLEND) ? 1.0f : 0.0f);
}

}  // namespace

const std::vector<Mutation>& mutationCatalogue() {
  static const std::vector<Mutation> m = build();
  return m;
}

const Mutation* findMutation(std::string_view name) {
  for (const Mutation& m : mutationCatalogue())
    if (m.name == name) return &m;
  return nullptr;
}

std::string Mutation::applyToSource(std::string_view program, std::string_view text) const {
  std::string s(text);
  for (const SourceEdit& e : edits) {
    if (e.program != program) continue;
    size_t count = 0;
    s = replaceAll(std::move(s), e.find, expand(e.replace, e.find), count);
    if (count == 0)
      throw Error("mutant " + std::string(name) + ": raster/programs/" + std::string(program) + ".glsl has no '" +
                  std::string(e.find) + "' to replace");
  }
  return s;
}

void Mutation::applyToState(const Command& c) const {
  std::visit(
      [&](const auto& cmd) {
        using T = std::decay_t<decltype(cmd)>;
        if constexpr (std::is_same_v<T, SetViewport>) {
          const Rect& r = cmd.rect;
          if (state == StateFault::FillRuleFlipped)
            glViewportIndexedf(0, float(r.x) + 1.0f / 256.0f, float(r.y) - 1.0f / 256.0f, float(r.w), float(r.h));
          if (state == StateFault::ViewportOffByOne) glViewport(r.x, r.y + 1, r.w, r.h);
        }
        if constexpr (std::is_same_v<T, SetScissor>) {
          const Rect& r = cmd.state.rect;
          if (state == StateFault::ScissorOffByOne) glScissor(r.x, r.y, r.w + 1, r.h);
        }
        if constexpr (std::is_same_v<T, SetDepthState>) {
          if (state == StateFault::DepthStrictSwapped) glDepthFunc(swapStrict(cmd.state.func));
        }
        if constexpr (std::is_same_v<T, SetBlendState>) {
          if (state == StateFault::BlendSubtractSwapped)
            glBlendEquationSeparate(swapSubtract(cmd.state.eqRgb), swapSubtract(cmd.state.eqAlpha));
        }
        if constexpr (std::is_same_v<T, SetRasterState>) {
          if (state == StateFault::FrontFaceFlipped) glFrontFace(cmd.state.frontCcw ? GL_CW : GL_CCW);
        }
        if constexpr (std::is_same_v<T, UseProgram>) {
          if (state == StateFault::ProvokingFirst) glProvokingVertex(GL_FIRST_VERTEX_CONVENTION);
        }
        if constexpr (std::is_same_v<T, UseProgram> || std::is_same_v<T, SetViewport> ||
                      std::is_same_v<T, SetBlendState>) {
          if (!edits.empty()) setMutationUniforms();
        }
      },
      c);
}

SamplerState Mutation::applyToState(const SamplerState& in) const {
  SamplerState s = in;
  switch (state) {
    case StateFault::WrapRepeatMirrored:
      s.wrapS = swapWrap(s.wrapS, Wrap::Repeat, Wrap::MirroredRepeat);
      s.wrapT = swapWrap(s.wrapT, Wrap::Repeat, Wrap::MirroredRepeat);
      break;
    case StateFault::WrapEdgeBorder:
      s.wrapS = swapWrap(s.wrapS, Wrap::ClampToEdge, Wrap::ClampToBorder);
      s.wrapT = swapWrap(s.wrapT, Wrap::ClampToEdge, Wrap::ClampToBorder);
      break;
    case StateFault::FilterNearestLinear:
      s.magFilter = swapTexelFilter(s.magFilter);
      s.minFilter = swapTexelFilter(s.minFilter);
      break;
    case StateFault::MipmapLinearNearest:
      if (s.minFilter == Filter::LinearMipmapLinear) s.minFilter = Filter::LinearMipmapNearest;
      if (s.minFilter == Filter::NearestMipmapLinear) s.minFilter = Filter::NearestMipmapNearest;
      break;
    case StateFault::SamplerLodBiasIgnored:
      s.lodBias = 0.0f;
      break;
    case StateFault::BorderColorIgnored:
      s.borderColor = {0, 0, 0, 0};
      break;
    default:
      break;
  }
  return s;
}

std::vector<uint8_t> Mutation::applyToUpload(const TextureDesc& d, std::span<const uint8_t> bytes) const {
  if (state != StateFault::Bc1EndpointsSwapped || d.compression != BcFormat::BC1) return {};
  std::vector<uint8_t> out(bytes.begin(), bytes.end());
  for (size_t b = 0; b + 8 <= out.size(); b += 8) {
    std::swap(out[b + 0], out[b + 2]);
    std::swap(out[b + 1], out[b + 3]);
  }
  return out;
}

}  // namespace tessera::gl
