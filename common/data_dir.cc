#include "common/data_dir.h"

#include <cstdlib>
#include <filesystem>

namespace mrsim {

namespace fs = std::filesystem;

std::string DataDirFor(const std::string& executable) {
  if (const char* env = std::getenv("MRSIM_DATA_DIR"); env && *env) {
    return env;
  }
  std::error_code ec;
  const fs::path dir =
      (fs::path(executable).parent_path() / ".." / "share" / "mrsim")
          .lexically_normal();
  if (fs::is_directory(dir, ec)) return dir.string();
  return "";
}

std::string DataDir() {
  std::error_code ec;
  const fs::path self = fs::read_symlink("/proc/self/exe", ec);
  // No /proc (a chroot without it): only MRSIM_DATA_DIR can say.
  return DataDirFor(ec ? std::string() : self.string());
}

std::string FindDataFile(const std::string& relative) {
  const std::string dir = DataDir();
  if (dir.empty()) return "";
  const fs::path path = fs::path(dir) / relative;
  std::error_code ec;
  return fs::exists(path, ec) ? path.string() : "";
}

}  // namespace mrsim
