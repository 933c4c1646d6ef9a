#include "sim_core/scenario/embed_assets.h"

#include <cerrno>
#include <cstring>
#include <optional>
#include <stdexcept>
#include <vector>

#include "common/input_limits.h"
#include "sim_core/mesh/base64.h"
#include "sim_core/mesh/embedded_mesh.h"

namespace mrsim {
namespace {

std::string Resolve(const std::string& path, const std::string& base_dir) {
  if (!path.empty() && path[0] != '/' && !base_dir.empty()) {
    return base_dir + "/" + path;
  }
  return path;
}

}  // namespace

void EmbedAssetFiles(Scenario& scenario) {
  auto embed = [&scenario](Frame& f, const std::string& where) {
    if (!f.is_mesh() || IsEmbeddedMesh(f.shape)) return;
    try {
      f.shape = EmbedMeshFile(Resolve(f.shape, scenario.base_dir));
    } catch (const std::exception& e) {
      throw std::runtime_error(where + " '" + f.guid + "' shape: " + e.what());
    }
  };
  for (Robot& r : scenario.robots) {
    for (Module& m : r.modules) {
      for (Frame& f : m.frames) embed(f, "robot " + r.name + " frame");
    }
  }
  for (Frame& f : scenario.loose_frames) embed(f, "loose frame");

  std::string& image = scenario.scene.height_image;
  if (image.empty() || image.rfind("base64:", 0) == 0) return;
  const std::string path = Resolve(image, scenario.base_dir);
  std::optional<std::string> bytes;
  try {
    bytes = ReadFileAtMost(path);
  } catch (const std::exception& e) {
    throw std::runtime_error("scene heightImage " + path + ": " + e.what());
  }
  // Not a file: the text is base64 bytes already (Scene::height_image).
  if (!bytes) return;
  image = "base64:" + Base64Encode(std::vector<unsigned char>(bytes->begin(),
                                                              bytes->end()));
}

bool NamesAssetFiles(const Scenario& scenario) {
  const auto names_file = [](const Frame& f) {
    return f.is_mesh() && !IsEmbeddedMesh(f.shape);
  };
  for (const Robot& r : scenario.robots) {
    for (const Module& m : r.modules) {
      for (const Frame& f : m.frames) {
        if (names_file(f)) return true;
      }
    }
  }
  for (const Frame& f : scenario.loose_frames) {
    if (names_file(f)) return true;
  }
  const std::string& image = scenario.scene.height_image;
  return !image.empty() && image.rfind("base64:", 0) != 0;
}

}  // namespace mrsim
