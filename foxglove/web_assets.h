// The files of mrsim-foxglove's browser page (foxglove/web: the page, its
// script and three.js), read into memory once at start and served by the
// WebSocket server's HTTP handler. Only the fixed list of paths below is
// served; a request's path is looked up in that list, never joined to a
// folder, so no request reaches any other file.
#pragma once

#include <cstddef>
#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace mrsim::foxglove {

struct HttpReply {
  int status = 200;
  std::string content_type;
  std::string body;
};

class WebAssets {
 public:
  // One served file: its URL path, its file name in the page's folder and
  // its Content-Type.
  struct File {
    const char* url_path;
    const char* name;
    const char* content_type;
  };
  static const std::vector<File>& Files();

  // No page: every request gets the hint of where to connect.
  WebAssets() = default;
  // Reads every file of Files() from `dir`. A missing or oversized file
  // leaves the page unavailable (why() says which and how to get it).
  explicit WebAssets(const std::string& dir);

  // The page's folder for the program at `executable`: web/ beside it (the
  // build tree) when it holds the page, else <data dir>/foxglove-web (the
  // install tree, common/data_dir.h); "" when neither has it.
  static std::string FindDir(const std::string& executable);
  // FindDir() of the running program (/proc/self/exe).
  static std::string FindDir();

  bool available() const { return why_.empty(); }
  // Why the page is not served ("" when it is).
  const std::string& why() const { return why_; }

  // The reply to a GET of `resource` (path and query, as in the request
  // line). `ws_port` goes into the hint served without the page.
  HttpReply Serve(std::string_view resource, int ws_port) const;

 private:
  std::map<std::string, std::string, std::less<>> bodies_;  // by URL path
  std::string why_ = "mrsim-foxglove was started without its page's folder";
};

}  // namespace mrsim::foxglove
