#include "verify/visibility_scene.h"

#include <algorithm>
#include <cstring>
#include <map>
#include <string>
#include <variant>

#include "raster/clip.h"
#include "raster/program.h"
#include "verify/vertex_fetch.h"

namespace tessera::verify {

namespace {

Rect intersect(const Rect& a, const Rect& b) {
  const int64_t x0 = std::max(a.x, b.x), y0 = std::max(a.y, b.y);
  const int64_t x1 = std::min<int64_t>(int64_t(a.x) + a.w, int64_t(b.x) + b.w);
  const int64_t y1 = std::min<int64_t>(int64_t(a.y) + a.h, int64_t(b.y) + b.h);
  return Rect{int32_t(x0), int32_t(y0), int32_t(std::max<int64_t>(0, x1 - x0)), int32_t(std::max<int64_t>(0, y1 - y0))};
}

struct WindowVertex {
  double x, y, z;
};

// GL 4.6 §13.8: perspective division, then the viewport transform with depth range [0, 1]. No
// snapping: this is the exact geometry the oracle's snapped triangles approximate.
WindowVertex toWindow(const double pos[4], const Rect& vp) {
  const double invW = 1.0 / pos[3];
  const double halfW = 0.5 * vp.w, halfH = 0.5 * vp.h;
  const double zw = pos[2] * invW * 0.5 + 0.5;
  return {pos[0] * invW * halfW + (vp.x + halfW), pos[1] * invW * halfH + (vp.y + halfH), std::clamp(zw, 0.0, 1.0)};
}

std::string at(size_t command) { return "visibility: command " + std::to_string(command) + ": "; }

// The state a replay needs; resources by id (one shared id space, like the command list).
class Replay {
 public:
  Replay(const CommandList& list, VisibilityScene& out) : list_(list), out_(out) {}

  void run() {
    const RenderTarget* last = nullptr;
    for (const Command& c : list_.commands())
      if (const auto* t = std::get_if<SetRenderTarget>(&c)) last = &t->target;
    if (!last) throw Error("visibility: the list never binds a render target, so it presents nothing");
    out_.target = *last;
    for (size_t i = 0; i < list_.commands().size(); ++i) {
      index_ = i;
      std::visit([&](const auto& c) { apply(c); }, list_.commands()[i]);
    }
  }

