// `tessera bench sweep`: how the oracle's and llvmpipe's frame times grow with pixels and with
// triangles (docs/bench.md, issue 13 section 1).
//
// Implements: the sweep's plan (which workload, variant and size or triangle count, in a fixed order,
// full or --quick), the worker that times a plan at one thread count and one llvmpipe mode in its own
// process (llvmpipe reads LP_NUM_THREADS, LP_PERF and GALLIVM_PERF once per process, gl_backend.h), and
// the registration of `bench sweep` and of its hidden child `bench sweep-worker`.
// Does not implement: the workloads themselves (tools/scenes/sweep_scenes.h), the report files
// (cmd_bench_sweep.cpp, sweep_plot.h).
#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "raster/command_list.h"

namespace tessera::cli {

struct SweepPoint {
  std::string workload;  // "fill_layers" (x = pixels) or "tiny_tris" (x = triangles)
  std::string variant;   // fill_layers: sweep_scenes.h fillVariants(); tiny_tris: "flat_color"
  int width = 0, height = 0;
  int triangles = 0;  // tiny_tris only
  double x() const { return workload == "tiny_tris" ? double(triangles) : double(width) * double(height); }
  CommandList build() const;
  std::string label() const;  // "fill_layers trilinear 640x480", "tiny_tris 10000 tris"
};

// Full: fill_layers in every variant at 320x240, 640x480, 1280x720, 1920x1080, then tiny_tris at
// 1280x720 with 1k, 10k, 100k, 1M triangles. Quick: fill_layers trilinear at 320x240 and 640x480, and
// tiny_tris with 1k and 10k triangles.
std::vector<SweepPoint> sweepPlan(bool quick);

// Registers `bench sweep` and the hidden `bench sweep-worker` under `bench` (cmd_bench_sweep.cpp).
void addBenchSweepCommands(CLI::App* bench);
// Registers the hidden `bench sweep-worker` (bench_sweep_worker.cpp): the child that times the plan with
// the oracle and llvmpipe interleaved run by run, and writes its raw runs as JSON to --out:
//   {"threads", "gl_mode": "llvmpipe" | "llvmpipe_strict", "repeat", "gl_info",
//    "points": [{"index", "oracle_ms": [...], "oracle_cpu_ms": [...], "gl_ms": [...], "gl_cpu_ms": [...],
//                "stages": {...} (with --stages)}]}
void addSweepWorkerCommand(CLI::App* bench);

}  // namespace tessera::cli
