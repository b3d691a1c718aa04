#include "diffray/core/atomic_file.h"

#include <unistd.h>

#include <cstdio>
#include <fstream>

#include "diffray/core/error.h"

namespace diffray::core {

void writeFileAtomically(const std::string& path, const std::function<void(std::ostream&)>& write) {
  const std::string tmp = path + ".tmp." + std::to_string(::getpid());
  try {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw InputError(path, "cannot open for writing");
    write(out);
    out.flush();
    if (!out) throw InputError(path, "write failed");
    out.close();
    if (std::rename(tmp.c_str(), path.c_str()) != 0) throw InputError(path, "cannot rename temporary file");
  } catch (...) {
    std::remove(tmp.c_str());
    throw;
  }
}

}  // namespace diffray::core
