#include "studio/design/chain_edit.h"

#include <cmath>
#include <map>
#include <stdexcept>
#include <utility>

#include "sim_core/export/frame_mesh.h"
#include "sim_core/scenario/face_geometry.h"

namespace mrsim::studio {
namespace {

std::string Renamed(const std::string& guid, const std::string& from,
                    const std::string& to) {
  if (guid.compare(0, from.size(), from) == 0) {
    return to + guid.substr(from.size());
  }
  return guid;
}

// A new module of `axis` looks like the existing ones of its kind: the
// mesh frames of the first such module that has them.
void CarryMeshOfKind(const Robot& old, Axis axis, Module* to) {
  for (const Module& m : old.modules) {
    if (m.axis != axis || !(m.frames[0].is_mesh() || m.frames[1].is_mesh())) {
      continue;
    }
    for (int f = 0; f < 2; ++f) {
      to->frames[f].shape = m.frames[f].shape;
      to->frames[f].scale = m.frames[f].scale;
    }
    return;
  }
}

void CarryModule(const Module& from, Module* to) {
  for (int f = 0; f < 2; ++f) {
    const Frame& a = from.frames[f];
    Frame& b = to->frames[f];
    b.shape = a.shape;
    b.scale = a.scale;
    b.mass = a.mass;
    b.is_static = a.is_static;
    b.material_name = a.material_name;
  }
  const Joint& a = from.joint;
  Joint& b = to->joint;
  b.type = a.type;
  b.lower_range_limit = a.lower_range_limit;
  b.upper_range_limit = a.upper_range_limit;
  b.kp = a.kp;
  b.max_vel = a.max_vel;
  b.velocity_gain = a.velocity_gain;
  b.max_torque = a.max_torque;
  b.break_force = a.break_force;
}

void CarrySensorModule(const SensorModule& from, SensorModule* to) {
  to->size = from.size;
  to->mass = from.mass;
  to->material_name = from.material_name;
  // Each sensor module keeps its own choice of plate (and its face).
  if (!from.force_sensor) {
    to->force_sensor.reset();
    to->force_sensor_lock.reset();
  } else if (to->force_sensor) {
    to->force_sensor->mass = from.force_sensor->mass;
    to->force_sensor->material_name = from.force_sensor->material_name;
    to->force_sensor->force_value = from.force_sensor->force_value;
    to->force_sensor->sensor_position = from.force_sensor->sensor_position;
    to->force_sensor->size = from.force_sensor->size;
  }
  // Distance sensors keep their place on the module as it moves.
  const Eigen::Vector3d shift = to->position - from.position;
  to->distance_sensors = from.distance_sensors;
  to->distance_sensor_locks = from.distance_sensor_locks;
  to->distance_lock_position = from.distance_lock_position + shift;
  for (DistanceSensor& d : to->distance_sensors) {
    d.position += shift;
    d.guid = Renamed(d.guid, from.guid, to->guid);
  }
  for (Joint& lock : to->distance_sensor_locks) {
    lock.guid = Renamed(lock.guid, from.guid, to->guid);
    lock.left_frame_guid = Renamed(lock.left_frame_guid, from.guid, to->guid);
    lock.right_frame_guid = Renamed(lock.right_frame_guid, from.guid, to->guid);
  }
  PlaceMounted(to);
}

// Moves `to` onto `target` unless it is there already (so a chain laid out
// by MakeChain keeps its exact coordinates).
void Place(Eigen::Vector3d* to, const Eigen::Vector3d& target) {
  if ((*to - target).norm() > 1e-9) *to = target;
}

// The guids a slot's part goes by: a module's two frames, a sensor
// module's own.
std::vector<std::string> SlotGuids(const Robot& robot, const ChainSlot& slot) {
  if (slot.sensor) return {robot.sensor_modules.at(slot.source).guid};
  const Module& m = robot.modules.at(slot.source);
  return {m.frames[0].guid, m.frames[1].guid};
}

// Place in ChainOrder of the part named `guid`, or -1.
int SlotOfGuid(const Robot& robot, const std::vector<ChainSlot>& slots,
               const std::string& guid) {
  for (size_t i = 0; i < slots.size(); ++i) {
    for (const std::string& g : SlotGuids(robot, slots[i])) {
      if (g == guid) return static_cast<int>(i);
    }
  }
  return -1;
}

// The old robot's locks on the new one: break forces of the chain's locks
// that join the same parts, and loop locks whose parts remain.
void CarryLocks(const Robot& old, const std::vector<ChainSlot>& slots,
                Robot* robot) {
  std::map<std::string, std::string> renamed;
  int module = 0, sensor = 0;
  for (const ChainSlot& slot : slots) {
    const ChainSlot now{slot.sensor, slot.sensor ? sensor++ : module++,
                        slot.axis};
    if (slot.source < 0) continue;
    const std::vector<std::string> from = SlotGuids(old, slot);
    const std::vector<std::string> to = SlotGuids(*robot, now);
    for (size_t k = 0; k < from.size(); ++k) renamed[from[k]] = to[k];
  }
  auto same_ends = [](const Joint& a, const std::string& l,
                      const std::string& r) {
    return (a.left_frame_guid == l && a.right_frame_guid == r) ||
           (a.left_frame_guid == r && a.right_frame_guid == l);
  };
  std::vector<Joint> loops;
  for (const Joint& lock : old.locks) {
    auto l = renamed.find(lock.left_frame_guid);
    auto r = renamed.find(lock.right_frame_guid);
    if (l == renamed.end() || r == renamed.end()) continue;
    if (IsChainLock(old, lock)) {
      for (Joint& made : robot->locks) {
        if (same_ends(made, l->second, r->second)) {
          made.break_force = lock.break_force;
        }
      }
      continue;
    }
    Joint loop = lock;
    loop.left_frame_guid = l->second;
    loop.right_frame_guid = r->second;
    loops.push_back(loop);
  }
  for (Joint& loop : loops) {
    bool taken = false;
    for (const Joint& j : robot->locks) taken = taken || j.guid == loop.guid;
    for (int k = 0; taken; ++k) {
      loop.guid = robot->name + "/loop" + std::to_string(k);
      taken = false;
      for (const Joint& j : robot->locks) taken = taken || j.guid == loop.guid;
      for (const Joint& j : loops) {
        taken = taken || (&j != &loop && j.guid == loop.guid);
      }
    }
    robot->locks.push_back(loop);
  }
}

}  // namespace

bool IsChainLock(const Robot& robot, const Joint& lock) {
  const std::vector<ChainSlot> slots = ChainOrder(robot);
  // The back of one part to the front of the next: a module's back frame
  // (frames[1]) or front frame (frames[0]), a sensor module itself.
  auto joins = [&](const std::string& back, const std::string& front) {
    const int a = SlotOfGuid(robot, slots, back);
    const int b = SlotOfGuid(robot, slots, front);
    if (a < 0 || b != a + 1) return false;
    return SlotGuids(robot, slots[a]).back() == back &&
           SlotGuids(robot, slots[b]).front() == front;
  };
  return joins(lock.left_frame_guid, lock.right_frame_guid) ||
         joins(lock.right_frame_guid, lock.left_frame_guid);
}

std::vector<ChainSlot> ChainOrder(const Robot& robot) {
  std::vector<ChainSlot> slots;
  std::vector<bool> placed(robot.sensor_modules.size(), false);
  auto sensors_after = [&](int mod_nr) {
    for (size_t j = 0; j < robot.sensor_modules.size(); ++j) {
      if (!placed[j] && robot.sensor_modules[j].left_mod_nr == mod_nr) {
        placed[j] = true;
        slots.push_back({true, static_cast<int>(j), Axis::kPitch});
      }
    }
  };
  sensors_after(-1);
  for (size_t i = 0; i < robot.modules.size(); ++i) {
    slots.push_back({false, static_cast<int>(i), robot.modules[i].axis});
    sensors_after(robot.modules[i].mod_nr);
  }
  for (size_t j = 0; j < placed.size(); ++j) {
    if (!placed[j]) slots.push_back({true, static_cast<int>(j), Axis::kPitch});
  }
  return slots;
}

void PlaceMounted(SensorModule* sm) {
  const Eigen::Vector3d half = sm->size / 2;
  // A point `out` beyond the centre of face `face`, in the world.
  auto beyond = [&](int face, double out) -> Eigen::Vector3d {
    const Eigen::Vector3d n = SensorFaceNormal(face);
    return sm->position +
           sm->quat_rotation * (n * (std::abs(n.dot(half)) + out));
  };
  if (sm->force_sensor) {
    ForceSensor& plate = *sm->force_sensor;
    Place(&sm->force_lock_position, beyond(plate.sensor_position, 0));
    Place(&plate.position, beyond(plate.sensor_position, plate.size.z() / 2));
  }
  for (size_t k = 0; k < sm->distance_sensors.size(); ++k) {
    DistanceSensor& d = sm->distance_sensors[k];
    const Eigen::Vector3d n = SensorFaceNormal(d.sensor_position);
    if (k == 0)
      Place(&sm->distance_lock_position, beyond(d.sensor_position, 0));
    Place(&d.position, beyond(d.sensor_position, std::abs(n.dot(d.size)) / 2));
  }
}

ChainOptions OptionsOf(const Robot& robot) {
  ChainOptions options;
  if (!robot.name.empty()) options.name = robot.name;
  for (const SensorModule& sm : robot.sensor_modules) {
    if (sm.force_sensor) options.force_sensors = true;
  }
  if (robot.sensor_modules.empty()) options.force_sensors = true;
  if (robot.modules.empty()) return options;
  const Module& m = robot.modules[0];
  options.frame_size = m.frames[0].scale;
  options.module_mass = m.frames[0].mass + m.frames[1].mass;
  options.material = m.frames[0].material_name;
  options.kp = m.joint.kp;
  options.max_vel = m.joint.max_vel;
  options.joint_limit = m.joint.upper_range_limit;
  bool plates = false;
  for (const SensorModule& sm : robot.sensor_modules) {
    if (sm.force_sensor) plates = true;
  }
  const double lift = plates ? ForceSensor().size.z() : 0.0;
  options.origin =
      Eigen::Vector3d(m.position.x(), m.position.y(),
                      m.position.z() - options.frame_size.z() / 2 - lift);
  return options;
}

Robot Relayout(const Robot& old, const std::vector<ChainSlot>& slots,
               const ChainOptions& options, const std::string& base_dir) {
  ChainOptions chain = options;
  chain.modules = 0;
  chain.pattern = ChainPattern::kPitch;
  chain.sensor_after.clear();
  bool previous_sensor = false;
  int previous_source = -1;
  bool old_rays = false;
  for (const SensorModule& sm : old.sensor_modules) {
    if (!sm.distance_sensors.empty()) old_rays = true;
  }
  for (const ChainSlot& slot : slots) {
    if (slot.sensor) {
      if (previous_sensor) {
        // Named as the chain list names them (S0, S1, ...).
        throw std::invalid_argument(
            "sensor modules S" + std::to_string(previous_source) + " and S" +
            std::to_string(slot.source) +
            " would be next to each other: put a module between them, or "
            "remove one of them first");
      }
      previous_source = slot.source;
      chain.sensor_after.push_back(chain.modules - 1);
    } else {
      ++chain.modules;
    }
    previous_sensor = slot.sensor;
  }
  if (chain.modules == 0) {
    throw std::invalid_argument(
        "a robot needs at least one module: add a module first");
  }
  // MakeChain lifts the chain onto plates even when there are no sensor
  // modules to carry them.
  if (chain.sensor_after.empty()) chain.force_sensors = false;
  // A new sensor module at the very front looks ahead, as in the case study.
  chain.front_distance_sensor =
      !old_rays && slots[0].sensor && slots[0].source < 0;
  Robot robot = MakeChain(chain);
  int module = 0;
  int sensor = 0;
  for (const ChainSlot& slot : slots) {
    if (slot.sensor) {
      SensorModule& sm = robot.sensor_modules[sensor++];
      if (slot.source >= 0) {
        CarrySensorModule(old.sensor_modules.at(slot.source), &sm);
      }
    } else {
      Module& m = robot.modules[module++];
      m.axis = slot.axis;
      if (slot.source >= 0) {
        CarryModule(old.modules.at(slot.source), &m);
      } else {
        CarryMeshOfKind(old, slot.axis, &m);
      }
    }
  }
  CarryLocks(old, slots, &robot);
  Restack(&robot, base_dir);
  return robot;
}

void Restack(Robot* robot, const std::string& base_dir) {
  constexpr double kTouching = 1e-9;  // m
  if (robot->modules.empty()) return;
  // Each frame's extent along x in its own coordinates: lo (behind its
  // origin, negative) and hi. A box spans +-scale/2.
  std::map<std::string, std::pair<double, double>> measured;
  auto extent = [&](const Frame& f) {
    if (!f.is_mesh()) return std::make_pair(-f.scale.x() / 2, f.scale.x() / 2);
    const std::string key = f.shape + "|" + std::to_string(f.scale.x()) + "|" +
                            std::to_string(f.scale.y()) + "|" +
                            std::to_string(f.scale.z());
    auto it = measured.find(key);
    if (it == measured.end()) {
      const Eigen::AlignedBox3d box = FrameBounds(f, base_dir);
      it = measured.emplace(key, std::make_pair(box.min().x(), box.max().x()))
               .first;
    }
    return it->second;
  };
  try {
    for (const Module& m : robot->modules) {
      for (const Frame& f : m.frames) extent(f);
    }
  } catch (const std::exception&) {
    return;  // a mesh that cannot be read: the validator says why
  }
  auto length = [&](const Frame& f) {
    const auto [lo, hi] = extent(f);
    return hi - lo;
  };
  // Front faces from the front going towards -x, relative to the first.
  const std::vector<ChainSlot> slots = ChainOrder(*robot);
  std::vector<double> front(slots.size());
  double cursor = 0;
  double hinge0 = 0;
  for (size_t i = 0; i < slots.size(); ++i) {
    front[i] = cursor;
    if (slots[i].sensor) {
      cursor -= robot->sensor_modules[slots[i].source].size.x();
    } else {
      const Module& m = robot->modules[slots[i].source];
      if (slots[i].source == 0) hinge0 = cursor - length(m.frames[0]);
      cursor -= length(m.frames[0]) + length(m.frames[1]);
    }
  }
  const double shift = robot->modules[0].position.x() - hinge0;
  auto place = [&](double* x, double target) {
    if (std::abs(*x - target) > kTouching) *x = target;
  };
  for (size_t i = 0; i < slots.size(); ++i) {
    const double face = front[i] + shift;
    if (slots[i].sensor) {
      SensorModule& sm = robot->sensor_modules[slots[i].source];
      place(&sm.position.x(), face - sm.size.x() / 2);
      PlaceMounted(&sm);
    } else {
      Module& m = robot->modules[slots[i].source];
      const double hinge = face - length(m.frames[0]);
      place(&m.position.x(), hinge);
      // The front frame spans [hinge, hinge + length], the back one
      // [hinge - length, hinge].
      place(&m.frames[0].position.x(), hinge - extent(m.frames[0]).first);
      place(&m.frames[1].position.x(), hinge - extent(m.frames[1]).second);
    }
  }
}

}  // namespace mrsim::studio
