#include "verify/atomic_file.h"

#include <unistd.h>

#include <cstdio>
#include <fstream>

#include "raster/command_list.h"

namespace tessera::verify {

void writeTextAtomically(const std::string& path, std::string_view content) {
  const std::string tmp = path + ".tmp-" + std::to_string(::getpid());
  {
    std::ofstream f(tmp, std::ios::binary | std::ios::trunc);
    if (!f) throw Error(path + ": cannot open for writing");
    f.write(content.data(), std::streamsize(content.size()));
    f.close();
    if (!f) {
      std::remove(tmp.c_str());
      throw Error(path + ": write failed");
    }
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    std::remove(tmp.c_str());
    throw Error(path + ": cannot rename the finished temporary file into place");
  }
}

}  // namespace tessera::verify
