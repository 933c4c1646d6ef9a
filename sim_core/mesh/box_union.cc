#include "sim_core/mesh/box_union.h"

#include <algorithm>
#include <cmath>

namespace mrsim {

std::optional<OrientedBox> FlushBoxUnion(const OrientedBox& a,
                                         const OrientedBox& b,
                                         double tolerance) {
  const double tol = tolerance * std::max(a.half.maxCoeff(), b.half.maxCoeff());
  if (!(tol > 0)) return std::nullopt;
  // b's axes in a's frame must be a's axes, permuted and signed.
  const Eigen::Matrix3d ra = a.quat.normalized().toRotationMatrix();
  const Eigen::Matrix3d m =
      ra.transpose() * b.quat.normalized().toRotationMatrix();
  Eigen::Vector3d b_half;
  for (int i = 0; i < 3; ++i) {
    int ones = 0;
    for (int j = 0; j < 3; ++j) {
      const double v = std::abs(m(i, j));
      if (std::abs(v - 1) <= 1e-9) {
        ++ones;
        b_half[i] = b.half[j];
      } else if (v > 1e-9) {
        return std::nullopt;
      }
    }
    if (ones != 1) return std::nullopt;
  }
  const Eigen::Vector3d d = ra.transpose() * (b.center - a.center);
  int along = -1;
  for (int k = 0; k < 3; ++k) {
    if (std::abs(std::abs(d[k]) - (a.half[k] + b_half[k])) <= tol) {
      along = k;
      break;
    }
  }
  if (along < 0) return std::nullopt;
  for (int j = 0; j < 3; ++j) {
    if (j == along) continue;
    if (std::abs(d[j]) > tol || std::abs(a.half[j] - b_half[j]) > tol) {
      return std::nullopt;
    }
  }
  OrientedBox u;
  u.quat = a.quat.normalized();
  u.half = a.half;
  u.half[along] = a.half[along] + b_half[along];
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();
  offset[along] = (d[along] > 0 ? 1 : -1) * b_half[along];
  u.center = a.center + ra * offset;
  return u;
}

}  // namespace mrsim
