#include "gl/gl_info.h"

#include <cstdlib>
#include <fstream>
#include <sstream>

namespace tessera::gl {

const std::vector<std::string_view>& recordedEnvNames() {
  // LP_NUM_THREADS: rasterizer threads. GALLIUM_OVERRIDE_CPU_CAPS / LP_NATIVE_VECTOR_WIDTH: the ISA
  // and vector width llvmpipe generates code for. LP_PERF / LP_DEBUG / GALLIVM_PERF: fast-path
  // switches (GlOptions::strict). EGL_PLATFORM: would redirect eglGetDisplay (not used, recorded).
  static const std::vector<std::string_view> names = {"LP_NUM_THREADS",
                                                      "GALLIUM_OVERRIDE_CPU_CAPS",
                                                      "LP_NATIVE_VECTOR_WIDTH",
                                                      "LP_PERF",
                                                      "LP_DEBUG",
                                                      "GALLIVM_PERF",
                                                      "GALLIUM_DRIVER",
                                                      "EGL_PLATFORM"};
  return names;
}

std::string parseMesaVersion(std::string_view glVersion) {
  const size_t at = glVersion.find("Mesa ");
  if (at == std::string_view::npos) return {};
  size_t b = at + 5, e = b;
  while (e < glVersion.size() && glVersion[e] != ' ' && glVersion[e] != ')') ++e;
  return std::string(glVersion.substr(b, e - b));
}

CpuCaps parseCpuCaps(std::string_view cpuinfo) {
  CpuCaps c;
  size_t pos = 0;
  while (pos < cpuinfo.size()) {
    size_t end = cpuinfo.find('\n', pos);
    if (end == std::string_view::npos) end = cpuinfo.size();
    const std::string_view line = cpuinfo.substr(pos, end - pos);
    pos = end + 1;
    if (line.rfind("flags", 0) != 0) continue;
    const size_t colon = line.find(':');
    if (colon == std::string_view::npos) continue;
    std::istringstream words{std::string(line.substr(colon + 1))};
    std::string w;
    while (words >> w) {
      if (w == "sse4_1") c.sse4_1 = true;
      if (w == "avx") c.avx = true;
      if (w == "avx2") c.avx2 = true;
      if (w == "fma") c.fma = true;
      if (w == "avx512f") c.avx512f = true;
    }
    break;  // the first processor speaks for all (llvmpipe detects features once, on the caller's CPU)
  }
  return c;
}

CpuCaps readCpuCaps() {
  std::ifstream f("/proc/cpuinfo");
  if (!f) return {};
  std::stringstream ss;
  ss << f.rdbuf();
  return parseCpuCaps(ss.str());
}

std::vector<std::pair<std::string, std::optional<std::string>>> readRecordedEnv() {
  std::vector<std::pair<std::string, std::optional<std::string>>> env;
  for (std::string_view n : recordedEnvNames()) {
    const char* v = std::getenv(std::string(n).c_str());
    env.emplace_back(std::string(n), v ? std::optional<std::string>(v) : std::nullopt);
  }
  return env;
}

nlohmann::json GlInfo::toJson() const {
  nlohmann::json e = nlohmann::json::object();
  for (const auto& [name, value] : env) e[name] = value ? nlohmann::json(*value) : nlohmann::json(nullptr);
  return {{"egl_platform", eglPlatform},
          {"egl_version", eglVersion},
          {"egl_vendor", eglVendor},
          {"gl_vendor", vendor},
          {"gl_renderer", renderer},
          {"gl_version", version},
          {"glsl_version", glslVersion},
          {"mesa_version", mesaVersion},
          {"debug_context", debugContext},
          {"subpixel_bits", subpixelBits},
          {"env", e},
          {"cpu_caps",
           {{"sse4_1", cpu.sse4_1}, {"avx", cpu.avx}, {"avx2", cpu.avx2}, {"fma", cpu.fma}, {"avx512f", cpu.avx512f}}}};
}

}  // namespace tessera::gl
