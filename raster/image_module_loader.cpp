// imagemod::api(): finds and loads libtessera_image_module.so once per process (image_module.h).
#include <dlfcn.h>
#include <unistd.h>

#include <cstdlib>
#include <mutex>
#include <string>
#include <vector>

#include "base/error.h"
#include "raster/image_module.h"

namespace tessera::imagemod {
namespace {

constexpr const char* kFileName = "libtessera_image_module.so";

std::string besideExecutable() {
  char buf[4096];
  const ssize_t n = ::readlink("/proc/self/exe", buf, sizeof buf - 1);
  if (n <= 0) return {};
  std::string exe(buf, size_t(n));
  const size_t slash = exe.rfind('/');
  return slash == std::string::npos ? std::string() : exe.substr(0, slash + 1) + kFileName;
}

// Where to look, in order: an explicit override (an installed layout, a test of a wrong module), the
// path CMake wrote in (the build tree, where every test and the demo run), beside the executable.
std::vector<std::string> candidates() {
  std::vector<std::string> c;
  if (const char* env = std::getenv("TESSERA_IMAGE_MODULE"); env && *env) return {env};
#ifdef TESSERA_IMAGE_MODULE_PATH
  c.push_back(TESSERA_IMAGE_MODULE_PATH);
#endif
  if (std::string b = besideExecutable(); !b.empty()) c.push_back(b);
  return c;
}

const Api* load() {
  std::string tried;
  for (const std::string& path : candidates()) {
    if (::access(path.c_str(), F_OK) != 0) {
      tried += "\n  " + path + ": no such file";
      continue;
    }
    // RTLD_LOCAL: OIIO's hundreds of libraries stay out of the global symbol namespace. RTLD_LAZY, as
    // the dynamic loader binds them at a normal start: RTLD_NOW would resolve every function of all
    // ~260 libraries up front, most of which an image write never calls.
    void* h = ::dlopen(path.c_str(), RTLD_LAZY | RTLD_LOCAL);
    if (!h) throw Error("cannot load the image module " + path + ": " + ::dlerror());
    using Entry = const Api* (*)();
    auto entry = reinterpret_cast<Entry>(::dlsym(h, "tessera_image_module_api"));
    if (!entry) throw Error("the image module " + path + " has no tessera_image_module_api: " + ::dlerror());
    const Api* api = entry();
    if (!api || api->abi != kAbi)
      throw Error("the image module " + path + " was built from other sources (interface " +
                  std::to_string(api ? api->abi : 0) + ", this program needs " + std::to_string(kAbi) +
                  "): rebuild, or point TESSERA_IMAGE_MODULE at the matching one");
    return api;
  }
  throw Error(std::string("cannot find the image module ") + kFileName + " (image files are read and written through it):" +
              tried + "\n  set TESSERA_IMAGE_MODULE to its path");
}

}  // namespace

const Api& api() {
  // A failed load is not cached: the error is thrown to this caller, and the next caller tries again
  // (and gets the same error), rather than a null interface.
  static std::mutex m;
  static const Api* loaded = nullptr;
  std::lock_guard<std::mutex> lock(m);
  if (!loaded) loaded = load();
  return *loaded;
}

}  // namespace tessera::imagemod
