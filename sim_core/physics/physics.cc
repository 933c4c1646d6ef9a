#include "sim_core/physics/physics.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <optional>
#include <set>
#include <stdexcept>

#include "common/hash.h"
#include "sim_core/mjcf/mjcf_builder.h"
#include "sim_core/mjcf/model_compiler.h"
#include "sim_core/mujoco/mujoco_data.h"
#include "sim_core/mujoco/mujoco_handlers.h"
#include "sim_core/physics/distance_ray.h"
#include "sim_core/physics/forward_pipeline.h"
#include "sim_core/physics/physics_effect_kinds.h"
#include "sim_core/physics/physics_effects.h"
#include "sim_core/physics/physics_state_fields.h"
#include "sim_core/physics/robot_orientation.h"
#include "sim_core/physics/world_split.h"
#include "sim_core/scenario/scenario_validate.h"
#include "sim_core/scenario/sensor_kind.h"
#include "sim_core/scenario/terrain.h"

namespace mrsim {
namespace {

// Version 4 adds the last unconstrained acceleration (qacc_smooth, which
// directional friction reads); version 3 added the lock states; version 2
// the integrated qpos, actuator_force and sensordata. Older blobs still
// load (all locks attached for v1/v2; resuming a version-1 blob, or a
// version-3 blob of a scenario with directional friction, may differ in
// the last bits).
constexpr char kStateMagic[8] = {'M', 'R', 'S', 'I', 'M', 'S', 'T', '4'};
// The version kStateMagic names, the one SaveState writes.
constexpr int kStateVersion = 4;
constexpr char kStateMagicV3[8] = {'M', 'R', 'S', 'I', 'M', 'S', 'T', '3'};
constexpr char kStateMagicV2[8] = {'M', 'R', 'S', 'I', 'M', 'S', 'T', '2'};
constexpr char kStateMagicV1[8] = {'M', 'R', 'S', 'I', 'M', 'S', 'T', '1'};
// Lock flags in a version-3 blob.
// The largest number a saved state may hold (positions, speeds, forces,
// warm-start accelerations): far beyond a stable run, far below overflow.
constexpr double kMaxStateValue = 1e12;
// Thirty years of sim time; beyond it a short timestep no longer changes
// the time's double and the run would never end.
constexpr double kMaxStateTime = 1e9;
constexpr unsigned char kLockAttached = 1;
constexpr unsigned char kLockRuntimeWeld = 2;

const char* WarningName(int w) {
  switch (w) {
    case mjWARN_INERTIA:
      return "INERTIA (near singular inertia matrix)";
    case mjWARN_CONTACTFULL:
      return "CONTACTFULL (too many contacts)";
    case mjWARN_CNSTRFULL:
      return "CNSTRFULL (too many constraints)";
    case mjWARN_VGEOMFULL:
      return "VGEOMFULL";
    case mjWARN_BADQPOS:
      return "BADQPOS (NaN, Inf or huge value in qpos)";
    case mjWARN_BADQVEL:
      return "BADQVEL (NaN, Inf or huge value in qvel)";
    case mjWARN_BADQACC:
      return "BADQACC (NaN, Inf or huge value in qacc)";
    case mjWARN_BADCTRL:
      return "BADCTRL (NaN, Inf or huge value in ctrl)";
    default:
      return "unknown";
  }
}

Pose BodyPose(const mjData* d, int body) {
  Pose p;
  p.position = Eigen::Vector3d(d->xpos[3 * body], d->xpos[3 * body + 1],
                               d->xpos[3 * body + 2]);
  const mjtNum* q = d->xquat + 4 * body;
  p.orientation = Eigen::Quaterniond(q[0], q[1], q[2], q[3]);
  return p;
}

template <typename T>
void Put(std::vector<unsigned char>& out, const T* values, size_t n) {
  const auto* bytes = reinterpret_cast<const unsigned char*>(values);
  out.insert(out.end(), bytes, bytes + n * sizeof(T));
}

// The checkpoint version of a blob, from its magic; 0 when it is none.
int StateVersion(const std::vector<unsigned char>& bytes) {
  if (bytes.size() < sizeof(kStateMagic)) return 0;
  for (const auto& [magic, version] :
       {std::pair<const char*, int>{kStateMagic, kStateVersion},
        {kStateMagicV3, 3},
        {kStateMagicV2, 2},
        {kStateMagicV1, 1}}) {
    if (std::memcmp(bytes.data(), magic, sizeof(kStateMagic)) == 0)
      return version;
  }
  return 0;
}

// Where the entries of each kind of state array go when the state moves
// from one model to another (matched by name): runs of {index in the
// destination, index in the source, length}, per StatePer.
class StateMap {
 public:
  using Run = std::array<int, 3>;
  std::vector<Run>& of(StatePer per) { return runs_[static_cast<size_t>(per)]; }
  void Copy(StatePer per, const mjtNum* from, mjtNum* to) const {
    for (const Run& r : runs_[static_cast<size_t>(per)]) {
      mju_copy(to + r[0], from + r[1], r[2]);
    }
  }

 private:
  std::array<std::vector<Run>, static_cast<size_t>(StatePer::kTarget) + 1>
      runs_;
};

bool InCheckpoint(const PhysicsStateField& f, int version) {
  return (f.copies & kStateCheckpoint) && f.since <= version;
}

}  // namespace

struct Physics::Impl {
  using Servo = HingeServo;
  struct SensorModuleIndex {
    int body = -1;
    int plate = -1;  // the first kPlate instance's body: rays skip it
    // Every sensor instance, in SensorKinds() order (sensor_kind.h).
    struct KindInstance {
      const SensorKind* kind = nullptr;
      int k = 0;
      int face = -1;
      std::vector<int> adr;  // sensordata address per SensorKind::mujoco
      int site = -1;         // kRay: the ray's site
      double max_range = 0;  // kRay
    };
    std::vector<KindInstance> kinds;
    std::vector<double> max_distance;  // kRay instances' ranges, in order
  };
  struct LockIndex {
    std::string name;
    int eq = -1;  // weld equality; -1: a rigid tree link (always attached)
  };
  // Servos and targets in the ServoRobot part, which the control effects
  // see (servo_robots).
  struct RobotIndex : ServoRobot {
    std::string name;
    std::vector<LockIndex> locks;
    std::vector<int> frame_bodies;  // two per module
    std::vector<SensorModuleIndex> sensor_modules;
    std::vector<int> bodies;  // every body of the robot, for the CoM
    // The loose parts' hinges in scenario order, as their state lists
    // them: each with the index of its servo in `servos`, or -1 when it
    // turns freely (Joint::servo off). A robot lists its servos instead.
    struct LooseHinge {
      int joint = -1;
      int servo = -1;
    };
    std::vector<LooseHinge> loose_hinges;
  };

