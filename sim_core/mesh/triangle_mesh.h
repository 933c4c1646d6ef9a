// A closed triangle surface in metres: what a printable part is made of.
// Boxes are built here; meshes a frame names come from MuJoCo's reader
// (part_geometry.h). Faces wind counter-clockwise seen from outside, so
// their normals point out, as STL expects.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <string>
#include <vector>

namespace mrsim {

struct TriangleMesh {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<std::array<int, 3>> faces;  // indices into vertices

  // Appends `other` moved by `pose` (rotation then translation).
  void Append(const TriangleMesh& other, const Eigen::Isometry3d& pose);
  // Axis-aligned bounds; both zero when there are no vertices.
  Eigen::AlignedBox3d Bounds() const;
};

// A box of full extents `size` centred on the origin, axes aligned:
// 8 vertices, 12 triangles, every edge shared by exactly two of them.
TriangleMesh BoxMesh(const Eigen::Vector3d& size);

// Binary STL (80-byte header, little-endian float32) of `mesh` with every
// coordinate multiplied by `unit_scale` (1000: millimetres, what slicers
// assume). `name` goes into the header, cut to fit.
std::string BinaryStl(const TriangleMesh& mesh, double unit_scale,
                      const std::string& name);

}  // namespace mrsim
