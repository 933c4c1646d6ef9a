// Whether MuJoCo's own mesh reader takes a mesh file's bytes at a frame's
// scale: the validator's check of every mesh frame (a file or an embedded
// mesh), so that a scenario which validates also compiles, and a broken
// mesh is reported against its frame, not as a compile error of a
// generated file.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

namespace mrsim {

// Throws std::runtime_error with MuJoCo's message when the bytes of
// `file_name` (its extension says OBJ or STL) do not compile as a mesh
// scaled by `scale`. Results are remembered (by content and scale), so a
// design validated after every edit reads each mesh once.
void CheckMeshReadable(const std::vector<unsigned char>& bytes,
                       const std::string& file_name,
                       const Eigen::Vector3d& scale);

}  // namespace mrsim
