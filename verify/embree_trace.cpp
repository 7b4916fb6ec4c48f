#include "verify/embree_trace.h"

#include <embree3/rtcore.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <iterator>
#include <limits>
#include <memory>

#include "raster/command_list.h"

namespace tessera::verify {

namespace {

struct DeviceDeleter {
  void operator()(RTCDevice d) const { rtcReleaseDevice(d); }
};
struct SceneDeleter {
  void operator()(RTCScene s) const { rtcReleaseScene(s); }
};
using DevicePtr = std::unique_ptr<RTCDeviceTy, DeviceDeleter>;
using ScenePtr = std::unique_ptr<RTCSceneTy, SceneDeleter>;

// Per-draw data the filter needs; geometry id = draw index.
struct DrawGeom {
  std::vector<uint32_t> global;  // Embree primID -> VisibilityScene::triangles index
  Rect rect;
  CompareFunc func;
};

struct Best {
  float t;
  uint32_t triangle;  // global index or kNoHit
  uint32_t draw;
};

// Embree passes the context pointer through to the filter; extending it is the documented way to
// hand per-ray data to callbacks.
struct RayContext {
  RTCIntersectContext base;
  const std::vector<DrawGeom>* draws;
  Best* best;
  int32_t px, py;
  float clearT;  // t of the cleared depth: the first fragment must pass the depth test against it
};

// Does a hit on `candidate` at depth t replace `best`? Smaller t wins; an exact tie is resolved as
// the depth test would resolve equal depths: the later primitive replaces the earlier one only
// under LEQUAL (its own function decides, as the incoming fragment).
bool replaces(const std::vector<DrawGeom>& draws, float t, uint32_t candidate, uint32_t candDraw, const Best& best) {
  if (best.triangle == kNoHit || t < best.t) return true;
  if (t > best.t || candidate == best.triangle) return false;
  const bool candLater = candidate > best.triangle;
  const CompareFunc laterFunc = draws[candLater ? candDraw : best.draw].func;
  return candLater == (laterFunc == CompareFunc::LEqual);
}

void filter(const RTCFilterFunctionNArguments* args) {
  const RayContext* ctx = reinterpret_cast<const RayContext*>(args->context);
  const std::vector<DrawGeom>& draws = *ctx->draws;
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] == 0) continue;
    const uint32_t geom = RTCHitN_geomID(args->hit, args->N, i);
    const uint32_t prim = RTCHitN_primID(args->hit, args->N, i);
    const DrawGeom& d = draws[geom];
    const Rect& r = d.rect;
    if (ctx->px < r.x || ctx->py < r.y || ctx->px >= r.x + r.w || ctx->py >= r.y + r.h) {
      args->valid[i] = 0;
      continue;
    }
    const float t = RTCRayN_tfar(args->ray, args->N, i);  // the potential hit's distance
    if (d.func == CompareFunc::Less ? !(t < ctx->clearT) : !(t <= ctx->clearT)) {
      args->valid[i] = 0;
      continue;
    }
    const uint32_t global = d.global[prim];
    if (replaces(draws, t, global, geom, *ctx->best)) {
      *ctx->best = {t, global, geom};
    } else {
      args->valid[i] = 0;  // keep Embree's committed hit equal to ours
    }
  }
}

DevicePtr newDevice(const std::vector<std::string>& isas, int threads, std::string& chosen) {
  for (const std::string& isa : isas) {
    // Embree silently falls back to SSE2 for a name it does not know: refuse those instead, or the
    // report would claim an ISA that was never used.
    static const char* kKnown[] = {"sse2", "sse4.2", "avx", "avx2", "avx512"};
    if (std::find(std::begin(kKnown), std::end(kKnown), isa) == std::end(kKnown))
      throw Error("visibility: unknown Embree ISA '" + isa + "' (known: sse2, sse4.2, avx, avx2, avx512)");
    // Only the ISA is pinned: it decides Embree's float arithmetic. The thread count is the caller's:
    // Embree's TBB backend turns "threads=N" into a process-wide tbb::global_control while the
    // device lives, so "threads=1" would also serialize the row loop below (measured: 2x slower on
    // 2 cores). The BVH may then differ between runs, which the filter makes irrelevant.
    std::string config = "isa=" + isa;
    if (threads > 0) config += ",threads=" + std::to_string(threads);
    RTCDevice d = rtcNewDevice(config.c_str());
    if (d && rtcGetDeviceError(d) == RTC_ERROR_NONE) {
      chosen = isa;
      return DevicePtr(d);
    }
    if (d) rtcReleaseDevice(d);
  }
  throw Error("visibility: Embree could not create a device for any of the pinned ISAs");
}

}  // namespace

