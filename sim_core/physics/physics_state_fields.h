// The physics state named once: every array a run carries from one step to
// the next, what it is indexed by, and which copy of the state carries it.
// A checkpoint (Physics::SaveState/LoadState, in this order on the wire),
// the bigger mjData of a step that ran out of constraint rows (MakeRoom),
// the force readings' private forward (ReadRobotState), a model rebuilt for
// a released lock (TransferState), the merge of a split scene's worlds
// (AbsorbState) and the split scene's view of them (WorldSplit::SyncView)
// are all made from kPhysicsStateFields, as MuJoCo makes its
// I/O from mjxmacro.h and names its state parts in mjtState. The sim time
// travels first in every copy and is not listed.
#pragma once

#include <mujoco/mujoco.h>

#include <array>

namespace mrsim {

// What one entry of an array belongs to: sizes it in a model and, when the
// state moves between two models (TransferState, AbsorbState), matches its
// entries by the owner's name.
enum class StatePer {
  kJointPosition,  // nq: by joint
  kDof,            // nv: by joint
  kActuator,       // nu
  kActivation,     // na: the last na actuators
  kBody,           // 6 per body (xfrc_applied)
  kMocapPosition,  // 3 per mocap body
  kMocapRotation,  // 4 per mocap body
  kUserdata,       // nuserdata
  kSensordata,     // nsensordata: by sensor
  kTarget,         // the robots' joint targets, by robot (keep last)
};

// Which copies carry an array (bit flags).
enum StateCopy : unsigned {
  kStateCheckpoint = 1u << 0,  // SaveState / LoadState
  kStateGrow = 1u << 1,        // MakeRoom: the same model, a bigger mjData
  kStateForward = 1u << 2,     // ReadRobotState's scratch forward
  kStateTransfer = 1u << 3,    // TransferState: a model rebuilt with welds
  kStateMerge = 1u << 4,       // AbsorbState: a split scene made one world
  // WorldSplit::SyncView: what data() of a split scene shows of its
  // worlds (the view then computes its own kinematics).
  kStateView = 1u << 5,
};

// Where a copy writes an array relative to the kinematics pass (mj_step1)
// that follows it.
enum class StateStage {
  kBefore,  // an input of mj_step1
  // Results of the last step's dynamics (mj_step2) or the saved pose, which
  // the kinematics pass would overwrite: written after it.
  kAfter,
};

struct PhysicsStateField {
  const char* name;
  // Null for the two parts of the state that are not mjData's:
  // kIntegratedQpos (Physics' qpos as mj_step2 left it) and the targets.
  mjtNum* mjData::*array;
  StatePer per;
  unsigned copies;
  StateStage stage;
  // The first checkpoint version holding it (blob magic "MRSIMST<n>").
  int since;
};

constexpr unsigned kStateAllCopies = kStateCheckpoint | kStateGrow |
                                     kStateForward | kStateTransfer |
                                     kStateMerge;

// The checkpoint's arrays are in their order in the blob: never reorder
// them; a new one goes after the last with the next version in `since`
// (and a new magic), so every older checkpoint still loads.
constexpr std::array<PhysicsStateField, 17> kPhysicsStateFields = {{
    // The pose as saved (maybe poked after the step), kept over the one
    // the kinematics pass renormalises from qpos_integrated. A bigger
    // mjData needs no copy: its kinematics pass makes it. The forward copy
    // (a full mj_forward) and TransferState (a new model, whose pass starts
    // from the current pose) take it as it is; a version-1 blob, without
    // qpos_integrated, runs the pass from it too.
    {"qpos", &mjData::qpos, StatePer::kJointPosition,
     kStateCheckpoint | kStateForward | kStateTransfer | kStateMerge |
         kStateView,
     StateStage::kAfter, 1},
    // Physics' own qpos as mj_step2 left it, before mj_step1 renormalised
    // its quaternions in place (not idempotent in the last bit): what the
    // kinematics pass of a loaded or merged state starts from.
    {"qpos_integrated", nullptr, StatePer::kJointPosition,
     kStateCheckpoint | kStateGrow | kStateMerge, StateStage::kBefore, 2},
    {"qvel", &mjData::qvel, StatePer::kDof, kStateAllCopies | kStateView,
     StateStage::kBefore, 1},
    // TransferState predates activations (no mrsim actuator has any yet).
    {"act", &mjData::act, StatePer::kActivation,
     kStateAllCopies & ~kStateTransfer, StateStage::kBefore, 1},
    {"ctrl", &mjData::ctrl, StatePer::kActuator, kStateAllCopies | kStateView,
     StateStage::kBefore, 1},
    {"qacc_warmstart", &mjData::qacc_warmstart, StatePer::kDof, kStateAllCopies,
     StateStage::kBefore, 1},
    {"qfrc_applied", &mjData::qfrc_applied, StatePer::kDof,
     kStateAllCopies | kStateView, StateStage::kBefore, 1},
    // The forward copy takes the body-force effects' forces instead when
    // one is built (they own the whole array then, as in a step).
    {"xfrc_applied", &mjData::xfrc_applied, StatePer::kBody,
     kStateAllCopies | kStateView, StateStage::kBefore, 1},
    // Torques and sensor values of the last step: mj_step1 does not
    // recompute them, ReadRobotState reports them. The forward copy
    // computes its own.
    {"actuator_force", &mjData::actuator_force, StatePer::kActuator,
     kStateCheckpoint | kStateGrow | kStateMerge | kStateView,
     StateStage::kAfter, 2},
    {"sensordata", &mjData::sensordata, StatePer::kSensordata,
     kStateCheckpoint | kStateGrow | kStateMerge | kStateView,
     StateStage::kAfter, 2},
    {"targets", nullptr, StatePer::kTarget, kStateCheckpoint | kStateMerge,
     StateStage::kBefore, 1},
    // Directional friction's look at the last unconstrained acceleration.
    // TransferState predates directional friction: a lock released at run
    // time in a scene with it starts its first step from zero (kept, since
    // runs must stay bit for bit what they were).
    {"qacc_smooth", &mjData::qacc_smooth, StatePer::kDof,
     kStateAllCopies & ~kStateTransfer, StateStage::kBefore, 4},
    // Only a bigger mjData of the same step needs these: every other copy
    // is followed by a step that recomputes them (qacc is also what the
    // stability check and data() read, so a split scene's view shows it).
    {"act_dot", &mjData::act_dot, StatePer::kActivation, kStateGrow,
     StateStage::kBefore, 0},
    {"qacc", &mjData::qacc, StatePer::kDof, kStateGrow | kStateView,
     StateStage::kBefore, 0},
    // mrsim's models have no mocap bodies and no user data; MakeRoom keeps
    // them so a model that does would not lose them mid-step. Not in the
    // checkpoint: adding them would need a version 5.
    {"mocap_pos", &mjData::mocap_pos, StatePer::kMocapPosition, kStateGrow,
     StateStage::kBefore, 0},
    {"mocap_quat", &mjData::mocap_quat, StatePer::kMocapRotation, kStateGrow,
     StateStage::kBefore, 0},
    {"userdata", &mjData::userdata, StatePer::kUserdata, kStateGrow,
     StateStage::kBefore, 0},
}};

// Checked at compile time: only a checkpoint array has a version; the
// copies that take an array from mjData to mjData (forward, transfer,
// view) list only mjData's arrays.
constexpr bool PhysicsStateTableIsConsistent() {
  for (const PhysicsStateField& f : kPhysicsStateFields) {
    const bool saved = (f.copies & kStateCheckpoint) != 0;
    if (saved != (f.since >= 1)) return false;
    if ((f.copies & (kStateForward | kStateTransfer | kStateView)) &&
        f.array == nullptr)
      return false;
    // A split scene's view maps joints, actuators, bodies and sensors.
    if ((f.copies & kStateView) &&
        (f.per == StatePer::kActivation || f.per == StatePer::kMocapPosition ||
         f.per == StatePer::kMocapRotation || f.per == StatePer::kUserdata))
      return false;
  }
  return true;
}
static_assert(PhysicsStateTableIsConsistent(),
              "kPhysicsStateFields: see PhysicsStateTableIsConsistent");

// The number of mjtNum of an array of the table in model m (kTarget: 0,
// the targets are Physics' own).
inline int StateSize(const mjModel* m, StatePer per) {
  switch (per) {
    case StatePer::kJointPosition:
      return m->nq;
    case StatePer::kDof:
      return m->nv;
    case StatePer::kActuator:
      return m->nu;
    case StatePer::kActivation:
      return m->na;
    case StatePer::kBody:
      return 6 * m->nbody;
    case StatePer::kMocapPosition:
      return 3 * m->nmocap;
    case StatePer::kMocapRotation:
      return 4 * m->nmocap;
    case StatePer::kUserdata:
      return m->nuserdata;
    case StatePer::kSensordata:
      return m->nsensordata;
    case StatePer::kTarget:
      return 0;
  }
  return 0;
}

}  // namespace mrsim
