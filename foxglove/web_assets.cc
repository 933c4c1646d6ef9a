#include "foxglove/web_assets.h"

#include <filesystem>
#include <fstream>
#include <sstream>

#include "common/data_dir.h"

namespace mrsim::foxglove {
namespace {

namespace fs = std::filesystem;

// three.core.js is the largest (1.5 MB); anything far over that is not
// the file that was shipped.
constexpr std::uintmax_t kMaxFileBytes = 8u << 20;

constexpr const char* kHtml = "text/html; charset=utf-8";
constexpr const char* kJs = "text/javascript; charset=utf-8";

}  // namespace

const std::vector<WebAssets::File>& WebAssets::Files() {
  static const std::vector<File> kFiles = {
      {"/", "index.html", kHtml},
      {"/index.html", "index.html", kHtml},
      {"/mrsim_page.js", "mrsim_page.js", kJs},
      {"/three.module.js", "three.module.js", kJs},
      {"/three.core.js", "three.core.js", kJs},
      {"/OrbitControls.js", "OrbitControls.js", kJs},
  };
  return kFiles;
}

WebAssets::WebAssets(const std::string& dir) {
  if (dir.empty()) {
    why_ =
        "the page's folder was not found (web/ beside mrsim-foxglove, or "
        "foxglove-web in mrsim's data folder)";
    return;
  }
  for (const File& f : Files()) {
    const fs::path path = fs::path(dir) / f.name;
    std::error_code ec;
    const std::uintmax_t size = fs::file_size(path, ec);
    if (ec || size > kMaxFileBytes) {
      bodies_.clear();
      why_ =
          path.string() +
          (ec ? ": missing (three.js comes from npm: scripts/install_deps.sh "
                "installs it, the build copies it)"
              : ": larger than 8 MB, not the file shipped");
      return;
    }
    std::ifstream in(path, std::ios::binary);
    std::ostringstream body;
    body << in.rdbuf();
    if (!in) {
      bodies_.clear();
      why_ = path.string() + ": cannot be read";
      return;
    }
    bodies_[f.url_path] = body.str();
  }
  why_.clear();
}

std::string WebAssets::FindDir(const std::string& executable) {
  std::error_code ec;
  const fs::path beside = fs::path(executable).parent_path() / "web";
  if (fs::is_regular_file(beside / "index.html", ec)) return beside.string();
  const std::string data = DataDirFor(executable);
  if (!data.empty()) {
    const fs::path installed = fs::path(data) / "foxglove-web";
    if (fs::is_regular_file(installed / "index.html", ec)) {
      return installed.string();
    }
  }
  return "";
}

std::string WebAssets::FindDir() {
  std::error_code ec;
  const fs::path self = fs::read_symlink("/proc/self/exe", ec);
  return ec ? FindDir(std::string()) : FindDir(self.string());
}

HttpReply WebAssets::Serve(std::string_view resource, int ws_port) const {
  const std::string_view path = resource.substr(0, resource.find('?'));
  if (!available()) {
    if (path != "/" && path != "/index.html") {
      return {404, "text/plain; charset=utf-8", "not found\n"};
    }
    return {200, "text/plain; charset=utf-8",
            "mrsim-foxglove: open Foxglove or Lichtblick and connect to "
            "ws://<this host>:" +
                std::to_string(ws_port) +
                " (Foxglove WebSocket). See docs/foxglove.md.\n"
                "The browser page is not served: " +
                why_ + "\n"};
  }
  for (const File& f : Files()) {
    if (path == f.url_path)
      return {200, f.content_type, bodies_.at(f.url_path)};
  }
  return {404, "text/plain; charset=utf-8", "not found\n"};
}

}  // namespace mrsim::foxglove