 private:
  void apply(const CreateTexture& c) { textures_[c.id] = c.desc; }
  void apply(const UploadTexture&) {}
  void apply(const CreateBuffer& c) { buffers_[c.id].assign(size_t(c.size), 0); }
  void apply(const UploadBuffer& c) {
    auto src = list_.bytes(c.data);
    auto& dst = buffers_.at(c.id);
    if (c.offset + src.size() > dst.size()) throw Error(at(index_) + "upload outside the buffer");
    std::memcpy(dst.data() + c.offset, src.data(), src.size());
  }
  void apply(const CreateSampler&) {}
  void apply(const CreateProgram& c) {
    programs_[c.id] = findProgram(c.name);
    uniforms_[c.id] = {};
  }
  void apply(const BindTexture&) {}
  void apply(const BindSampler&) {}
  void apply(const UseProgram& c) { program_ = c.program; }
  void apply(const SetUniforms& c) {
    auto src = list_.bytes(c.data);
    auto& u = uniforms_[program_];
    if (c.slot + c.count > u.size() || src.size() != size_t(c.count) * sizeof(Vec4))
      throw Error(at(index_) + "uniform range outside the program's slots");
    std::memcpy(u.data() + c.slot, src.data(), src.size());
  }
  void apply(const BindVertexBuffer& c) { vertexBuffer_ = c.buffer; }
  void apply(const SetVertexLayout& c) { layout_ = c.layout; }
  void apply(const BindIndexBuffer& c) { indexBuffer_ = c.buffer, indexType_ = c.type; }
  void apply(const SetViewport& c) { viewport_ = c.rect; }
  void apply(const SetScissor& c) { scissor_ = c.state; }
  void apply(const SetDepthState& c) { depth_ = c.state; }
  void apply(const SetBlendState&) {}  // R32UI targets are never blended (GL 4.6 §17.3.6)
  void apply(const SetRasterState& c) { raster_ = c.state; }
  void apply(const SetRenderTarget& c) {
    inScope_ = c.target == out_.target;
    if (!inScope_) return;
    if (c.target.layer == kLayered) throw Error(at(index_) + "the presented target is layered (unsupported)");
    const ResourceId any = c.target.color[0] != kNone ? c.target.color[0] : c.target.depth;
    if (any == kNone) throw Error(at(index_) + "the presented target has no attachments");
    const TextureDesc& d = textures_.at(any);
    out_.width = int32_t(levelWidth(d, c.target.level));
    out_.height = int32_t(levelHeight(d, c.target.level));
  }
  void checkClear() const {
    // A clear after draws would hide some of them; a scissored clear makes the background
    // non-uniform. Neither happens in ID frames, so they are refused rather than modelled.
    if (scissor_.enabled) throw Error(at(index_) + "scissored clear of the presented target (unsupported)");
    if (!out_.draws.empty()) throw Error(at(index_) + "clear of the presented target after draws to it (unsupported)");
  }
  void apply(const ClearColor& c) {
    if (!inScope_) return;
    checkClear();
    if (c.attachment < 2) out_.clearIds[c.attachment] = c.bits[0];
  }
  void apply(const ClearDepth& c) {
    if (!inScope_) return;
    checkClear();
    // glClearDepth clamps to [0, 1] (GL 4.6 §17.4.3); NaN is taken as 0 as in the oracle.
    out_.clearDepth = c.depth > 0.0f ? (c.depth < 1.0f ? c.depth : 1.0f) : 0.0f;
  }
  void apply(const Marker&) {}
  void apply(const Draw& d) {
    if (!inScope_) return;
    checkDrawScope();
    drawTriangles(d);
  }

  void checkDrawScope() const {
    const Program* p = programs_.count(program_) ? programs_.at(program_) : nullptr;
    if (!p) throw Error(at(index_) + "draw without a known program");
    if (p->name() != "object_id")
      throw Error(at(index_) + "program '" + std::string(p->name()) +
                  "' does not write ids; only object_id draws can be checked");
    if (out_.target.depth == kNone) throw Error(at(index_) + "the presented target has no depth attachment");
    if (!depth_.test || !depth_.write)
      throw Error(at(index_) + "depth test and depth writes must be on (nearest-wins is what is checked)");
    if (depth_.func != CompareFunc::Less && depth_.func != CompareFunc::LEqual)
      throw Error(at(index_) + "depth function " + std::to_string(int(depth_.func)) +
                  " is unsupported (LESS and LEQUAL only)");
  }

  void drawTriangles(const Draw& d) {
    const uint32_t triCount = d.count / 3;  // a trailing partial triangle is ignored (GL 4.6 §10.1)
    SceneDraw sd;
    sd.command = index_;
    sd.depthFunc = depth_.func;
    sd.clampRect = intersect(viewport_, Rect{0, 0, out_.width, out_.height});
    if (scissor_.enabled) sd.clampRect = intersect(sd.clampRect, scissor_.rect);
    const uint32_t drawIndex = uint32_t(out_.draws.size());
    out_.draws.push_back(sd);
    if (triCount == 0) return;

    const Program& prog = *programs_.at(program_);
    ShadeContext ctx;
    ctx.uniforms = uniforms_[program_].data();
    const std::vector<uint8_t>& vb = buffers_.at(vertexBuffer_);
    const size_t n = size_t(triCount) * 3;
    std::vector<VertexIn> in(n);
    std::vector<VertexOut> out(n);
    for (size_t i = 0; i < n; ++i) {
      const uint32_t index =
          d.indexed ? readIndex(buffers_.at(indexBuffer_), indexType_, uint64_t(d.first) + i) : uint32_t(d.first + i);
      fetchVertex(vb, layout_, index, in[i]);
    }
    std::memset(out.data(), 0, out.size() * sizeof(VertexOut));
    prog.shadeVertices(in, out, ctx);

    for (uint32_t t = 0; t < triCount; ++t) {
      VertexOut v[3] = {out[3 * size_t(t)], out[3 * size_t(t) + 1], out[3 * size_t(t) + 2]};
      uint32_t layer = 0;
      if (prog.hasGeometryStage() && !prog.shadeTriangle(v, t, layer, ctx)) continue;
      addPrimitive(v, drawIndex, t);
    }
  }

