#include "sim_core/mjcf/model_compiler.h"

#include <algorithm>
#include <cstring>
#include <mutex>
#include <stdexcept>
#include <utility>
#include <vector>

#include "sim_core/mujoco/mujoco_compile_lock.h"
#include "sim_core/mujoco/mujoco_handlers.h"
#include "sim_core/scenario/terrain.h"

namespace mrsim {

MjModelPtr CompileScenarioModel(const Scenario& scenario, MjcfOptions options,
                                MjcfInfo* info) {
  options.assets_in_memory = true;
  options.hfield_data_after_compile = true;
  MjcfInfo own_info;
  if (info == nullptr) info = &own_info;
  const std::string xml = BuildMjcf(scenario, options, info);

  InstallMujocoHandlers();  // before any MuJoCo call: never print or exit
  MjModelPtr model;
  {
    std::lock_guard<std::mutex> lock(MujocoCompileMutex());
    MjVfsPtr vfs = MakeMjVfs();
    const std::string kName = "mrsim_scenario.xml";
    AddMjVfsFile(vfs.get(), kName, xml.data(), xml.size());
    for (const auto& [name, bytes] : info->memory_files) {
      if (mj_findFileVFS(vfs.get(), name.c_str()) >= 0) continue;
      AddMjVfsFile(vfs.get(), name, bytes.data(), bytes.size());
    }
    char error[1024] = {0};
    model.reset(mj_loadXML(kName.c_str(), vfs.get(), error, sizeof(error)));
    if (!model) {
      throw std::runtime_error(
          std::string("MuJoCo cannot compile the scenario: ") + error);
    }
  }
  mjModel* m = model.get();
  if (!scenario.scene.height_image.empty() && m->nhfield > 0) {
    const std::vector<float> heights =
        HeightFieldData(LoadTerrainImage(scenario.scene, scenario.base_dir));
    std::copy(heights.begin(), heights.end(),
              m->hfield_data + m->hfield_adr[0]);
  }
  return model;
}

}  // namespace mrsim