  Scenario scenario;
  // Set when the scene runs as several worlds (world_split.h); model and
  // data are then a view of the whole scene that the worlds fill in.
  std::unique_ptr<WorldSplit> split;
  // Set once mutable_data() handed out the view: what is written there
  // goes back into the worlds before a step, and the view follows every
  // step.
  bool view_poked = false;
  // In a world of a split scene: the robots' indices in the whole
  // scenario (noise and sensor keys), and the rays of the other worlds.
  std::vector<int> global_ids;
  std::vector<bool> skip_objects;  // the other worlds' scene objects
  RayCast other_rays;
  uint64_t GlobalId(size_t r) const {
    return global_ids.empty() ? r : static_cast<uint64_t>(global_ids[r]);
  }
  // Locks ("<robot>/<lock>") released at run time that the scenario's
  // model held as rigid tree links; the model is rebuilt with them as
  // welds (MjcfOptions::weld_locks).
  std::set<std::string> runtime_welds;
  MjModelPtr model;
  MjDataPtr data;
  // For force readings (needs a full forward); made on first use, since
  // an mjData of a long chain is large (njmax^2).
  mutable MjDataPtr scratch;
  std::vector<RobotIndex> robots;
  // Every robot's locks in scenario order, then the loose parts': the
  // checkpoint's order.
  template <class F>
  void ForEachLock(F f) const {
    for (const RobotIndex& r : robots) {
      for (const LockIndex& l : r.locks) f(r, l);
    }
    if (loose) {
      for (const LockIndex& l : loose->locks) f(*loose, l);
    }
  }
  // The parts outside any robot (Scenario::loose_*), read as one more
  // state under kLooseOwnerName. Its servos (the loose hinges with
  // Joint::servo) run the nominal law: the effects never see them.
  std::optional<RobotIndex> loose;
  std::vector<const ServoRobot*> servo_robots;  // robots, as effects see them
  // The reality gap's per-step part (SetRealityGap); off by default. Kept
  // across rebuilds and Reset(); an input of the effects.
  RealityGap gap;
  // What this Physics adds to MuJoCo's model (physics_effect_kinds.h),
  // made from the scenario, the model and the gap by MakeEffects.
  PhysicsEffects effects;
  void MakeEffects() {
    effects = PhysicsEffects(PhysicsEffectInput{scenario, model.get(), gap});
    effects.Restart(servo_robots);
  }
  std::array<int, mjNWARNING> warnings{};
  std::vector<mjtByte> eq_active0;  // the model's initial eq_active
  std::vector<double> eq_break;     // per equality: break force, 0 never
  bool any_breakable = false;
  // qpos as mj_step2 left it, before mj_step1's kinematics renormalised the
  // free and ball joint quaternions in place. Renormalising is not
  // idempotent in the last bit, so a loaded state must run mj_step1 from
  // this, not from the current qpos, to get the very same qpos and poses.
  std::vector<mjtNum> qpos_integrated;

