#include "tools/scenes/scenes.h"

#include "tools/scenes/scene_common.h"

namespace tessera::scenes {
namespace {
using BuildFn = void (*)(CommandList&, int, int);
struct Entry {
  SceneInfo info;
  BuildFn build;
};
const std::vector<Entry>& entries() {
  static const std::vector<Entry> e = {
      {{"fill_fan", "fill rule: fans whose edges pass exactly through pixel centres, additive blend shows gaps or double hits", 128, 128}, buildFillFan},
      {{"mip_tunnel", "LOD: a perspective tunnel over a texture whose levels have distinct tints, trilinear and nearest-mip halves", 256, 256}, buildMipTunnel},
      {{"wrap_filter", "every wrap mode x NEAREST / LINEAR / LINEAR_MIPMAP_LINEAR on texcoords from -1.5 to 2.5, border colour", 256, 192}, buildWrapFilter},
      {{"texture_array", "texture-array batching: 3 arrays of different sizes, a TAM buffer texture, one draw call", 256, 256}, buildTextureArray},
      {{"layered_target", "render-to-texture-atlas: objects displaced into regions of a 2-layer array target, then shown", 256, 128}, buildLayeredTarget},
      {{"clip_planes", "user clip distances: three enabled planes cutting a colour-ramp fan, plus near-plane clipping", 192, 192}, buildClipPlanes},
      {{"blend", "blending: every equation and a set of factors over a gradient, in RGBA8", 256, 128}, buildBlend},
      {{"depth", "depth: interpenetrating triangles under LESS, then GEQUAL / EQUAL / ALWAYS passes", 192, 192}, buildDepth},
      {{"city_block", "a textured city block: 256 facade textures, depth, ~60k triangles, one bind per facade", 320, 240}, buildCityBlock},
      {{"city_block_tab", "city_block batched with texture arrays (TAB): 256 facades in one 256-layer array, ground and buildings in one draw call", 320, 240}, buildCityBlockTab},
      {{"far_vertices", "clip_planes with every other vertex at x = -3.4e38: clipping at the limits of float (valid input)", 192, 192}, buildFarVertices},
      {{"city_ids", "the city block through the object_id program into two R32UI targets (object id, primitive id)", 320, 240}, buildCityIds},
      {{"provoking_vertex", "flat varyings: object_id with a different id on each vertex, so every pixel shows the provoking (last) vertex", 64, 64}, buildProvokingVertex},
      {{"array_layers", "array layer selection: texture-array lookups at fractional layers 0.3 .. 2.7, rounded (not truncated) to a layer", 192, 32}, buildArrayLayers},
      {{"atlas_clip", "render-to-texture-atlas clipping: clip distances from the undisplaced position cut a quad that the displacement moves inside", 64, 64}, buildAtlasClip},
      {{"lod_levels", "LOD without rho freedom: screen-aligned quads of constant isotropic lambda (0.25 .. 1.7) over a texture with one tint per level, trilinear and nearest-mip", 128, 64}, buildLodLevels},
      {{"depth_ties", "exact depth ties: sloped quads redrawn with the same vertices under LESS / LEQUAL / GREATER / GEQUAL, so only the non-strict functions pass", 160, 96}, buildDepthTies},
      {{"alpha_mask", "glTF materials: base-colour factors, alpha MASK (discard), OPAQUE and BLEND in textured and in texarray_batch's materials TAM, over an alpha gradient", 128, 96}, buildAlphaMask},
      {{"atlas_capture", "render-to-texture-atlas capture with depth: atlas_capture into a layered RGBA8 + RG32F (gl_FragCoord.z, covered) + D32F target, every layer presented", 96, 64}, buildAtlasCapture},
      {{"atlas_capture_tab", "atlas_capture's objects batched (TAB): atlas_capture_tab captures every object from one texture array in ONE draw call", 96, 64}, buildAtlasCaptureTab},
      {{"atlas_sprites", "render-to-texture-atlas compositing: atlas_sprite depth sprites from a hand-made atlas, gl_FragDepth decides overlaps, empty texels discarded", 64, 64}, buildAtlasSprites},
      {{"rtta_five_atlas", "render-to-texture-atlas on the five-object brake assembly: Algorithm 1 and one capture pass; the atlas colour and window-depth layers", 160, 160}, buildRttaFiveAtlas},
      {{"rtta_five", "render-to-texture-atlas: the five objects captured, then composited with depth sprites (gl_FragDepth from the atlas): the plain rendering again", 160, 160}, buildRttaFive},
      {{"rtta_five_transparent", "render-to-texture-atlas: the five objects composited translucent, back to front, no depth test (Fig. 3B)", 160, 160}, buildRttaFiveTransparent},
      {{"rtta_five_ghosted", "render-to-texture-atlas: ghosted view, the pad opaque and highlighted, the rest translucent (Fig. 3C)", 160, 160}, buildRttaFiveGhosted},
      {{"rtta_five_ghosted_ao", "render-to-texture-atlas: ghosted view with ambient occlusion and edges computed on the caliper's own atlas region (Fig. 3D; atlas_sprite_ao, not monotone: INPUT_INTERVAL)", 160, 160}, buildRttaFiveGhostedAo},
      {{"rtta_five_ao_post", "render-to-texture-atlas: ghosted-ao's post-process alone, every object by atlas_sprite_ao over the oracle's own capture uploaded (exact texels: GL must compute the program's floats)", 160, 160}, buildRttaFiveAoPost},
      {{"light_map", "a second texture layer multiplied in (textured_layers, thesis 5.1.3): trilinear base x trilinear light map, RGB at strength 1 and glTF occlusion (R) at 0.6", 256, 192}, buildLightMap},
      {{"s3tc_blocks", "S3TC textures uploaded as blocks: BC1 and BC3 (alpha ramp), magnified and trilinear-minified, decoded by GL and by the oracle's documented rule (BC_INTERPOLANT)", 128, 128}, buildS3tcBlocks},
  };
  return e;
}
}  // namespace

const std::vector<SceneInfo>& all() {
  static const std::vector<SceneInfo> infos = [] {
    std::vector<SceneInfo> v;
    for (const Entry& e : entries()) v.push_back(e.info);
    return v;
  }();
  return infos;
}

const SceneInfo* find(std::string_view name) {
  for (const SceneInfo& s : all())
    if (s.name == name) return &s;
  return nullptr;
}

CommandList build(std::string_view name, int width, int height) {
  for (const Entry& e : entries())
    if (e.info.name == name) {
      if (width < 1 || height < 1 || width > kMaxTextureSize || height > kMaxTextureSize)
        throw Error("scene " + std::string(name) + ": size " + std::to_string(width) + "x" +
                    std::to_string(height) + " is outside 1..16384");
      CommandList cl;
      cl.marker("scene " + std::string(name));
      e.build(cl, width, height);
      return cl;
    }
  std::string known;
  for (const Entry& e : entries()) known += (known.empty() ? "" : ", ") + std::string(e.info.name);
  throw Error("unknown scene '" + std::string(name) + "' (known: " + known + ")");
}

Frame beginFrame(CommandList& cl, int w, int h, bool withDepth, std::array<float, 4> clear) {
  Frame f;
  f.color = createTarget(cl, Format::RGBA8, w, h);
  if (withDepth) f.depth = createTarget(cl, Format::D32F, w, h);
  RenderTarget t;
  t.color[0] = f.color;
  t.depth = f.depth;
  cl.setRenderTarget(t);
  cl.setViewport({0, 0, w, h});
  cl.clearColor(0, clear);
  if (withDepth) cl.clearDepth(1.0f);
  return f;
}

}  // namespace tessera::scenes
