#include "sim_core/export/frame_mesh.h"

#include <mujoco/mujoco.h>

#include <stdexcept>

#include "sim_core/mjcf/model_compiler.h"
#include "sim_core/mujoco/mujoco_ptr.h"

namespace mrsim {

TriangleMesh FrameMeshSurface(const Frame& frame, const std::string& base_dir) {
  if (!frame.is_mesh()) return BoxMesh(frame.scale);
  // The frame alone, at the origin, compiled as the simulator would: the
  // same reader, scale and embedded-mesh handling.
  Scenario alone;
  alone.base_dir = base_dir;
  Frame f = frame;
  f.guid = "mesh";
  f.position.setZero();
  f.quat_rotation.setIdentity();
  f.rotation.setZero();
  f.is_static = true;
  alone.loose_frames.push_back(f);
  MjModelPtr model;
  try {
    model = CompileScenarioModel(alone, MjcfOptions{});
  } catch (const std::exception& e) {
    throw std::runtime_error("frame '" + frame.guid +
                             "': cannot read its mesh: " + e.what());
  }
  const mjModel* m = model.get();
  MjDataPtr data(mj_makeData(m));
  if (!data) throw std::runtime_error("cannot allocate MuJoCo data");
  mj_kinematics(m, data.get());
  for (int g = 0; g < m->ngeom; ++g) {
    if (m->geom_type[g] != mjGEOM_MESH) continue;
    const int id = m->geom_dataid[g];
    const int vert0 = m->mesh_vertadr[id];
    const int nvert = m->mesh_vertnum[id];
    const int face0 = m->mesh_faceadr[id];
    const int nface = m->mesh_facenum[id];
    // MuJoCo moved the vertices to the mesh's inertial frame and the geom
    // there; the geom's pose puts them back where the file had them.
    Eigen::Map<const Eigen::Matrix<mjtNum, 3, 3, Eigen::RowMajor>> rot(
        data->geom_xmat + 9 * g);
    Eigen::Map<const Eigen::Matrix<mjtNum, 3, 1>> pos(data->geom_xpos + 3 * g);
    TriangleMesh mesh;
    mesh.vertices.reserve(nvert);
    for (int v = 0; v < nvert; ++v) {
      const float* p = m->mesh_vert + 3 * (vert0 + v);
      mesh.vertices.push_back(rot * Eigen::Vector3d(p[0], p[1], p[2]) + pos);
    }
    mesh.faces.reserve(nface);
    for (int k = 0; k < nface; ++k) {
      const int* idx = m->mesh_face + 3 * (face0 + k);
      mesh.faces.push_back({idx[0], idx[1], idx[2]});
    }
    return mesh;
  }
  throw std::runtime_error("frame '" + frame.guid + "': its mesh has no faces");
}

Eigen::AlignedBox3d FrameBounds(const Frame& frame,
                                const std::string& base_dir) {
  if (!frame.is_mesh()) {
    return Eigen::AlignedBox3d(-frame.scale / 2, frame.scale / 2);
  }
  return FrameMeshSurface(frame, base_dir).Bounds();
}

}  // namespace mrsim
