#include "sim_core/physics/scene_object_state.h"

#include <stdexcept>
#include <string>

#include "sim_core/mjcf/mjcf_names.h"

namespace mrsim {

std::vector<SceneObjectState> ReadSceneObjects(const Physics& physics) {
  std::vector<SceneObjectState> objects;
  const Scenario& scenario = physics.scenario();
  const mjModel* m = physics.model();
  const mjData* d = physics.data();
  for (size_t i = 0; i < scenario.scene_objects.size(); ++i) {
    if (scenario.scene_objects[i].is_static) continue;
    const std::string name = mjcf_names::SceneObject(static_cast<int>(i));
    const int body = mj_name2id(m, mjOBJ_BODY, name.c_str());
    if (body < 0) {
      throw std::runtime_error("scene object '" +
                               scenario.scene_objects[i].guid + "': no body '" +
                               name + "' in the model");
    }
    SceneObjectState s;
    s.index = static_cast<int>(i);
    const mjtNum* p = d->xpos + 3 * body;
    const mjtNum* q = d->xquat + 4 * body;
    s.pose.position = Eigen::Vector3d(p[0], p[1], p[2]);
    s.pose.orientation = Eigen::Quaterniond(q[0], q[1], q[2], q[3]);
    objects.push_back(s);
  }
  return objects;
}

}  // namespace mrsim
