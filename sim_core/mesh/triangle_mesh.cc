#include "sim_core/mesh/triangle_mesh.h"

#include <algorithm>
#include <cstdint>
#include <cstring>

namespace mrsim {
namespace {

void PutFloat(std::string* out, double value) {
  const float f = static_cast<float>(value);
  uint32_t bits = 0;
  std::memcpy(&bits, &f, sizeof bits);
  // STL is little-endian whatever the machine.
  for (int i = 0; i < 4; ++i)
    out->push_back(static_cast<char>(bits >> (8 * i)));
}

}  // namespace

void TriangleMesh::Append(const TriangleMesh& other,
                          const Eigen::Isometry3d& pose) {
  const int base = static_cast<int>(vertices.size());
  for (const Eigen::Vector3d& v : other.vertices) vertices.push_back(pose * v);
  for (const auto& f : other.faces) {
    faces.push_back({f[0] + base, f[1] + base, f[2] + base});
  }
}

Eigen::AlignedBox3d TriangleMesh::Bounds() const {
  if (vertices.empty()) {
    return Eigen::AlignedBox3d(Eigen::Vector3d::Zero(),
                               Eigen::Vector3d::Zero());
  }
  Eigen::AlignedBox3d box;
  for (const Eigen::Vector3d& v : vertices) box.extend(v);
  return box;
}

TriangleMesh BoxMesh(const Eigen::Vector3d& size) {
  TriangleMesh mesh;
  const Eigen::Vector3d h = size / 2;
  // Vertex i has x = +h.x when bit 0 is set, y when bit 1, z when bit 2.
  for (int i = 0; i < 8; ++i) {
    mesh.vertices.emplace_back(i & 1 ? h.x() : -h.x(), i & 2 ? h.y() : -h.y(),
                               i & 4 ? h.z() : -h.z());
  }
  // Each face as a quad wound counter-clockwise seen from outside.
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6},   // -z, +z
                           {0, 1, 5, 4}, {2, 6, 7, 3},   // -y, +y
                           {0, 4, 6, 2}, {1, 3, 7, 5}};  // -x, +x
  for (const auto& q : quads) {
    mesh.faces.push_back({q[0], q[1], q[2]});
    mesh.faces.push_back({q[0], q[2], q[3]});
  }
  return mesh;
}

std::string BinaryStl(const TriangleMesh& mesh, double unit_scale,
                      const std::string& name) {
  std::string out(80, ' ');
  const std::string header = "mrsim " + name;
  std::copy_n(header.begin(), std::min<size_t>(header.size(), 80), out.begin());
  const auto count = static_cast<uint32_t>(mesh.faces.size());
  for (int i = 0; i < 4; ++i)
    out.push_back(static_cast<char>(count >> (8 * i)));
  out.reserve(out.size() + 50 * mesh.faces.size());
  for (const auto& f : mesh.faces) {
    const Eigen::Vector3d& a = mesh.vertices[f[0]];
    const Eigen::Vector3d& b = mesh.vertices[f[1]];
    const Eigen::Vector3d& c = mesh.vertices[f[2]];
    Eigen::Vector3d n = (b - a).cross(c - a);
    if (n.norm() > 0) n.normalize();
    for (int k = 0; k < 3; ++k) PutFloat(&out, n[k]);
    for (const Eigen::Vector3d* v : {&a, &b, &c}) {
      for (int k = 0; k < 3; ++k) PutFloat(&out, (*v)[k] * unit_scale);
    }
    out.push_back(0);
    out.push_back(0);
  }
  return out;
}

}  // namespace mrsim
