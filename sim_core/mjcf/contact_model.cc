#include "sim_core/mjcf/contact_model.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace mrsim {
namespace {

constexpr double kRefMass = 0.1;     // kg, one module
constexpr double kRefLength = 0.01;  // m, size of a contact patch
constexpr double kTorsional = 0.005;
constexpr double kRolling = 0.0001;
// The stiffest contact (1 / its natural frequency): a material's, not the
// step's, so a run at 0.5 ms gives what a run at 2 ms gives. 4 ms is twice
// the default 2 ms step, the stiffest MuJoCo integrates stably there;
// MuJoCo itself raises time constants to 2 steps for steps above 2 ms.
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
  // 1 / natural frequency of the contact spring: the material's stiffness
  // (a patch of E l_ref under m_ref), never stiffer than the step allows.
  double inverse_frequency = kMinTimeconst;
  if (entry.youngs_modulus > 0) {
    inverse_frequency =
        std::max(inverse_frequency,
                 std::sqrt(kRefMass / (entry.youngs_modulus * kRefLength)));
  }
  // MuJoCo's solref time constant is the decay time, and its spring is
  // k = 1 / (timeconst * dampratio)^2: with the time constant fixed, a lower
  // damping ratio made the spring stiffer by 1 / dampratio^2, beyond what
  // the step integrates (a box dropped at 2 ms with restitution 0.5 rose
  // 23 times higher than it fell, and a bouncy snake blew up). Dividing by
  // the damping ratio keeps the spring at the material's stiffness, so the
  // restitution sets only the damping. Restitution 0: unchanged.
  return Eigen::Vector2d(inverse_frequency / damping, damping);
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
