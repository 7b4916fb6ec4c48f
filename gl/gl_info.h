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

// Implementation limits the judge may derive tolerances from (GL 4.6 Table 23.53 ff.): what the
// context reports, never an assumed value. 0 = the query is not available on this context.
struct GlLimits {
  int subpixelBits = 0;             // GL_SUBPIXEL_BITS: llvmpipe 8, softpipe 4 (GL's minimum is 4, §14.5)
  float maxTextureLodBias = 0;      // GL_MAX_TEXTURE_LOD_BIAS
  int maxViewportDims[2] = {0, 0};  // GL_MAX_VIEWPORT_DIMS
  float viewportBoundsRange[2] = {0, 0};  // GL_VIEWPORT_BOUNDS_RANGE (GL 4.1 / ARB_viewport_array)
  int maxClipDistances = 0;         // GL_MAX_CLIP_DISTANCES
  int maxTextureBufferSize = 0;     // GL_MAX_TEXTURE_BUFFER_SIZE
  int maxArrayTextureLayers = 0;    // GL_MAX_ARRAY_TEXTURE_LAYERS
  int maxTextureSize = 0;           // GL_MAX_TEXTURE_SIZE
  int maxColorAttachments = 0;      // GL_MAX_COLOR_ATTACHMENTS
};

struct GlInfo {
  std::string eglPlatform;  // "surfaceless" or "device"
  std::string eglVersion, eglVendor;
  std::string vendor, renderer, version, glslVersion;
  std::string mesaVersion;  // "22.3.6", or "" when GL_VERSION names no Mesa
  // The Gallium driver GL_RENDERER names ("llvmpipe", "softpipe", "zink"; else GL_RENDERER's first
  // word) and the one GlOptions::driver asked for ("" = Mesa's default).
  std::string driver, requestedDriver;
  // The GL path the backend uses: 45 = OpenGL 4.5 core with DSA, 33 = OpenGL 3.3 core with bind
  // points (docs/gl-backend.md, "The 3.3 core path"). GL_VERSION may be higher than the path (Mesa
  // returns its highest compatible version for a 3.3 request).
  int contextVersion = 0;
  // The GLSL twins as compiled: "450 core" or "330 core", the #extension directives the 3.3 rewrite
  // enabled, and the features it had to drop for lack of an extension (each a possible deviation).
  std::string glslDialect;
  std::vector<std::string> glslExtensions, glslFallbacks;
  GlLimits limits;
  bool debugContext = false;
  // The llvmpipe switches as they were when the process initialised its EGL display (llvmpipe reads
  // them then, once); nullopt = unset.
  std::vector<std::pair<std::string, std::optional<std::string>>> env;
  CpuCaps cpu;

  nlohmann::json toJson() const;
};

// Environment variables recorded in GlInfo::env, in this order.
const std::vector<std::string_view>& recordedEnvNames();
// "llvmpipe (LLVM 15.0.6, 256 bits)" -> "llvmpipe", "softpipe" -> "softpipe", "zink (lavapipe)" ->
// "zink"; otherwise the first word of GL_RENDERER ("" for an empty string).
std::string parseDriver(std::string_view renderer);
// "4.5 (Core Profile) Mesa 22.3.6" -> "22.3.6"; "" when the string has no "Mesa <version>".
std::string parseMesaVersion(std::string_view glVersion);
// The flags of the first processor in cpuinfo text (the content of /proc/cpuinfo).
CpuCaps parseCpuCaps(std::string_view cpuinfo);
// parseCpuCaps of /proc/cpuinfo; all false when it cannot be read.
CpuCaps readCpuCaps();
// The current value of each recordedEnvNames() variable.
std::vector<std::pair<std::string, std::optional<std::string>>> readRecordedEnv();

}  // namespace tessera::gl
