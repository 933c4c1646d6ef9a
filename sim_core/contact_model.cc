#include "sim_core/contact_model.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace mrsim {
namespace {

constexpr double kRefMass = 0.1;     // kg, one module
constexpr double kRefLength = 0.01;  // m, size of a contact patch
constexpr double kTorsional = 0.005;
constexpr double kRolling = 0.0001;
// The stiffest contact: a material's time constant, not the step's, so a
// run at 0.5 ms gives what a run at 2 ms gives. 4 ms is twice the default
// 2 ms step, the stiffest MuJoCo integrates stably there; MuJoCo itself
// raises it to 2 steps for steps above 2 ms.
constexpr double kMinTimeconst = 0.004;

std::string Num(double v) { return v == 0 ? "0" : fmt::format("{}", v); }

}  // namespace

const ContactFriction* FindContactFriction(const Scenario& scenario,
                                           const std::string& material1,
                                           const std::string& material2) {
  for (const ContactFriction& c : scenario.contact_frictions) {
    if ((c.material1 == material1 && c.material2 == material2) ||
        (c.material1 == material2 && c.material2 == material1)) {
      return &c;
    }
  }
  return nullptr;
}

Eigen::Vector2d ContactSolref(const ContactFriction& entry) {
  double damping = 1.0;
  const double e = std::min(entry.restitution, 0.99);
  if (e > 0) {
    const double l = std::log(e);
    damping = -l / std::sqrt(M_PI * M_PI + l * l);
  }
  double timeconst = kMinTimeconst;
  if (entry.youngs_modulus > 0) {
    timeconst = std::max(
        timeconst, std::sqrt(kRefMass / (entry.youngs_modulus * kRefLength)));
  }
  return Eigen::Vector2d(timeconst, damping);
}

MjcfAttributes ContactGeomAttributes(const Scenario& scenario,
                                     const std::string& material) {
  const ContactFriction* c = FindContactFriction(scenario, material, material);
  if (!c) return {};
  const Eigen::Vector2d solref = ContactSolref(*c);
  return {{"friction", Num(std::max(c->friction, 0.0)) + " " + Num(kTorsional) +
                           " " + Num(kRolling)},
          {"solref", Num(solref.x()) + " " + Num(solref.y())}};
}

MjcfAttributes ContactPairAttributes(const ContactFriction& entry) {
  const Eigen::Vector2d solref = ContactSolref(entry);
  const double f = std::max(entry.friction, 0.0);
  return {{"friction", Num(f) + " " + Num(f) + " " + Num(kTorsional) + " " +
                           Num(kRolling) + " " + Num(kRolling)},
          {"solref", Num(solref.x()) + " " + Num(solref.y())}};
}

}  // namespace mrsim