  int Id(mjtObj type, const std::string& name) const {
    const int id = mj_name2id(model.get(), type, name.c_str());
    if (id < 0) {
      throw std::logic_error("MJCF has no " + std::string(mju_type2Str(type)) +
                             " named '" + name + "'");
    }
    return id;
  }
  void Build();
  // The one-world model of a split scene, for model()/data() and the
  // robots' index; never stepped, so its constraint buffers stay small.
  void BuildView();
  // Pokes into the view go to the worlds (see view_poked).
  void PushView() {
    if (split && view_poked) split->PushView(data.get());
  }
  void Index(const MjcfInfo& info);
  void IndexSensorModules(const std::vector<SensorModule>& sensor_modules,
                          RobotIndex* ri) const;
  void IndexLooseParts(const MjcfInfo& info);
  // The state of robot (or loose parts) `r`, whose sensor modules are
  // `sensor_modules`; `id` keys the sensors' noise; `robot` is the robot's
  // index for the reading effects, -1 for the loose parts (none apply).
  RobotState Read(const RobotIndex& r,
                  const std::vector<SensorModule>& sensor_modules, uint64_t id,
                  int robot);
  void TransferState(const mjModel* om, const mjData* od);
  void BreakOverloadedLocks();
  // Recomputes the current state's kinematics and constraints after the
  // model changed (eq_active), from the integrated qpos as a step does.
  void Refresh() {
    mju_copy(data->qpos, qpos_integrated.data(), model->nq);
    Step1();
    for (int w = 0; w < mjNWARNING; ++w) warnings[w] = data->warning[w].number;
  }
  LockIndex& FindLock(const std::string& robot, const std::string& lock);
  uint64_t StepIndex(const mjData* d) const {
    return static_cast<uint64_t>(std::llround(d->time / model->opt.timestep));
  }
  // The servos' commands for the next step of d: the nominal law, or the
  // control effect's (the reality gap). advance: a real step; false for
  // the force readings' private forward, which replays the last commands.
  void ComputeControls(mjData* d, bool advance = true) {
    // The reality gap is a robot's servos' imperfection; the loose servos
    // stay nominal (the law depends on the state alone, so a replay for
    // the force readings gives the same commands).
    if (loose) NominalControls(*loose, d);
    if (PhysicsEffect* effect = effects.controls()) {
      effect->Controls(model.get(), servo_robots, d, advance);
      return;
    }
    for (const RobotIndex& r : robots) NominalControls(r, d);
  }
  static void NominalControls(const RobotIndex& r, mjData* d) {
    const size_t n = r.servos.size();
    for (size_t j = 0; j < n; ++j) {
      const Servo& s = r.servos[j];
      const double u = s.kp * (r.targets[j] - d->qpos[s.qpos]);
      d->ctrl[s.actuator] = std::clamp(u, -s.max_vel, s.max_vel);
    }
  }
  // Every robot's targets, then the loose servos': the checkpoint's order.
  template <typename F>
  void ForEachTargets(F&& f) {
    for (RobotIndex& r : robots) f(r.targets);
    if (loose) f(loose->targets);
  }
  static void ResetTargets(RobotIndex* r) {
    for (size_t j = 0; j < r->servos.size(); ++j) {
      r->targets[j] = std::clamp(0.0, r->servos[j].lower, r->servos[j].upper);
    }
  }
  // The body forces the next step of state `from` applies, into `to`
  // (may be `from`): the body-force effects' (fluids) when any is built
  // (they replace the whole array), else from's own. Step and the force
  // readings' forward both come here, so they cannot differ.
  void ApplyBodyForces(const mjData* from, mjData* to) const {
    const std::vector<const PhysicsEffect*>& forces = effects.body_forces();
    if (!forces.empty()) {
      std::memset(to->xfrc_applied, 0, sizeof(mjtNum) * 6 * model->nbody);
      for (const PhysicsEffect* effect : forces) {
        effect->AddBodyForces(model.get(), from, to->xfrc_applied);
      }
    } else if (to != from) {
      mju_copy(to->xfrc_applied, from->xfrc_applied, 6 * model->nbody);
    }
  }
  void AfterStateChange() {
    mju_copy(qpos_integrated.data(), data->qpos, model->nq);
    Step1();
    for (int w = 0; w < mjNWARNING; ++w) warnings[w] = data->warning[w].number;
  }
  // mj_step1 (kinematics, contacts, constraints of the current state).
  // MuJoCo 2.2 drops the contacts (CONTACTFULL) and constraint rows
  // (CNSTRFULL) that do not fit mjData's buffers, which are sized for the
  // model at rest; when it did, MakeRoom gives the step bigger buffers and
  // redoes it, so no constraint is ever dropped.
  void Step1() {
    const int contacts = data->warning[mjWARN_CONTACTFULL].number;
    const int rows = data->warning[mjWARN_CNSTRFULL].number;
    // MuJoCo's own mj_step1, or its stages with the contact effects in
    // between (directional friction).
    ::mrsim::Step1(model.get(), data.get(), effects.contacts());
    if (data->warning[mjWARN_CONTACTFULL].number != contacts ||
        data->warning[mjWARN_CNSTRFULL].number != rows) {
      MakeRoom();
    }
  }
  void MakeRoom();
  void CheckStability(double time_before);
  [[noreturn]] void Fail(double time, const std::string& what);
  const RobotIndex& robot(int r) const {
    if (r < 0 || r >= static_cast<int>(robots.size())) {
      throw std::out_of_range("robot index " + std::to_string(r) +
                              " out of range (" +
                              std::to_string(robots.size()) + " robots)");
    }
    return robots[r];
  }
  const Servo& servo(int r, int j) const {
    const RobotIndex& ri = robot(r);
    if (j < 0 || j >= static_cast<int>(ri.servos.size())) {
      throw std::out_of_range("joint index " + std::to_string(j) +
                              " out of range for robot '" + ri.name + "'");
    }
    return ri.servos[j];
  }
};

void Physics::Impl::Build() {
  std::vector<std::vector<double>> old_targets;
  for (const RobotIndex& r : robots) old_targets.push_back(r.targets);
  const std::vector<double> old_loose_targets =
      loose ? loose->targets : std::vector<double>();
  MjcfOptions options;
  options.rangefinders = false;
  options.weld_locks = runtime_welds;
  options.skip_scene_objects = skip_objects;
  options.textures = global_ids.empty();  // a world of a split scene: undrawn
  MjcfInfo info;
  model = CompileScenarioModel(scenario, options, &info);
  mjModel* m = model.get();
  robots.clear();
  Index(info);
  if (old_targets.size() == robots.size()) {
    for (size_t r = 0; r < robots.size(); ++r)
      robots[r].targets = old_targets[r];
  }
  if (loose && old_loose_targets.size() == loose->targets.size()) {
    loose->targets = old_loose_targets;
  }
  eq_active0.assign(m->eq_active, m->eq_active + m->neq);
  data = MakeMjData(m);
  if (!data) {
    throw std::runtime_error(fmt::format(
        "MuJoCo cannot allocate the simulation data ({} constraint rows)",
        m->njmax));
  }
  scratch.reset();
  qpos_integrated.assign(m->nq, 0);
  MakeEffects();
  AfterStateChange();
}

void Physics::Impl::BuildView() {
  MjcfOptions options;
  options.rangefinders = false;
  MjcfInfo info;
  model = CompileScenarioModel(scenario, options, &info);
  mjModel* m = model.get();
  Index(info);
  eq_active0.assign(m->eq_active, m->eq_active + m->neq);
  // Kinematics only: no contacts or constraint rows are ever computed here.
  m->nconmax = 1;
  m->njmax = 1;
  m->nstack = std::min(m->nstack, 100000 + 100 * m->nv);
  data = MakeMjData(m);
  if (!data) throw std::runtime_error("MuJoCo cannot allocate data");
}

void Physics::Impl::TransferState(const mjModel* om, const mjData* od) {
  // Same bodies, joints and actuators by name; a body that gained a free
  // joint (its lock became a weld) starts from its current pose and
  // velocity. Deterministic, so a resumed run does the same.
  const mjModel* m = model.get();
  mjData* d = data.get();
  d->time = od->time;
  StateMap map;
  for (int j = 0; j < m->njnt; ++j) {
    const char* jname = mj_id2name(m, mjOBJ_JOINT, j);
    const int ob =
        mj_name2id(om, mjOBJ_BODY, mj_id2name(m, mjOBJ_BODY, m->jnt_bodyid[j]));
    const int oj = jname ? mj_name2id(om, mjOBJ_JOINT, jname) : -1;
    const int qa = m->jnt_qposadr[j], va = m->jnt_dofadr[j];
    const int type = m->jnt_type[j];
    const int nq = type == mjJNT_FREE ? 7 : type == mjJNT_BALL ? 4 : 1;
    const int nv = type == mjJNT_FREE ? 6 : type == mjJNT_BALL ? 3 : 1;
    if (oj >= 0 && om->jnt_type[oj] == type && om->jnt_bodyid[oj] == ob) {
      map.of(StatePer::kJointPosition).push_back({qa, om->jnt_qposadr[oj], nq});
      map.of(StatePer::kDof).push_back({va, om->jnt_dofadr[oj], nv});
    } else if (type == mjJNT_FREE && ob >= 0) {
      mju_copy3(d->qpos + qa, od->xpos + 3 * ob);
      mju_copy4(d->qpos + qa + 3, od->xquat + 4 * ob);
      mjtNum vel[6];  // rotation then translation, world axes
      mj_objectVelocity(om, od, mjOBJ_XBODY, ob, vel, 0);
      mju_copy3(d->qvel + va, vel + 3);
      mju_rotVecMatT(d->qvel + va + 3, vel, od->xmat + 9 * ob);
    }
  }
  for (int a = 0; a < m->nu; ++a) {
    const int oa =
        mj_name2id(om, mjOBJ_ACTUATOR, mj_id2name(m, mjOBJ_ACTUATOR, a));
    if (oa >= 0) map.of(StatePer::kActuator).push_back({a, oa, 1});
  }
  for (int b = 0; b < m->nbody; ++b) {
    const char* name = mj_id2name(m, mjOBJ_BODY, b);
    const int ob = name ? mj_name2id(om, mjOBJ_BODY, name) : (b == 0 ? 0 : -1);
    if (ob >= 0) map.of(StatePer::kBody).push_back({6 * b, 6 * ob, 6});
  }
  // The old model's integrated qpos is not carried: the new model's
  // kinematics start from the current pose (AfterStateChange).
  for (const PhysicsStateField& f : kPhysicsStateFields) {
    if (f.copies & kStateTransfer) map.Copy(f.per, od->*f.array, d->*f.array);
  }
  for (int e = 0; e < m->neq; ++e) {
    const char* name = mj_id2name(m, mjOBJ_EQUALITY, e);
    const int oe = name ? mj_name2id(om, mjOBJ_EQUALITY, name) : -1;
    if (oe >= 0) model->eq_active[e] = om->eq_active[oe];
  }
  AfterStateChange();
}

void Physics::Impl::BreakOverloadedLocks() {
  // After the step's constraint solve: a weld's first three rows carry the
  // force between its bodies (N, world axes).
  const mjData* d = data.get();
  for (int i = 0; i < d->nefc; ++i) {
    if (d->efc_type[i] != mjCNSTR_EQUALITY) continue;
    const int eq = d->efc_id[i];
    if (i > 0 && d->efc_type[i - 1] == mjCNSTR_EQUALITY &&
        d->efc_id[i - 1] == eq) {
      continue;  // not the first row of this equality
    }
    if (eq_break[eq] > 0 && model->eq_active[eq] &&
        mju_norm3(d->efc_force + i) > eq_break[eq]) {
      model->eq_active[eq] = 0;
    }
  }
}

Physics::Impl::LockIndex& Physics::Impl::FindLock(const std::string& robot,
                                                  const std::string& lock) {
  for (RobotIndex& r : robots) {
    if (r.name != robot) continue;
    for (LockIndex& l : r.locks) {
      if (l.name == lock) return l;
    }
    std::string names;
    for (const LockIndex& l : r.locks)
      names += (names.empty() ? "" : ", ") + l.name;
    throw PhysicsError(
        fmt::format("robot '{}' has no lock named '{}' (its locks: {})", robot,
                    lock, names.empty() ? "none" : names));
  }
  throw PhysicsError(
      fmt::format("no robot named '{}' (lock '{}')", robot, lock));
}

void Physics::Impl::Index(const MjcfInfo& info) {
  const mjModel* m = model.get();
  eq_break.assign(m->neq, 0.0);
  any_breakable = false;
  for (size_t r = 0; r < scenario.robots.size(); ++r) {
    const Robot& robot = scenario.robots[r];
    RobotIndex ri;
    ri.id = GlobalId(r);
    ri.name = mjcf_names::RobotName(scenario, r);
    for (const MjcfLock& l : info.robot_locks.at(r)) {
      LockIndex li;
      li.name = l.name;
      if (!l.weld.empty()) {
        li.eq = Id(mjOBJ_EQUALITY, l.weld);
        eq_break[li.eq] = l.break_force;
        any_breakable |= l.break_force > 0;
      }
      ri.locks.push_back(li);
    }
    for (size_t i = 0; i < robot.modules.size(); ++i) {
      for (int f = 0; f < 2; ++f) {
        const int b = Id(mjOBJ_BODY, mjcf_names::FrameBody(ri.name, i, f));
        ri.frame_bodies.push_back(b);
        ri.bodies.push_back(b);
      }
      const Module& mod = robot.modules[i];
      if (mod.joint.type != JointType::kHinge) continue;
      Servo s;
      s.joint = Id(mjOBJ_JOINT, mjcf_names::Hinge(ri.name, i));
      s.qpos = m->jnt_qposadr[s.joint];
      s.dof = m->jnt_dofadr[s.joint];
      s.actuator = Id(mjOBJ_ACTUATOR, mjcf_names::Servo(ri.name, i));
      s.module = static_cast<int>(i);
      s.axis = mod.axis;
      s.kp = mod.joint.kp;
      s.max_vel = std::abs(mod.joint.max_vel);
      s.lower = mod.joint.lower_range_limit;
      s.upper = mod.joint.upper_range_limit;
      ri.servos.push_back(s);
      ri.targets.push_back(std::clamp(0.0, s.lower, s.upper));
    }
    IndexSensorModules(robot.sensor_modules, &ri);
    robots.push_back(std::move(ri));
  }
  servo_robots.clear();
  for (const RobotIndex& r : robots) servo_robots.push_back(&r);
  IndexLooseParts(info);
}

void Physics::Impl::IndexSensorModules(
    const std::vector<SensorModule>& sensor_modules, RobotIndex* ri) const {
  const mjModel* m = model.get();
  for (size_t k = 0; k < sensor_modules.size(); ++k) {
    const SensorModule& sm = sensor_modules[k];
    SensorModuleIndex si;
    si.body = Id(mjOBJ_BODY, mjcf_names::SensorModuleBody(ri->name, k));
    ri->bodies.push_back(si.body);
    for (const SensorKind& kind : SensorKinds()) {
      if (kind.read == nullptr) continue;  // a camera: nothing to read
      for (int i = 0; i < kind.count(sm); ++i) {
        SensorModuleIndex::KindInstance inst{&kind, i, kind.face(sm, i), {}};
        for (const SensorMujoco& ms : kind.mujoco) {
          const int sensor =
              Id(mjOBJ_SENSOR, mjcf_names::SensorKindSensor(
                                   ri->name, k, kind.name, i, ms.suffix));
          inst.adr.push_back(m->sensor_adr[sensor]);
        }
        if (kind.mount == SensorMount::kPlate) {
          const int plate = Id(mjOBJ_BODY, mjcf_names::SensorKindBody(
                                               ri->name, k, kind.name, i));
          ri->bodies.push_back(plate);
          if (si.plate < 0) si.plate = plate;
        } else if (kind.mount == SensorMount::kRay) {
          inst.site = Id(mjOBJ_SITE,
                         mjcf_names::SensorKindSite(ri->name, k, kind.name, i));
          inst.max_range = kind.ray(sm, i).max_range;
          si.max_distance.push_back(inst.max_range);
        }
        si.kinds.push_back(std::move(inst));
      }
    }
    ri->sensor_modules.push_back(si);
  }
}

void Physics::Impl::IndexLooseParts(const MjcfInfo& info) {
  loose.reset();
  if (scenario.loose_frames.empty() && scenario.loose_sensor_modules.empty()) {
    return;
  }
  RobotIndex ri;
  ri.name = mjcf_names::LooseRobot();
  ri.id = scenario.robots.size();  // after every robot: its own noise keys
  for (size_t i = 0; i < scenario.loose_frames.size(); ++i) {
    // The builder names a loose frame's body "<loose>/f<i>".
    const int b = Id(mjOBJ_BODY, ri.name + "/f" + std::to_string(i));
    ri.frame_bodies.push_back(b);
    ri.bodies.push_back(b);
  }
  const mjModel* m = model.get();
  for (size_t k = 0; k < scenario.loose_joints.size(); ++k) {
    const Joint& joint = scenario.loose_joints[k];
    if (joint.type != JointType::kHinge) continue;
    // Every hinge is a tree edge (ConnectTree), so it has a MuJoCo joint.
    RobotIndex::LooseHinge h;
    h.joint = Id(mjOBJ_JOINT, mjcf_names::LooseHinge(static_cast<int>(k)));
    if (joint.servo) {
      Servo s;
      s.joint = h.joint;
      s.qpos = m->jnt_qposadr[s.joint];
      s.dof = m->jnt_dofadr[s.joint];
      s.actuator =
          Id(mjOBJ_ACTUATOR, mjcf_names::LooseServo(static_cast<int>(k)));
      s.module = static_cast<int>(k);  // its place in Scenario::loose_joints
      s.kp = joint.kp;
      s.max_vel = std::abs(joint.max_vel);
      s.lower = joint.lower_range_limit;
      s.upper = joint.upper_range_limit;
      h.servo = static_cast<int>(ri.servos.size());
      ri.servos.push_back(s);
      ri.targets.push_back(std::clamp(0.0, s.lower, s.upper));
    }
    ri.loose_hinges.push_back(h);
  }
  // A loose lock with a break force is a weld that breaks as a robot's.
  for (const MjcfLock& l : info.loose_locks) {
    LockIndex li;
    li.name = l.name;
    if (!l.weld.empty()) {
      li.eq = Id(mjOBJ_EQUALITY, l.weld);
      eq_break[li.eq] = l.break_force;
      any_breakable |= l.break_force > 0;
    }
    ri.locks.push_back(li);
  }
  IndexSensorModules(scenario.loose_sensor_modules, &ri);
  loose = std::move(ri);
}

void Physics::Impl::MakeRoom() {
  mjModel* m = model.get();
  for (;;) {
    const bool contacts_full = data->warning[mjWARN_CONTACTFULL].number > 0;
    const bool rows_full = data->warning[mjWARN_CNSTRFULL].number > 0;
    if (!contacts_full && !rows_full) return;
    const int max_rows = MjcfMaxRows(m->nv);
    if (m->njmax >= max_rows) {
      for (int w = 0; w < mjNWARNING; ++w)
        warnings[w] = data->warning[w].number;
      throw PhysicsError(fmt::format(
          "physics at t={:.4f} s: the constraints need more than {} rows "
          "({} contacts found), the most one MuJoCo 2.2 world holds; fewer "
          "parts touching at once fit",
          data->time, m->njmax, data->ncon));
    }
    // Half as much again (memory grows with njmax^2); the stack (untouched
    // until used) in proportion, as the compiler sizes it.
    const int nconmax =
        contacts_full ? m->nconmax + m->nconmax / 2 : m->nconmax;
    long njmax = m->njmax + m->njmax / 2;
    if (contacts_full) {
      njmax =
          std::max(njmax, m->njmax + static_cast<long>(kMjcfRowsPerContact) *
                                         (nconmax - m->nconmax));
    }
    njmax = std::min<long>(njmax, max_rows);
    const double scale = static_cast<double>(njmax) / m->njmax;
    m->nstack =
        static_cast<int>(std::min(2e9, std::ceil(m->nstack * scale * scale)));
    m->nconmax = nconmax;
    m->njmax = static_cast<int>(njmax);
    MjDataPtr grown = MakeMjData(m);
    if (!grown) {
      Fail(data->time, fmt::format("cannot allocate buffers for {} contacts "
                                   "and {} constraint rows",
                                   m->nconmax, m->njmax));
    }
    mjData* to = grown.get();
    const mjData* from = data.get();
    to->time = from->time;
    for (const PhysicsStateField& f : kPhysicsStateFields) {
      const int n = StateSize(m, f.per);
      if (!(f.copies & kStateGrow) || n == 0) continue;
      // The integrated qpos: the kinematics pass below runs from it.
      mju_copy(f.array ? to->*f.array : to->qpos,
               f.array ? from->*f.array : qpos_integrated.data(), n);
    }
    data = std::move(grown);
    scratch.reset();
    warnings.fill(0);  // the counters of the new mjData
    ::mrsim::Step1(m, data.get(), effects.contacts());
  }
}

void Physics::Impl::Fail(double time, const std::string& what) {
  // Accept the current counters so a caller that resets can go on.
  for (int w = 0; w < mjNWARNING; ++w) warnings[w] = data->warning[w].number;
  throw PhysicsError(
      fmt::format("physics unstable at t={:.4f} s: {}", time, what));
}

void Physics::Impl::CheckStability(double time_before) {
  const mjModel* m = model.get();
  const mjData* d = data.get();
  for (int w = 0; w < mjNWARNING; ++w) {
    // Full contact / constraint buffers are made room for (Step1).
    if (w == mjWARN_VGEOMFULL || w == mjWARN_CONTACTFULL ||
        w == mjWARN_CNSTRFULL || d->warning[w].number == warnings[w]) {
      continue;
    }
    std::string where;
    const int info = d->warning[w].lastinfo;
    if ((w == mjWARN_BADQVEL || w == mjWARN_BADQACC) && info >= 0 &&
        info < m->nv) {
      const char* body = mj_id2name(m, mjOBJ_BODY, m->dof_bodyid[info]);
      where = fmt::format(" at DOF {} of body '{}'", info, body ? body : "?");
    } else if (w == mjWARN_BADQPOS && info >= 0 && info < m->nq) {
      int joint = 0;
      while (joint + 1 < m->njnt && m->jnt_qposadr[joint + 1] <= info) ++joint;
      const char* body = m->njnt > 0
                             ? mj_id2name(m, mjOBJ_BODY, m->jnt_bodyid[joint])
                             : nullptr;
      where = fmt::format(" at qpos[{}] of body '{}'", info, body ? body : "?");
    } else if (w == mjWARN_BADCTRL && info >= 0 && info < m->nu) {
      const char* act = mj_id2name(m, mjOBJ_ACTUATOR, info);
      where = fmt::format(" for actuator '{}'", act ? act : "?");
    }
    Fail(time_before, fmt::format("MuJoCo warning {}{} (the state was reset "
                                  "by MuJoCo; reduce the timestep or check "
                                  "masses, gains and contacts)",
                                  WarningName(w), where));
  }
  auto bad = [](const mjtNum* v, int n) {
    for (int i = 0; i < n; ++i) {
      if (!std::isfinite(v[i])) return i;
    }
    return -1;
  };
  int i = bad(d->qpos, m->nq);
  if (i >= 0) Fail(time_before, fmt::format("qpos[{}] is not finite", i));
  i = bad(d->qvel, m->nv);
  if (i < 0) i = bad(d->qacc, m->nv);
  if (i >= 0) {
    const char* body = mj_id2name(m, mjOBJ_BODY, m->dof_bodyid[i]);
    Fail(time_before, fmt::format("velocity or acceleration of DOF {} (body "
                                  "'{}') is not finite",
                                  i, body ? body : "?"));
  }
  // A run that cannot reach its end must say so rather than step forever.
  if (!(d->time > time_before)) {
    Fail(time_before,
         fmt::format("the sim time did not advance with a timestep of {} s",
                     m->opt.timestep));
  }
}

Physics::Physics(const Scenario& scenario) : impl_(std::make_unique<Impl>()) {
  ValidateScenario(scenario);
  impl_->scenario = scenario;
  impl_->split = WorldSplit::Make(scenario);
  if (impl_->split) {
    impl_->BuildView();
  } else {
    impl_->Build();
  }
}

Physics::Physics(const Scenario& part, std::vector<int> global_ids,
                 std::vector<bool> skip_objects)
    : impl_(std::make_unique<Impl>()) {
  impl_->scenario = part;
  impl_->global_ids = std::move(global_ids);
  impl_->skip_objects = std::move(skip_objects);
  impl_->Build();
}

Physics::~Physics() = default;

// The hot path: servo law, body forces, one MuJoCo step split as
// step2 (dynamics + integration of the current state) then step1 (the new
// state's kinematics), so poses read between steps are current.
void Physics::Step() {
  if (impl_->split) {
    impl_->PushView();
    impl_->split->Step();
    if (impl_->view_poked) impl_->split->SyncView(model(), impl_->data.get());
    return;
  }
  mjModel* m = impl_->model.get();
  mjData* d = impl_->data.get();
  const double time_before = d->time;
  impl_->ComputeControls(d);
  impl_->ApplyBodyForces(d, d);
  mj_step2(m, d);
  if (impl_->any_breakable) impl_->BreakOverloadedLocks();
  mju_copy(impl_->qpos_integrated.data(), d->qpos, m->nq);
  impl_->Step1();
  impl_->CheckStability(time_before);
}

void Physics::Step(int n) {
  for (int i = 0; i < n; ++i) Step();
}

void Physics::SetRealityGap(const RealityGap& gap) {
  gap.Validate();
  if (impl_->split) {
    impl_->split->SetRealityGap(gap);
    return;
  }
  impl_->gap = gap;
  impl_->MakeEffects();
}

std::vector<std::string> Physics::effects() const {
  if (!impl_->split) return impl_->effects.names();
  // Every world runs the effects its part of the scene needs.
  std::vector<std::string> out;
  for (const PhysicsEffectKind& kind : PhysicsEffectKinds()) {
    for (int r = 0; r < robot_count(); ++r) {
      int local = 0;
      const std::vector<std::string> names =
          impl_->split->world_of(r, &local).effects();
      if (std::find(names.begin(), names.end(), kind.name) != names.end()) {
        out.push_back(kind.name);
        break;
      }
    }
  }
  return out;
}

void Physics::Reset() {
  if (impl_->split) {
    impl_->split->Reset();
    for (Impl::RobotIndex& r : impl_->robots) Impl::ResetTargets(&r);
    if (impl_->view_poked) impl_->split->SyncView(model(), impl_->data.get());
    return;
  }
  std::copy(impl_->eq_active0.begin(), impl_->eq_active0.end(),
            impl_->model->eq_active);
  ResetMjData(impl_->model.get(), impl_->data.get());
  for (Impl::RobotIndex& r : impl_->robots) Impl::ResetTargets(&r);
  if (impl_->loose) Impl::ResetTargets(&*impl_->loose);
  impl_->effects.Restart(impl_->servo_robots);
  impl_->AfterStateChange();
}

double Physics::time() const {
  return impl_->split ? impl_->split->time() : impl_->data->time;
}
double Physics::timestep() const { return impl_->model->opt.timestep; }

int Physics::robot_count() const {
  return static_cast<int>(impl_->robots.size());
}
const std::string& Physics::robot_name(int robot) const {
  return impl_->robot(robot).name;
}
int Physics::robot_index(const std::string& name) const {
  for (size_t r = 0; r < impl_->robots.size(); ++r) {
    if (impl_->robots[r].name == name) return static_cast<int>(r);
  }
  return -1;
}
int Physics::joint_count(int robot) const {
  return static_cast<int>(impl_->robot(robot).servos.size());
}
Axis Physics::joint_axis(int robot, int joint) const {
  return impl_->servo(robot, joint).axis;
}
double Physics::joint_lower_limit(int robot, int joint) const {
  return impl_->servo(robot, joint).lower;
}
double Physics::joint_upper_limit(int robot, int joint) const {
  return impl_->servo(robot, joint).upper;
}
int Physics::joint_module(int robot, int joint) const {
  return impl_->servo(robot, joint).module;
}
int Physics::module_count(int robot) const {
  return static_cast<int>(impl_->robot(robot).frame_bodies.size() / 2);
}
int Physics::sensor_module_count(int robot) const {
  return static_cast<int>(impl_->robot(robot).sensor_modules.size());
}

void Physics::SetLockAttached(const std::string& robot, const std::string& lock,
                              bool attached) {
  if (impl_->split && robot_index(robot) >= 0) {
    int local = 0;
    impl_->split->world_of(robot_index(robot), &local)
        .SetLockAttached(robot, lock, attached);
    impl_->split->MarkStale();
    return;
  }
  Impl::LockIndex* l = &impl_->FindLock(robot, lock);
  if (l->eq < 0) {
    if (attached) return;  // a rigid link is attached
    // Rebuild with this lock as a weld, carrying the state over.
    impl_->runtime_welds.insert(robot + "/" + lock);
    MjModelPtr old_model = std::move(impl_->model);
    MjDataPtr old_data = std::move(impl_->data);
    impl_->Build();
    impl_->TransferState(old_model.get(), old_data.get());
    l = &impl_->FindLock(robot, lock);
  }
  const mjtByte active = attached ? 1 : 0;
  if (impl_->model->eq_active[l->eq] == active) return;
  impl_->model->eq_active[l->eq] = active;
  impl_->Refresh();
}

std::vector<std::pair<std::string, bool>> Physics::LockStates(
    const std::string& robot) const {
  const int r = robot_index(robot);
  if (r < 0 && robot == kLooseOwnerName && impl_->loose) {
    std::vector<std::pair<std::string, bool>> out;
    for (const Impl::LockIndex& l : impl_->loose->locks) {
      out.emplace_back(l.name, l.eq < 0 || impl_->model->eq_active[l.eq] != 0);
    }
    return out;
  }
  if (r < 0) throw PhysicsError(fmt::format("no robot named '{}'", robot));
  if (impl_->split) {
    int local = 0;
    return impl_->split->world_of(r, &local).LockStates(robot);
  }
  std::vector<std::pair<std::string, bool>> out;
  for (const Impl::LockIndex& l : impl_->robots[r].locks) {
    out.emplace_back(l.name, l.eq < 0 || impl_->model->eq_active[l.eq] != 0);
  }
  return out;
}

void Physics::SetJointTargets(int robot, const std::vector<double>& targets) {
  impl_->robot(robot);  // range check
  if (impl_->split) {
    int local = 0;
    impl_->split->world_of(robot, &local).SetJointTargets(local, targets);
    return;
  }
  Impl::RobotIndex& r = impl_->robots[robot];
  if (targets.size() != r.servos.size()) {
    throw std::invalid_argument(
        fmt::format("robot '{}' has {} hinge joints, got {} targets", r.name,
                    r.servos.size(), targets.size()));
  }
  for (size_t j = 0; j < targets.size(); ++j) {
    if (!std::isfinite(targets[j])) {
      throw std::invalid_argument(
          fmt::format("robot '{}' joint {}: target is not finite", r.name, j));
    }
  }
  for (size_t j = 0; j < targets.size(); ++j) {
    r.targets[j] = std::clamp(targets[j], r.servos[j].lower, r.servos[j].upper);
  }
}

int Physics::loose_servo_count() const {
  return impl_->loose ? static_cast<int>(impl_->loose->servos.size()) : 0;
}

void Physics::SetLooseTargets(const std::vector<double>& targets) {
  const int n = loose_servo_count();
  if (static_cast<int>(targets.size()) != n) {
    throw std::invalid_argument(fmt::format(
        "the loose parts have {} servo(s) (loose hinges with <servo>), got {} "
        "targets",
        n, targets.size()));
  }
  if (n == 0) return;
  Impl::RobotIndex& r = *impl_->loose;
  for (size_t j = 0; j < targets.size(); ++j) {
    if (!std::isfinite(targets[j])) {
      throw std::invalid_argument(
          fmt::format("loose servo {}: target is not finite", j));
    }
  }
  for (size_t j = 0; j < targets.size(); ++j) {
    r.targets[j] = std::clamp(targets[j], r.servos[j].lower, r.servos[j].upper);
  }
}

const std::vector<double>& Physics::loose_targets() const {
  static const std::vector<double> kNone;
  return impl_->loose ? impl_->loose->targets : kNone;
}

const std::vector<double>& Physics::joint_targets(int robot) const {
  if (impl_->split) {
    impl_->robot(robot);  // range check
    int local = 0;
    return impl_->split->world_of(robot, &local).joint_targets(local);
  }
  return impl_->robot(robot).targets;
}

RobotState Physics::ReadRobotState(int robot) const {
  if (impl_->split) {
    impl_->robot(robot);  // range check
    impl_->PushView();
    int local = 0;
    return impl_->split->world_of(robot, &local).ReadRobotState(local);
  }
  return impl_->Read(impl_->robot(robot),
                     impl_->scenario.robots.at(robot).sensor_modules,
                     impl_->GlobalId(robot), robot);
}

bool Physics::has_loose_parts() const { return impl_->loose.has_value(); }

RobotState Physics::ReadLooseState() const {
  if (!impl_->loose) {
    throw std::logic_error(
        "the scenario has no loose frames or sensor modules");
  }
  return impl_->Read(*impl_->loose, impl_->scenario.loose_sensor_modules,
                     impl_->loose->id, -1);
}

RobotState Physics::Impl::Read(const RobotIndex& r,
                               const std::vector<SensorModule>& sensor_modules,
                               uint64_t id, int robot) {
  const mjModel* m = model.get();
  const mjData* d = data.get();
  RobotState state;
  state.time = d->time;
  state.robot = r.name;
  for (int b : r.frame_bodies) state.frames.push_back(BodyPose(d, b));
  // A robot's frames come two per module; loose frames one by one.
  for (size_t i = 0; robot >= 0 && i + 1 < state.frames.size(); i += 2) {
    Pose p;
    p.position = (state.frames[i].position + state.frames[i + 1].position) / 2;
    p.orientation =
        state.frames[i].orientation.slerp(0.5, state.frames[i + 1].orientation);
    state.modules.push_back(p);
  }
  // actuator -1: a passive hinge, no actuator torque.
  auto add_joint = [&](int joint, int actuator) {
    JointState j;
    j.angle = d->qpos[m->jnt_qposadr[joint]];
    j.speed = d->qvel[m->jnt_dofadr[joint]];
    j.torque = actuator >= 0 ? d->actuator_force[actuator] : 0.0;
    j.world = BodyPose(d, m->jnt_bodyid[joint]);
    j.world.position =
        Eigen::Vector3d(d->xanchor[3 * joint], d->xanchor[3 * joint + 1],
                        d->xanchor[3 * joint + 2]);
    state.joints.push_back(j);
  };
  if (robot >= 0) {
    for (const Servo& s : r.servos) add_joint(s.joint, s.actuator);
  } else {
    for (const RobotIndex::LooseHinge& h : r.loose_hinges) {
      add_joint(h.joint, h.servo >= 0 ? r.servos[h.servo].actuator : -1);
    }
  }
  bool need_forces = false;
  // Kinds read through MuJoCo sensors (plate forces, accelerations) need
  // the current state's forces.
  for (const auto& si : r.sensor_modules) {
    for (const auto& inst : si.kinds) need_forces |= !inst.adr.empty();
  }
  if (need_forces) {
    // Contact forces of the current state: a full forward pass on a copy,
    // with the controls the next step would apply.
    if (!scratch) scratch = MakeMjData(m);
    if (!scratch) throw std::runtime_error("MuJoCo cannot allocate data");
    mjData* s = scratch.get();
    s->time = d->time;
    for (const PhysicsStateField& f : kPhysicsStateFields) {
      const int n = StateSize(m, f.per);
      if (!(f.copies & kStateForward) || n == 0) continue;
      if (f.array == &mjData::xfrc_applied) {
        ApplyBodyForces(d, s);  // as the next step will
      } else {
        mju_copy(s->*f.array, d->*f.array, n);
      }
    }
    ComputeControls(s, false);
    Forward(m, s, effects.contacts());
  }
  for (size_t smi = 0; smi < r.sensor_modules.size(); ++smi) {
    const SensorModuleIndex& si = r.sensor_modules[smi];
    SensorModuleState sm;
    sm.pose = BodyPose(d, si.body);
    for (const auto& inst : si.kinds) {
      SensorReadInput in;
      in.sensor_module = &sensor_modules.at(smi);
      in.instance = inst.k;
      for (int adr : inst.adr) {
        in.mujoco.push_back(scratch->sensordata + adr);
      }
      if (inst.site >= 0) {
        in.ray =
            CastDistanceRay(m, d, inst.site, si.plate, inst.max_range).distance;
        if (other_rays) {  // the robots in the scene's other worlds
          in.ray = std::min(
              in.ray, other_rays(d->site_xpos + 3 * inst.site,
                                 d->site_xmat + 9 * inst.site, inst.max_range));
        }
      }
      in.time = d->time;
      const uint64_t ids[3] = {id, smi, static_cast<uint64_t>(inst.k)};
      in.key = Fnv1a64(ids, sizeof ids);
      std::vector<double> values(inst.kind->channels.size());
      inst.kind->read(in, values.data());
      if (inst.kind->store != nullptr) {
        inst.kind->store(sm, inst.face, values);
      } else {
        sm.readings.push_back({inst.kind->name, inst.face, std::move(values)});
      }
    }
    state.sensor_modules.push_back(std::move(sm));
  }
  double mass = 0;
  for (int b : r.bodies) {
    const double mb = m->body_mass[b];
    mjtNum vel[6];
    mj_objectVelocity(m, d, mjOBJ_BODY, b, vel, 0);
    for (int i = 0; i < 3; ++i) {
      state.com[i] += mb * d->xipos[3 * b + i];
      state.com_velocity[i] += mb * vel[3 + i];
    }
    mass += mb;
  }
  if (mass > 0) {
    state.com /= mass;
    state.com_velocity /= mass;
  }
  FillRobotOrientation(&state);
  if (robot >= 0 && !effects.readings().empty()) {
    std::vector<std::vector<double>> max_distance;
    for (const auto& si : r.sensor_modules) {
      max_distance.push_back(si.max_distance);
    }
    for (const PhysicsEffect* effect : effects.readings()) {
      effect->AdjustReadings(StepIndex(d), id, max_distance, &state);
    }
  }
  return state;
}

Eigen::Vector3d Physics::CenterOfMass(int robot) const {
  if (impl_->split) {
    impl_->robot(robot);  // range check
    impl_->PushView();
    int local = 0;
    return impl_->split->world_of(robot, &local).CenterOfMass(local);
  }
  const Impl::RobotIndex& r = impl_->robot(robot);
  const mjModel* m = impl_->model.get();
  const mjData* d = impl_->data.get();
  Eigen::Vector3d com = Eigen::Vector3d::Zero();
  double mass = 0;
  for (int b : r.bodies) {
    const double mb = m->body_mass[b];
    for (int i = 0; i < 3; ++i) com[i] += mb * d->xipos[3 * b + i];
    mass += mb;
  }
  return mass > 0 ? Eigen::Vector3d(com / mass) : com;
}

std::vector<unsigned char> Physics::SaveState() const {
  if (impl_->split) {
    impl_->PushView();
    return impl_->split->SaveState();
  }
  const mjModel* m = impl_->model.get();
  const mjData* d = impl_->data.get();
  std::vector<double> targets;
  impl_->ForEachTargets([&](const std::vector<double>& t) {
    targets.insert(targets.end(), t.begin(), t.end());
  });
  const int32_t sizes[7] = {m->nq,
                            m->nv,
                            m->na,
                            m->nu,
                            m->nbody,
                            m->nsensordata,
                            static_cast<int32_t>(targets.size())};
  std::vector<unsigned char> locks;
  impl_->ForEachLock([&](const Impl::RobotIndex& r, const Impl::LockIndex& l) {
    unsigned char flags = 0;
    if (l.eq < 0 || m->eq_active[l.eq]) flags |= kLockAttached;
    if (impl_->runtime_welds.count(r.name + "/" + l.name)) {
      flags |= kLockRuntimeWeld;
    }
    locks.push_back(flags);
  });
  const int32_t nlocks = static_cast<int32_t>(locks.size());
  std::vector<unsigned char> out;
  Put(out, kStateMagic, sizeof(kStateMagic));
  Put(out, &nlocks, 1);
  Put(out, locks.data(), locks.size());
  Put(out, sizes, 7);
  Put(out, &d->time, 1);
  for (const PhysicsStateField& f : kPhysicsStateFields) {
    if (!InCheckpoint(f, kStateVersion)) continue;
    if (f.per == StatePer::kTarget) {
      Put(out, targets.data(), targets.size());
    } else if (f.array == nullptr) {
      Put(out, impl_->qpos_integrated.data(), m->nq);
    } else {
      Put(out, d->*f.array, StateSize(m, f.per));
    }
  }
  return out;
}

void Physics::LoadState(const std::vector<unsigned char>& bytes) {
  if (impl_->split) {
    impl_->split->LoadState(bytes);
    if (impl_->view_poked) impl_->split->SyncView(model(), impl_->data.get());
    return;
  }
  if (WorldSplit::IsSplitState(bytes)) {
    throw std::invalid_argument(
        "physics state: saved for a scene of several worlds; this scene runs "
        "as one");
  }
  size_t ntargets = 0;
  size_t nlocks = 0;
  impl_->ForEachLock(
      [&](const Impl::RobotIndex&, const Impl::LockIndex&) { ++nlocks; });
  // States saved before the loose locks were listed end at the robots'.
  size_t robot_locks = 0;
  for (const auto& r : impl_->robots) robot_locks += r.locks.size();
  impl_->ForEachTargets(
      [&](const std::vector<double>& t) { ntargets += t.size(); });
  const int version = StateVersion(bytes);
  if (version == 0) {
    throw std::invalid_argument("physics state: not an mrsim state blob");
  }
  const bool v1 = version == 1;
  const bool v3 = version >= 3;
  // Version 3: lock states first, since a lock released at run time
  // changes the model the rest was saved from.
  std::vector<unsigned char> lock_flags(nlocks, kLockAttached);
  size_t lock_bytes = 0;
  if (v3) {
    int32_t saved_locks = -1;
    if (bytes.size() >= sizeof(kStateMagic) + sizeof(int32_t)) {
      std::memcpy(&saved_locks, bytes.data() + sizeof(kStateMagic),
                  sizeof(int32_t));
    }
    const size_t nsaved =
        saved_locks == static_cast<int32_t>(robot_locks) ? robot_locks : nlocks;
    if (saved_locks != static_cast<int32_t>(nsaved) ||
        bytes.size() < sizeof(kStateMagic) + sizeof(int32_t) + nsaved) {
      throw std::invalid_argument(fmt::format(
          "physics state: saved for a different model ({} locks; this model "
          "has {})",
          saved_locks, nlocks));
    }
    lock_bytes = sizeof(int32_t) + nsaved;
    if (nsaved > 0) {  // an empty vector's data() may be null
      std::memcpy(lock_flags.data(),
                  bytes.data() + sizeof(kStateMagic) + sizeof(int32_t), nsaved);
    }
    std::set<std::string> welds;
    size_t i = 0;
    for (const auto& r : impl_->robots) {
      for (const Impl::LockIndex& l : r.locks) {
        if (lock_flags[i++] & kLockRuntimeWeld)
          welds.insert(r.name + "/" + l.name);
      }
    }
    if (welds != impl_->runtime_welds) {
      impl_->runtime_welds = welds;
      impl_->Build();
    }
  }
  const mjModel* m = impl_->model.get();
  // Version 1 has no nsensordata entry.
  std::vector<int32_t> expect = {m->nq, m->nv, m->na, m->nu, m->nbody};
  if (!v1) expect.push_back(m->nsensordata);
  expect.push_back(static_cast<int32_t>(ntargets));
  const size_t header =
      sizeof(kStateMagic) + lock_bytes + expect.size() * sizeof(int32_t);
  size_t doubles = 1;  // the time
  for (const PhysicsStateField& f : kPhysicsStateFields) {
    if (InCheckpoint(f, version)) {
      doubles += f.per == StatePer::kTarget ? ntargets : StateSize(m, f.per);
    }
  }
  std::vector<int32_t> sizes(expect.size(), -1);
  if (bytes.size() >= header) {
    std::memcpy(sizes.data(), bytes.data() + sizeof(kStateMagic) + lock_bytes,
                sizes.size() * sizeof(int32_t));
  }
  if (sizes != expect || bytes.size() != header + doubles * sizeof(double)) {
    auto list = [](const std::vector<int32_t>& v) {
      return fmt::format(
          "nq {} nv {} na {} nu {} nbody {}{} targets {}", v[0], v[1], v[2],
          v[3], v[4],
          v.size() == 7 ? fmt::format(" nsensordata {}", v[5]) : std::string(),
          v.back());
    };
    throw std::invalid_argument(fmt::format(
        "physics state: saved for a different model ({}, {} bytes; this "
        "model has {}, {} bytes)",
        list(sizes), bytes.size(), list(expect),
        header + doubles * sizeof(double)));
  }
  // Every number as the physics could have saved it: finite, and the time
  // a sim time (a NaN or 1e308 in a hostile checkpoint stalls stepping).
  for (size_t i = 0; i < doubles; ++i) {
    double v;
    std::memcpy(&v, bytes.data() + header + i * sizeof(double), sizeof(v));
    if (!std::isfinite(v) || std::abs(v) > kMaxStateValue ||
        (i == 0 && (v < 0 || v > kMaxStateTime))) {
      throw std::invalid_argument(fmt::format(
          "physics state: number {} of {} is {}, not a state the physics "
          "can have ({}finite, at most {} in size)",
          i + 1, doubles, v,
          i == 0 ? fmt::format("the sim time: 0..{} s, ", kMaxStateTime) : "",
          kMaxStateValue));
    }
  }
  mjData* d = impl_->data.get();
  ResetMjData(m, d);
  const unsigned char* p = bytes.data() + header;
  auto get = [&p](mjtNum* dst, size_t n) {
    if (n == 0) return;  // MuJoCo leaves empty arrays null (e.g. act)
    std::memcpy(dst, p, n * sizeof(double));
    p += n * sizeof(double);
  };
  get(&d->time, 1);
  // Arrays the kinematics pass would overwrite, written after it.
  std::array<std::vector<mjtNum>, kPhysicsStateFields.size()> after;
  bool integrated = false;
  for (size_t i = 0; i < kPhysicsStateFields.size(); ++i) {
    const PhysicsStateField& f = kPhysicsStateFields[i];
    if (!InCheckpoint(f, version)) continue;
    if (f.per == StatePer::kTarget) {
      impl_->ForEachTargets(
          [&](std::vector<double>& t) { get(t.data(), t.size()); });
    } else if (f.array == nullptr) {
      get(d->qpos, m->nq);  // the integrated qpos (see qpos_integrated)
      integrated = true;
    } else if (f.stage == StateStage::kAfter) {
      after[i].resize(StateSize(m, f.per));
      get(after[i].data(), after[i].size());
    } else {
      get(d->*f.array, StateSize(m, f.per));
    }
  }
  if (!integrated) {  // version 1: the saved qpos is all there is
    for (size_t i = 0; i < kPhysicsStateFields.size(); ++i) {
      if (kPhysicsStateFields[i].array == &mjData::qpos && !after[i].empty())
        mju_copy(d->qpos, after[i].data(), m->nq);
    }
  }
  std::copy(impl_->eq_active0.begin(), impl_->eq_active0.end(),
            impl_->model->eq_active);
  size_t li = 0;
  impl_->ForEachLock([&](const Impl::RobotIndex& r, const Impl::LockIndex& l) {
    const bool attached = lock_flags[li++] & kLockAttached;
    if (l.eq >= 0) {
      impl_->model->eq_active[l.eq] = attached ? 1 : 0;
    } else if (!attached) {
      throw std::invalid_argument(
          "physics state: lock '" + l.name + "' of robot '" + r.name +
          "' is released in the state but rigid in this model");
    }
  });
  impl_->AfterStateChange();
  // The kinematics pass reproduces the saved qpos exactly unless the state
  // was poked between the step and the save; the saved one is kept. The
  // pass may have given the physics a bigger mjData (MakeRoom).
  d = impl_->data.get();
  for (size_t i = 0; i < kPhysicsStateFields.size(); ++i) {
    if (!after[i].empty()) {
      mju_copy(d->*kPhysicsStateFields[i].array, after[i].data(),
               static_cast<int>(after[i].size()));
    }
  }
}

const Scenario& Physics::scenario() const { return impl_->scenario; }
const mjModel* Physics::model() const { return impl_->model.get(); }
const mjData* Physics::data() const {
  if (impl_->split) impl_->split->SyncView(model(), impl_->data.get());
  return impl_->data.get();
}
mjData* Physics::mutable_data() {
  if (impl_->split) {
    impl_->split->SyncView(model(), impl_->data.get());
    impl_->view_poked = true;
  }
  return impl_->data.get();
}

void Physics::SetOtherWorldsRay(RayCast cast) {
  impl_->other_rays = std::move(cast);
}

void Physics::AfterPoke() { impl_->AfterStateChange(); }

void Physics::AbsorbState(const std::vector<const Physics*>& parts) {
  Impl& to = *impl_;
  std::set<std::string> welds;
  for (const Physics* p : parts) {
    welds.insert(p->impl_->runtime_welds.begin(),
                 p->impl_->runtime_welds.end());
  }
  if (welds != to.runtime_welds) {
    to.runtime_welds = welds;
    to.Build();
  }
  const mjModel* m = to.model.get();
  mjData* d = to.data.get();
  std::copy(to.eq_active0.begin(), to.eq_active0.end(), to.model->eq_active);
  auto id = [m](mjtObj type, const char* name) {
    const int i = name ? mj_name2id(m, type, name) : -1;
    if (i < 0) {
      throw std::logic_error(fmt::format("merged world has no {} '{}'",
                                         mju_type2Str(type),
                                         name ? name : "(unnamed)"));
    }
    return i;
  };
  // Per part, where its entries go in the merged world; indices, since
  // Refresh may give the world a bigger mjData (MakeRoom).
  std::vector<StateMap> maps(parts.size());
  for (size_t pi = 0; pi < parts.size(); ++pi) {
    const Impl& from = *parts[pi]->impl_;
    const mjModel* om = from.model.get();
    const mjData* od = from.data.get();
    StateMap& map = maps[pi];
    for (int j = 0; j < om->njnt; ++j) {
      const int nj = id(mjOBJ_JOINT, mj_id2name(om, mjOBJ_JOINT, j));
      const int type = om->jnt_type[j];
      const int nq = type == mjJNT_FREE ? 7 : type == mjJNT_BALL ? 4 : 1;
      const int nv = type == mjJNT_FREE ? 6 : type == mjJNT_BALL ? 3 : 1;
      map.of(StatePer::kJointPosition)
          .push_back({m->jnt_qposadr[nj], om->jnt_qposadr[j], nq});
      map.of(StatePer::kDof)
          .push_back({m->jnt_dofadr[nj], om->jnt_dofadr[j], nv});
    }
    for (int a = 0; a < om->nu; ++a) {
      const int na = id(mjOBJ_ACTUATOR, mj_id2name(om, mjOBJ_ACTUATOR, a));
      map.of(StatePer::kActuator).push_back({na, a, 1});
      // MuJoCo 2.2 keeps the activations of the last na actuators.
      if (om->na > 0 && a >= om->nu - om->na) {
        map.of(StatePer::kActivation)
            .push_back({na - (m->nu - m->na), a - (om->nu - om->na), 1});
      }
    }
    for (int b = 1; b < om->nbody; ++b) {
      const char* name = mj_id2name(om, mjOBJ_BODY, b);
      if (name) {
        map.of(StatePer::kBody).push_back({6 * id(mjOBJ_BODY, name), 6 * b, 6});
      }
    }
    for (int s = 0; s < om->nsensor; ++s) {
      const int ns = id(mjOBJ_SENSOR, mj_id2name(om, mjOBJ_SENSOR, s));
      map.of(StatePer::kSensordata)
          .push_back({m->sensor_adr[ns], om->sensor_adr[s], om->sensor_dim[s]});
    }
    d->time = od->time;
    for (const PhysicsStateField& f : kPhysicsStateFields) {
      if (!(f.copies & kStateMerge) || f.stage == StateStage::kAfter) continue;
      if (f.per == StatePer::kTarget) {
        // And the effects' history of them (the reality gap's latency).
        std::vector<int> to_robot(from.robots.size(), -1);
        for (size_t r = 0; r < from.robots.size(); ++r) {
          for (size_t k = 0; k < to.robots.size(); ++k) {
            if (to.robots[k].name != from.robots[r].name) continue;
            to.robots[k].targets = from.robots[r].targets;
            to_robot[r] = static_cast<int>(k);
          }
        }
        to.effects.Absorb(from.effects, to_robot);
      } else if (f.array == nullptr) {
        // In the merged world's Refresh below, the pose of every part is
        // computed from its integrated qpos, as in its own world.
        map.Copy(f.per, from.qpos_integrated.data(), to.qpos_integrated.data());
      } else {
        map.Copy(f.per, od->*f.array, d->*f.array);
      }
    }
    for (int e = 0; e < om->neq; ++e) {
      to.model
          ->eq_active[id(mjOBJ_EQUALITY, mj_id2name(om, mjOBJ_EQUALITY, e))] =
          om->eq_active[e];
    }
  }
  to.Refresh();
  // Torques and sensor values of the last steps, which the kinematics pass
  // does not recompute, and a qpos poked after its world's step (kept, as
  // LoadState does).
  d = to.data.get();
  for (size_t pi = 0; pi < parts.size(); ++pi) {
    const mjData* od = parts[pi]->impl_->data.get();
    for (const PhysicsStateField& f : kPhysicsStateFields) {
      if ((f.copies & kStateMerge) && f.stage == StateStage::kAfter) {
        maps[pi].Copy(f.per, od->*f.array, d->*f.array);
      }
    }
  }
}

}  // namespace mrsim