  void addPrimitive(const VertexOut (&v)[3], uint32_t drawIndex, uint32_t primitiveId) {
    const uint8_t clipMask = raster_.clipMask;
    const detail::ClipResult cr = detail::classifyTriangle(v, clipMask);
    if (cr == detail::ClipResult::Outside) return;
    double poly[detail::kMaxClipPolygon][4];
    int n = 0;
    if (cr == detail::ClipResult::Inside) {
      for (int i = 0; i < 3; ++i)
        for (int k = 0; k < 4; ++k) poly[i][k] = v[i].pos[k];
      n = 3;
    } else {
      ++out_.primitivesClipped;
      detail::ClipVertex cv[detail::kMaxClipPolygon];
      n = detail::clipTriangle(v, clipMask, 0, cv);
      for (int i = 0; i < n; ++i)
        for (int k = 0; k < 4; ++k) poly[i][k] = cv[i].pos[k];
    }
    // w <= 0 survives clipping only at the clip-space origin: no window position (the oracle drops
    // the primitive, docs/spec-choices.md V4).
    for (int i = 0; i < n; ++i)
      if (!(poly[i][3] > 0.0)) return;
    WindowVertex w[detail::kMaxClipPolygon];
    for (int i = 0; i < n; ++i) w[i] = toWindow(poly[i], viewport_);
    // GL triangulates a clipped polygon any way it likes; a fan from the first vertex covers the same
    // area, and flat values stay those of the primitive's provoking vertex (GL 4.6 §13.4).
    for (int i = 1; i + 1 < n; ++i) {
      WindowTriangle t;
      const WindowVertex* corner[3] = {&w[0], &w[i], &w[i + 1]};
      for (int k = 0; k < 3; ++k) t.x[k] = corner[k]->x, t.y[k] = corner[k]->y, t.z[k] = corner[k]->z;
      t.draw = drawIndex;
      t.primitiveId = primitiveId;
      t.objectId = v[2].flat[0];
      // Facing from the signed area in window space (GL 4.6 §14.6.1, eq. 14.8), unsnapped.
      const double area2 = (t.x[1] - t.x[0]) * (t.y[2] - t.y[0]) - (t.x[2] - t.x[0]) * (t.y[1] - t.y[0]);
      const bool front = (area2 > 0.0) == raster_.frontCcw;
      t.culled =
          area2 == 0.0 || (raster_.cull == CullMode::Back && !front) || (raster_.cull == CullMode::Front && front);
      out_.triangles.push_back(t);
    }
  }

  const CommandList& list_;
  VisibilityScene& out_;
  size_t index_ = 0;
  bool inScope_ = false;
  std::map<ResourceId, TextureDesc> textures_;
  std::map<ResourceId, std::vector<uint8_t>> buffers_;
  std::map<ResourceId, const Program*> programs_;
  std::map<ResourceId, std::array<Vec4, kMaxUniformSlots>> uniforms_;
  ResourceId program_ = kNone, vertexBuffer_ = kNone, indexBuffer_ = kNone;
  IndexType indexType_ = IndexType::U16;
  VertexLayout layout_;
  Rect viewport_;
  ScissorState scissor_;
  DepthState depth_;
  RasterState raster_;
};

}  // namespace

VisibilityScene buildVisibilityScene(const CommandList& list) {
  VisibilityScene scene;
  Replay(list, scene).run();
  return scene;
}

}  // namespace tessera::verify
