#include "sim_core/mesh/mesh_check.h"

#include <fmt/format.h>
#include <mujoco/mujoco.h>

#include <cstring>
#include <filesystem>
#include <map>
#include <mutex>
#include <stdexcept>
#include <tuple>

#include "common/hash.h"
#include "sim_core/mujoco/mujoco_compile_lock.h"
#include "sim_core/mujoco/mujoco_handlers.h"
#include "sim_core/mujoco/mujoco_ptr.h"
#include "sim_core/mesh/obj_check.h"

namespace mrsim {
namespace {

// Enough for every mesh of a design; a fuzzer's stream of meshes only
// starts the memory over.
constexpr size_t kMaxRemembered = 256;

using Key =
    std::tuple<std::uint64_t, size_t, std::string, double, double, double>;

std::string CompileError(const std::vector<unsigned char>& bytes,
                         const std::string& ext, const std::string& shown_name,
                         const Eigen::Vector3d& scale) {
  const std::string mesh_file = "mrsim-mesh-check" + ext;
  const std::string xml = fmt::format(
      "<mujoco><asset><mesh name=\"m\" file=\"{}\" scale=\"{:.17g} {:.17g} "
      "{:.17g}\"/></asset><worldbody><body><freejoint/><geom type=\"mesh\" "
      "mesh=\"m\"/></body></worldbody></mujoco>",
      mesh_file, scale.x(), scale.y(), scale.z());
  InstallMujocoHandlers();  // before any MuJoCo call: never print or exit
  std::lock_guard<std::mutex> lock(MujocoCompileMutex());
  MjVfsPtr vfs = MakeMjVfs();
  AddMjVfsFile(vfs.get(), "mrsim-mesh-check.xml", xml.data(), xml.size());
  AddMjVfsFile(vfs.get(), mesh_file, bytes.data(), bytes.size());
  char error[1024] = {0};
  MjModelPtr model(
      mj_loadXML("mrsim-mesh-check.xml", vfs.get(), error, sizeof(error)));
  if (model) return "";
  std::string text = error;
  // The user's file name, not the one the check gave it.
  for (size_t at = text.find(mesh_file); at != std::string::npos;
       at = text.find(mesh_file, at + shown_name.size())) {
    text.replace(at, mesh_file.size(), shown_name);
  }
  // MuJoCo's message names the generated file and asset: only its reason
  // means something to the user.
  if (const size_t at = text.find("\nObject name"); at != std::string::npos) {
    text.resize(at);
  }
  while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) {
    text.pop_back();
  }
  return text.empty() ? "MuJoCo cannot read it" : text;
}

}  // namespace

void CheckMeshReadable(const std::vector<unsigned char>& bytes,
                       const std::string& file_name,
                       const Eigen::Vector3d& scale) {
  std::string ext = std::filesystem::path(file_name).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(c));
  const std::string shown_name =
      std::filesystem::path(file_name).filename().string();
  // The name is part of the key: MuJoCo's message names the file.
  const Key key{Fnv1a64(bytes.data(), bytes.size()),
                bytes.size(),
                shown_name,
                scale.x(),
                scale.y(),
                scale.z()};
  static std::mutex remembered_mutex;
  static std::map<Key, std::string> remembered;
  std::string error;
  bool known = false;
  {
    std::lock_guard<std::mutex> lock(remembered_mutex);
    const auto it = remembered.find(key);
    if (it != remembered.end()) {
      error = it->second;
      known = true;
    }
  }
  if (!known) {
    if (ext == ".obj") {
      // MuJoCo's OBJ loader trusts the file: ours reads it first.
      try {
        CheckObjText(reinterpret_cast<const char*>(bytes.data()), bytes.size());
      } catch (const std::exception& e) {
        error = shown_name + ": " + e.what();
      }
    }
    if (error.empty()) error = CompileError(bytes, ext, shown_name, scale);
    std::lock_guard<std::mutex> lock(remembered_mutex);
    if (remembered.size() >= kMaxRemembered) remembered.clear();
    remembered.emplace(key, error);
  }
  if (!error.empty()) throw std::runtime_error(error);
}

}  // namespace mrsim
