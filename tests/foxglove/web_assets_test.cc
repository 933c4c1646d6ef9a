// The browser page's HTTP side, in-process: only the shipped files are
// served, each with its Content-Type, whatever path a request names; a
// server without the page's files says what is missing; the files are
// found beside the binary (build tree) and in the data folder (install).
#include "foxglove/web_assets.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "tests/common/child_process.h"

namespace mrsim::foxglove {
namespace {

namespace fs = std::filesystem;

void Write(const fs::path& path, const std::string& text) {
  fs::create_directories(path.parent_path());
  std::ofstream(path) << text;
}

// A page folder with every shipped file (its content: its name), and a
// secret beside and above it that no request may reach.
std::string PageDir() {
  const fs::path root = testing::TempDir("web_assets");
  const fs::path dir = root / "web";
  for (const WebAssets::File& f : WebAssets::Files()) {
    Write(dir / f.name, std::string("contents of ") + f.name);
  }
  Write(dir / "secret.txt", "secret");
  Write(root / "secret.txt", "secret");
  return dir.string();
}

TEST(WebAssets, ServesEachShippedFileWithItsContentType) {
  const WebAssets web(PageDir());
  ASSERT_TRUE(web.available()) << web.why();
  HttpReply r = web.Serve("/", 8765);
  EXPECT_EQ(r.status, 200);
  EXPECT_EQ(r.content_type, "text/html; charset=utf-8");
  EXPECT_EQ(r.body, "contents of index.html");
  r = web.Serve("/?token=abc", 8765);  // the control token rides along
  EXPECT_EQ(r.body, "contents of index.html");
  r = web.Serve("/three.core.js", 8765);
  EXPECT_EQ(r.status, 200);
  EXPECT_EQ(r.content_type, "text/javascript; charset=utf-8");
  EXPECT_EQ(r.body, "contents of three.core.js");
  for (const char* js :
       {"/mrsim_page.js", "/three.module.js", "/OrbitControls.js"}) {
    EXPECT_EQ(web.Serve(js, 8765).status, 200) << js;
  }
}

TEST(WebAssets, AnyOtherPathIsNotFoundAndReachesNoFile) {
  const WebAssets web(PageDir());
  ASSERT_TRUE(web.available()) << web.why();
  for (const char* path :
       {"/secret.txt", "/../secret.txt", "/web/../secret.txt",
        "/%2e%2e/secret.txt", "/..%2fsecret.txt", "//etc/passwd", "/etc/passwd",
        "/index.html/", "/index.html/..", "/./index.html", "/INDEX.HTML",
        "/three.core.js%00", "index.html", "", "/web/",
        "http://evil/index.html", "/node_modules/three/package.json"}) {
    const HttpReply r = web.Serve(path, 8765);
    EXPECT_EQ(r.status, 404) << path;
    EXPECT_EQ(r.content_type, "text/plain; charset=utf-8") << path;
    EXPECT_EQ(r.body.find("secret"), std::string::npos) << path;
  }
}

TEST(WebAssets, WithoutItsFilesTheRootSaysWhatIsMissingAndWhereToConnect) {
  const std::string dir = PageDir();
  fs::remove(fs::path(dir) / "three.core.js");
  const WebAssets web(dir);
  EXPECT_FALSE(web.available());
  EXPECT_NE(web.why().find("three.core.js: missing"), std::string::npos)
      << web.why();
  const HttpReply r = web.Serve("/", 8123);
  EXPECT_EQ(r.status, 200);
  EXPECT_EQ(r.content_type, "text/plain; charset=utf-8");
  EXPECT_NE(r.body.find("ws://<this host>:8123"), std::string::npos) << r.body;
  EXPECT_NE(r.body.find("scripts/install_deps.sh"), std::string::npos)
      << r.body;
  EXPECT_EQ(web.Serve("/three.module.js", 8123).status, 404);
  EXPECT_FALSE(WebAssets().available());
}

TEST(WebAssets, ThePageIsFoundBesideTheBinaryAndInTheInstallTree) {
  EXPECT_EQ(WebAssets::FindDir(
                testing::BinaryPath("foxglove/process/mrsim-foxglove")),
            testing::BinaryPath("foxglove/process/web"));
  const fs::path prefix = testing::TempDir("web_assets_install");
  Write(prefix / "share/mrsim/foxglove-web/index.html", "page");
  EXPECT_EQ(WebAssets::FindDir((prefix / "bin/mrsim-foxglove").string()),
            (prefix / "share/mrsim/foxglove-web").string());
  const fs::path bare = testing::TempDir("web_assets_nowhere");
  EXPECT_EQ(WebAssets::FindDir((bare / "bin/mrsim-foxglove").string()), "");
}

}  // namespace
}  // namespace mrsim::foxglove
