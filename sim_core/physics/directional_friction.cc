#include "sim_core/physics/directional_friction.h"

#include <algorithm>
#include <map>
#include <string>

#include "sim_core/mjcf/mjcf_names.h"

namespace mrsim {
namespace {

// Below this share of the forward axis left in the contact plane (the
// part stands on its end) the axis gives no direction: both tangents get
// the lateral coefficient.
constexpr double kMinInPlane = 1e-6;

bool Collides(const mjModel* m, int g) {
  return m->geom_contype[g] != 0 || m->geom_conaffinity[g] != 0;
}

}  // namespace

DirectionalFriction::DirectionalFriction(const Scenario& scenario,
                                         const mjModel* m) {
  // Material indices: every material a directional entry names.
  std::map<std::string, int> index;
  for (const ContactFriction& c : scenario.contact_frictions) {
    if (!c.directional) continue;
    index.emplace(c.material1, static_cast<int>(index.size()));
    index.emplace(c.material2, static_cast<int>(index.size()));
  }
  materials_ = static_cast<int>(index.size());
  pair_rule_.assign(materials_ * materials_, -1);
  for (const ContactFriction& c : scenario.contact_frictions) {
    if (!c.directional) continue;
    Rule r;
    r.forward = c.forward_friction;
    r.backward = c.backward_friction;
    r.lateral = c.lateral_friction;
    r.torsional = c.torsional_friction;
    r.rolling = c.rolling_friction;
    rules_.push_back(r);
    const int a = index.at(c.material1), b = index.at(c.material2);
    pair_rule_[a * materials_ + b] = static_cast<int>(rules_.size()) - 1;
  }
  // A geom's scenario material is in its MuJoCo material's name,
  // "<kind>/<material>"; the ground's look is "scene/ground".
  geom_material_.assign(m->ngeom, -1);
  geom_wheel_.assign(m->ngeom, 0);
  for (int g = 0; g < m->ngeom; ++g) {
    if (!Collides(m, g) || m->geom_matid[g] < 0) continue;
    const char* look = mj_id2name(m, mjOBJ_MATERIAL, m->geom_matid[g]);
    if (!look) continue;
    std::string name = look;
    if (name == "scene/ground") {
      name = scenario.scene.material_name;
    } else {
      const size_t slash = name.find('/');
      if (slash == std::string::npos) continue;
      name = name.substr(slash + 1);
    }
    const auto it = index.find(name);
    if (it != index.end()) geom_material_[g] = it->second;
  }
  bool wheels = false;
  for (size_t r = 0; r < scenario.robots.size(); ++r) {
    const std::string robot = RobotName(scenario, static_cast<int>(r));
    const auto& modules = scenario.robots[r].modules;
    for (size_t i = 0; i < modules.size(); ++i) {
      if (!modules[i].passive_wheels) continue;
      for (int f = 0; f < 2; ++f) {
        const int g = mj_name2id(
            m, mjOBJ_GEOM,
            mjcf_names::FrameBody(robot, static_cast<int>(i), f).c_str());
        if (g >= 0 && Collides(m, g)) {
          geom_wheel_[g] = 1;
          wheels = true;
        }
      }
    }
  }
  empty_ = rules_.empty() && !wheels;
}

std::unique_ptr<PhysicsEffect> DirectionalFriction::Make(
    const PhysicsEffectInput& input) {
  auto friction =
      std::make_unique<DirectionalFriction>(input.scenario, input.model);
  if (friction->empty()) return nullptr;
  return friction;
}

const DirectionalFriction::Rule* DirectionalFriction::Find(const mjModel* m,
                                                           int g1, int g2,
                                                           int* side) const {
  static const Rule kWheel{0, 0, 0, 0, 0, true};
  // Passive wheels win over a material entry; of two, the first geom's.
  if (geom_wheel_[g1]) {
    *side = 0;
    return &kWheel;
  }
  if (geom_wheel_[g2]) {
    *side = 1;
    return &kWheel;
  }
  const int a = geom_material_[g1], b = geom_material_[g2];
  if (a < 0 || b < 0) return nullptr;
  const int ab = pair_rule_[a * materials_ + b];
  const int ba = pair_rule_[b * materials_ + a];
  if (ab >= 0 && ba >= 0) {
    // Both orders match (one material on both sides, or two entries): the
    // part that moves orients it, geom1's when both move.
    *side = m->body_rootid[m->geom_bodyid[g1]] == 0 &&
                    m->body_rootid[m->geom_bodyid[g2]] != 0
                ? 1
                : 0;
    return &rules_[*side == 0 ? ab : ba];
  }
  if (ab >= 0) {
    *side = 0;
    return &rules_[ab];
  }
  if (ba >= 0) {
    *side = 1;
    return &rules_[ba];
  }
  return nullptr;
}

void DirectionalFriction::AdjustContacts(const mjModel* m, mjData* d) const {
  if (empty_ || d->ncon == 0) return;
  const int nv = m->nv;
  mjMARKSTACK;
  // The velocity the contact points are heading for: this state's plus one
  // step of the last unconstrained acceleration (gravity, servos, applied
  // forces). A part at rest that is being pushed forward so picks the
  // forward coefficient, one pushed back the backward one.
  mjtNum* w = mj_stackAlloc(d, nv);
  mju_addScl(w, d->qvel, d->qacc_smooth, m->opt.timestep, nv);
  mjtNum* jac = mj_stackAlloc(d, 3 * nv);
  auto point_speed = [&](int body, const mjtNum* pos, const mjtNum* dir) {
    if (body == 0 || nv == 0) return 0.0;
    mj_jac(m, d, jac, nullptr, pos, body);
    mjtNum v[3];
    mju_mulMatVec(v, jac, w, 3, nv);
    return mju_dot3(v, dir);
  };
  for (int i = 0; i < d->ncon; ++i) {
    mjContact& c = d->contact[i];
    if (c.dim < 3 || c.exclude != 0) continue;
    int side = 0;
    const Rule* rule = Find(m, c.geom1, c.geom2, &side);
    if (!rule) continue;
    const int part = side == 0 ? c.geom1 : c.geom2;
    const int other = side == 0 ? c.geom2 : c.geom1;
    const int body = m->geom_bodyid[part];
    const mjtNum* xmat = d->xmat + 9 * body;
    const mjtNum axis[3] = {xmat[0], xmat[3], xmat[6]};  // the part's +x
    const mjtNum* n = c.frame;
    mjtNum t1[3];
    mju_addScl3(t1, axis, n, -mju_dot3(axis, n));
    const mjtNum in_plane = mju_normalize3(t1);
    const double lateral = rule->wheel ? c.friction[0] : rule->lateral;
    double along = lateral;
    if (in_plane > kMinInPlane) {
      mjtNum t2[3];
      mju_cross(t2, n, t1);
      mju_copy3(c.frame + 3, t1);
      mju_copy3(c.frame + 6, t2);
      const double slide = point_speed(body, c.pos, t1) -
                           point_speed(m->geom_bodyid[other], c.pos, t1);
      const double forward = rule->wheel ? kWheelRolling : rule->forward;
      const double backward = rule->wheel ? kWheelRolling : rule->backward;
      // A tilted part (its axis partly along the normal) blends towards
      // the lateral coefficient, so nothing jumps as it stands up.
      along =
          lateral + in_plane * ((slide >= 0 ? forward : backward) - lateral);
    }
    c.friction[0] = along;
    c.friction[1] = lateral;
    if (!rule->wheel) {
      c.friction[2] = rule->torsional;
      c.friction[3] = c.friction[4] = rule->rolling;
      // The entry decides the contact's dimension: condim 3 (sliding
      // only), 4 with spin friction, 6 with rolling friction too.
      c.dim = rule->rolling > 0 ? 6 : rule->torsional > 0 ? 4 : 3;
    }
  }
  mjFREESTACK;
}

}  // namespace mrsim
