// Maps ContactFriction material pairs onto MuJoCo contact parameters
// (docs/physics.md, "Contacts").
#pragma once

#include <Eigen/Core>
#include <string>
#include <utility>
#include <vector>

#include "sim_core/scenario/scenario.h"

namespace mrsim {

// The entry for two materials in either order, or nullptr.
const ContactFriction* FindContactFriction(const Scenario& scenario,
                                           const std::string& material1,
                                           const std::string& material2);

// MuJoCo solref (time constant, damping ratio) for an entry:
// restitution e -> damping ratio z = -ln(e)/sqrt(pi^2 + ln(e)^2) (1 for
// e <= 0); Young's modulus E -> the spring's 1 / natural frequency
// w = sqrt(m_ref / (E * l_ref)) with m_ref = 0.1 kg and l_ref = 0.01 m,
// never below 4 ms; time constant w / z (MuJoCo's spring is
// 1 / (timeconst * z)^2, so e changes the damping only). Independent of the
// timestep, so results converge as the step shrinks (MuJoCo raises time
// constants below 2 steps to 2 steps, i.e. for steps above 2 ms).
Eigen::Vector2d ContactSolref(const ContactFriction& entry);

using MjcfAttributes = std::vector<std::pair<std::string, std::string>>;

// friction and solref of a geom of this material when the scenario has an
// entry pairing the material with itself, else none (MuJoCo defaults).
MjcfAttributes ContactGeomAttributes(const Scenario& scenario,
                                     const std::string& material);

// friction and solref of a <pair> for an entry of two different materials.
MjcfAttributes ContactPairAttributes(const ContactFriction& entry);

}  // namespace mrsim
