#include "diffray/core/atomic_file.h"

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>

#include "diffray/core/error.h"

namespace diffray::core {

void writeFileAtomically(const std::string& path, const std::function<void(std::ostream&)>& write) {
  const std::string tmp = path + ".tmp." + std::to_string(::getpid());
  const TempRegistration registered(tmp);  // deleted if the program is interrupted meanwhile
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

OutputFiles::~OutputFiles() {
  for (const auto& [staging, target] : staged_) std::remove(staging.c_str());
}

void OutputFiles::commit() {
  for (std::size_t i = 0; i < staged_.size(); ++i) {
    const auto& [staging, target] = staged_[i];
    if (std::rename(staging.c_str(), target.c_str()) != 0) {
      const std::string failed = target;
      staged_.erase(staged_.begin(), staged_.begin() + static_cast<std::ptrdiff_t>(i));  // already in place
      throw InputError(failed, "cannot rename the finished output into place");  // the destructor cleans up
    }
    committed_.push_back(target);
  }
  staged_.clear();
  registered_.clear();
}

void OutputFiles::rethrowNaming(const InputError& e, const std::string& staging, const std::string& path) {
  const auto renamed = [&](std::string s) {
    for (std::size_t at = s.find(staging); at != std::string::npos; at = s.find(staging, at + path.size()))
      s.replace(at, staging.size(), path);
    return s;
  };
  const std::string where = renamed(e.where()), message = renamed(e.what());
  const std::string prefix = where.empty() ? "" : where + ": ";
  throw InputError(where, message.compare(0, prefix.size(), prefix) == 0 ? message.substr(prefix.size()) : message);
}

std::string OutputFiles::stagingName(const std::string& path, std::size_t index) {
  const std::filesystem::path p(path);
  std::filesystem::path staged = p;
  staged.replace_filename(p.stem().string() + ".part" + std::to_string(::getpid()) + "-" + std::to_string(index) +
                          p.extension().string());
  return staged.string();
}

}  // namespace diffray::core