EmbreeImage traceScene(const VisibilityScene& scene, const std::vector<std::string>& isas, int threads) {
  EmbreeImage img;
  img.width = scene.width;
  img.height = scene.height;
  img.triangle.assign(size_t(scene.width) * size_t(scene.height), kNoHit);
  DevicePtr device = newDevice(isas, threads, img.isa);
  const long version = long(rtcGetDeviceProperty(device.get(), RTC_DEVICE_PROPERTY_VERSION));
  img.version =
      std::to_string(version / 10000) + "." + std::to_string(version / 100 % 100) + "." + std::to_string(version % 100);
  // Backface culling compiled into Embree would silently drop hits of clockwise triangles.
  if (rtcGetDeviceProperty(device.get(), RTC_DEVICE_PROPERTY_BACKFACE_CULLING_ENABLED))
    throw Error("visibility: this Embree build culls back faces; the visibility oracle needs both windings");

  const auto t0 = std::chrono::steady_clock::now();
  ScenePtr rtScene(rtcNewScene(device.get()));
  // ROBUST: watertight traversal and intersection, so a ray through a shared edge or vertex is not
  // lost between two triangles (it may hit both; the filter then decides).
  rtcSetSceneFlags(rtScene.get(), RTC_SCENE_FLAG_ROBUST);
  std::vector<DrawGeom> draws(scene.draws.size());
  for (size_t d = 0; d < scene.draws.size(); ++d) {
    draws[d].rect = scene.draws[d].clampRect;
    draws[d].func = scene.draws[d].depthFunc;
  }
  for (uint32_t i = 0; i < scene.triangles.size(); ++i)
    if (!scene.triangles[i].culled) draws[scene.triangles[i].draw].global.push_back(i);
  for (uint32_t d = 0; d < draws.size(); ++d) {
    const std::vector<uint32_t>& tris = draws[d].global;
    if (tris.empty()) continue;
    RTCGeometry g = rtcNewGeometry(device.get(), RTC_GEOMETRY_TYPE_TRIANGLE);
    float* v = static_cast<float*>(
        rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), 3 * tris.size()));
    unsigned* idx = static_cast<unsigned*>(
        rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), tris.size()));
    if (!v || !idx) throw Error("visibility: Embree could not allocate geometry buffers");
    for (size_t k = 0; k < tris.size(); ++k) {
      const WindowTriangle& t = scene.triangles[tris[k]];
      for (int c = 0; c < 3; ++c) {
        // Window coordinates as float: Embree's precision. Pixels where this matters are re-judged
        // in double by visibility_check.cpp.
        v[9 * k + 3 * size_t(c)] = float(t.x[c]);
        v[9 * k + 3 * size_t(c) + 1] = float(t.y[c]);
        v[9 * k + 3 * size_t(c) + 2] = float(t.z[c]);
        idx[3 * k + size_t(c)] = unsigned(3 * k + size_t(c));
      }
    }
    rtcSetGeometryIntersectFilterFunction(g, filter);
    rtcCommitGeometry(g);
    rtcAttachGeometryByID(rtScene.get(), g, d);
    rtcReleaseGeometry(g);
    img.triangles += tris.size();
  }
  rtcCommitScene(rtScene.get());
  if (rtcGetDeviceError(device.get()) != RTC_ERROR_NONE) throw Error("visibility: Embree failed to build the scene");
  const auto t1 = std::chrono::steady_clock::now();

  const int32_t w = scene.width;
  // Rays start at z = -1, so a hit at window depth z has t = z + 1 (exact in float for z in [0, 1]
  // up to one rounding).
  const float clearT = float(1.0 + double(scene.clearDepth));
  auto castRows = [&](const tbb::blocked_range<int32_t>& rows) {
    for (int32_t y = rows.begin(); y != rows.end(); ++y)
      for (int32_t x = 0; x < w; ++x) {
        Best best{std::numeric_limits<float>::infinity(), kNoHit, 0};
        RayContext ctx;
        rtcInitIntersectContext(&ctx.base);
        ctx.draws = &draws;
        ctx.best = &best;
        ctx.px = x, ctx.py = y;
        ctx.clearT = clearT;
        RTCRayHit rh{};
        rh.ray.org_x = float(x) + 0.5f;
        rh.ray.org_y = float(y) + 0.5f;
        rh.ray.org_z = -1.0f;
        rh.ray.dir_x = 0.0f, rh.ray.dir_y = 0.0f, rh.ray.dir_z = 1.0f;
        rh.ray.tnear = 0.0f;
        rh.ray.tfar = clearT;
        rh.ray.mask = 0xffffffffu;
        rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        rh.hit.primID = RTC_INVALID_GEOMETRY_ID;
        rtcIntersect1(rtScene.get(), &ctx.base, &rh);
        img.triangle[size_t(y) * size_t(w) + size_t(x)] = best.triangle;
      }
  };
  tbb::task_arena arena(threads > 0 ? threads : tbb::this_task_arena::max_concurrency());
  arena.execute([&] { tbb::parallel_for(tbb::blocked_range<int32_t>(0, scene.height, 1), castRows); });
  const auto t2 = std::chrono::steady_clock::now();
  img.buildMs = std::chrono::duration<double, std::milli>(t1 - t0).count();
  img.castMs = std::chrono::duration<double, std::milli>(t2 - t1).count();
  return img;
}

}  // namespace tessera::verify
