#include "studio/design/recent_files.h"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>

namespace mrsim::studio {

namespace fs = std::filesystem;

RecentFiles::RecentFiles(std::string store) : store_(std::move(store)) {
  if (store_.empty()) {
    const char* xdg = std::getenv("XDG_CONFIG_HOME");
    const char* home = std::getenv("HOME");
    if (xdg && *xdg) {
      store_ = std::string(xdg) + "/mrsim/studio_recent";
    } else if (home && *home) {
      store_ = std::string(home) + "/.config/mrsim/studio_recent";
    } else {
      store_ = "-";
    }
  }
  if (store_ == "-") return;
  std::ifstream in(store_);
  std::string line;
  while (std::getline(in, line) && paths_.size() < kMax) {
    if (!line.empty()) paths_.push_back(line);
  }
}

void RecentFiles::Add(const std::string& path) {
  std::error_code ec;
  const std::string abs = fs::absolute(path, ec).lexically_normal().string();
  paths_.erase(std::remove(paths_.begin(), paths_.end(), abs), paths_.end());
  paths_.insert(paths_.begin(), abs);
  if (paths_.size() > kMax) paths_.resize(kMax);
  if (store_ == "-") return;
  fs::create_directories(fs::path(store_).parent_path(), ec);
  std::ofstream out(store_, std::ios::trunc);
  for (const std::string& p : paths_) out << p << "\n";
}

}  // namespace mrsim::studio
