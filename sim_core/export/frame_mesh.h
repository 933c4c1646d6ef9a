// The surface of a mesh frame (Frame::shape an OBJ/STL path or an embedded
// mesh), scaled by Frame::scale, in the frame's own coordinates, as the
// physics sees it. The file is read by MuJoCo's own mesh reader (the one
// the simulator uses), so nothing here parses mesh bytes itself.
#pragma once

#include <string>

#include "sim_core/scenario/scenario.h"
#include "sim_core/mesh/triangle_mesh.h"

namespace mrsim {

// Throws std::runtime_error naming the frame when the mesh cannot be read
// (missing file, a format MuJoCo refuses, too many vertices).
TriangleMesh FrameMeshSurface(const Frame& frame, const std::string& base_dir);

// Bounds of that surface in the frame's own coordinates; for a box frame,
// the box (+-scale/2).
Eigen::AlignedBox3d FrameBounds(const Frame& frame,
                                const std::string& base_dir);

}  // namespace mrsim
