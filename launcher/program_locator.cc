#include "launcher/program_locator.h"

#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <set>
#include <sstream>
#include <stdexcept>

#include "common/edit_distance.h"

namespace mrsim {

std::vector<std::string> ProgramSearchPath(const std::string& argv0) {
  namespace fs = std::filesystem;
  std::vector<std::string> dirs;
  if (argv0.find('/') != std::string::npos) {
    dirs.push_back(fs::absolute(argv0).parent_path().string());
  }
  std::error_code ec;
  const fs::path self = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    dirs.push_back((self.parent_path().parent_path() / "bin").string());
  }
  if (const char* path = std::getenv("PATH")) {
    std::stringstream ss(path);
    for (std::string dir; std::getline(ss, dir, ':');) {
      if (!dir.empty()) dirs.push_back(dir);
    }
  }
  // Once each (build/bin is often both beside us and on PATH), in order.
  std::vector<std::string> unique;
  for (const std::string& d : dirs) {
    const std::string normal = fs::path(d).lexically_normal().string();
    if (std::find(unique.begin(), unique.end(), normal) == unique.end()) {
      unique.push_back(normal);
    }
  }
  return unique;
}

std::string FindProgram(const std::string& program,
                        const std::vector<std::string>& search_path) {
  if (program.find('/') != std::string::npos) {
    if (access(program.c_str(), X_OK) == 0) return program;
    throw std::runtime_error("program " + program + " is not executable");
  }
  for (const auto& dir : search_path) {
    const std::string candidate = dir + "/" + program;
    if (access(candidate.c_str(), X_OK) == 0) return candidate;
  }
  const std::string prefix = "mrsim-";
  const std::vector<std::string> tools = ListTools(search_path);
  if (program.rfind(prefix, 0) == 0 && !tools.empty()) {
    // A typo: say what there is rather than every folder on PATH.
    const std::string tool = program.substr(prefix.size());
    std::string nearest, list;
    size_t best = 3;  // at most two edits away
    for (const std::string& t : tools) {
      list += (list.empty() ? "" : ", ") + t;
      const size_t d = EditDistance(tool, t);
      if (d < best) best = d, nearest = t;
    }
    throw std::runtime_error(
        "cannot find program '" + program + "'" +
        (nearest.empty() ? "" : " (did you mean '" + prefix + nearest + "'?)") +
        "; the mrsim programs are " + prefix + "{" + list + "}");
  }
  std::string tried;
  for (const auto& dir : search_path) tried += "\n  " + dir;
  throw std::runtime_error("cannot find program '" + program +
                           "'; looked in:" + tried +
                           "\n(build it, or add its directory to PATH)");
}

std::vector<std::string> ListTools(
    const std::vector<std::string>& search_path) {
  namespace fs = std::filesystem;
  std::set<std::string> tools;
  for (const std::string& dir : search_path) {
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(dir, ec)) {
      const std::string name = entry.path().filename().string();
      if (name.rfind("mrsim-", 0) == 0 && name.size() > 6 &&
          access(entry.path().c_str(), X_OK) == 0) {
        tools.insert(name.substr(6));
      }
    }
  }
  return {tools.begin(), tools.end()};
}

}  // namespace mrsim
