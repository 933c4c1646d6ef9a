// The studio's recently opened or saved scenario files, newest first, kept
// in $XDG_CONFIG_HOME/mrsim/studio_recent (or ~/.config/...).
#pragma once

#include <string>
#include <vector>

namespace mrsim::studio {

class RecentFiles {
 public:
  // `store` empty: the default place above; "-": kept in memory only.
  explicit RecentFiles(std::string store = "");
  const std::vector<std::string>& paths() const { return paths_; }
  // Moves `path` (made absolute) to the front; at most kMax kept. A store
  // that cannot be written is ignored (recent files are a convenience).
  void Add(const std::string& path);

  static constexpr size_t kMax = 8;

 private:
  std::string store_;
  std::vector<std::string> paths_;
};

}  // namespace mrsim::studio
