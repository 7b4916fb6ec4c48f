// What a GL backend ran on: the EGL platform, GL strings, the llvmpipe environment switches and the
// CPU features that decide llvmpipe's code generation. Recorded next to every GL image so a pixel
// difference can be traced to the machine (llvmpipe generates code for the CPU it runs on, so its
// output can depend on FMA, the vector width and GALLIUM_OVERRIDE_CPU_CAPS; docs/gl-backend.md).
//
// Implements: the record, its JSON form, parsing the Mesa version from GL_VERSION and the CPU
// flags from /proc/cpuinfo. Does not implement: creating a context (egl_context.h).
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace tessera::gl {

struct CpuCaps {
  bool sse4_1 = false, avx = false, avx2 = false, fma = false, avx512f = false;
};

struct GlInfo {
  std::string eglPlatform;  // "surfaceless" or "device"
  std::string eglVersion, eglVendor;
  std::string vendor, renderer, version, glslVersion;
  std::string mesaVersion;  // "22.3.6", or "" when GL_VERSION names no Mesa
  bool debugContext = false;
  int subpixelBits = 0;  // GL_SUBPIXEL_BITS (GL 4.6 §14.5: at least 4); 0 = not queried
  // The llvmpipe switches as they were when the process initialised its EGL display (llvmpipe reads
  // them then, once); nullopt = unset.
  std::vector<std::pair<std::string, std::optional<std::string>>> env;
  CpuCaps cpu;

  nlohmann::json toJson() const;
};

// Environment variables recorded in GlInfo::env, in this order.
const std::vector<std::string_view>& recordedEnvNames();
// "4.5 (Core Profile) Mesa 22.3.6" -> "22.3.6"; "" when the string has no "Mesa <version>".
std::string parseMesaVersion(std::string_view glVersion);
// The flags of the first processor in cpuinfo text (the content of /proc/cpuinfo).
CpuCaps parseCpuCaps(std::string_view cpuinfo);
// parseCpuCaps of /proc/cpuinfo; all false when it cannot be read.
CpuCaps readCpuCaps();
// The current value of each recordedEnvNames() variable.
std::vector<std::pair<std::string, std::optional<std::string>>> readRecordedEnv();

}  // namespace tessera::gl
