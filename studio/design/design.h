// The studio's editing model, with no window: the scenario being designed,
// the selection, and every edit as a command that goes through the one
// validator and can be undone. The window only calls these.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include "sim_core/scenario/chain_builder.h"
#include "sim_core/scenario/scenario.h"
#include "sim_core/scenario/sensor_kind.h"
#include "studio/design/ground_move.h"
#include "studio/design/selection.h"

namespace mrsim::studio {

// An edit the design refuses; what() says why (the schema's message for a
// field). The design is unchanged.
class DesignError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

enum class NextPart { kPitchModule, kYawModule, kSensorModule };
// Where AddPart puts the new part in the chain.
enum class Where { kAfterSelection, kFront, kTail };
enum class ObjectKind { kBall, kBox, kCylinder, kCapsule, kRamp };
// A part without a robot (Scenario::loose_*): a frame, a sensor module, or
// a hinge (two loose frames joined by a loose joint).
enum class LoosePart { kFrame, kSensorModule, kHinge };

// A part of a robot a lock may join: a frame or a sensor module, by guid,
// with its name in words ("module 2 back frame", "S0 sensor module").
struct LockEnd {
  std::string guid;
  std::string name;
};

// One field of one part: the part, the sub-part ("" for the part itself,
// "frames[0]", "frames[1]", "joint", "force_sensor", "distance_sensors[k]")
// and the field's XML name.
// No module is a metre long: a mesh frame longer than this on some axis was
// almost surely drawn in millimetres.
inline constexpr double kMeshLooksLikeMillimetres = 1.0;  // m

struct FieldAddress {
  Selection part;
  std::string sub;
  std::string field;
};

// The options of `mrsim-scenario new` (sim_core/scenario/chain_builder.h).
using TemplateOptions = ChainScenarioOptions;
// The scenario `mrsim-scenario new` writes for these options (the same
// MakeChainScenario); throws DesignError for impossible options.
Scenario MakeTemplateScenario(const TemplateOptions& options);
// No robot yet, flat ground: where a new design starts.
Scenario EmptyScenario();

class Design {
 public:
  Design();
  // Opens a file (throws ScenarioError naming it). A path that does not
  // exist yet starts an empty design that saves there.
  static Design Open(const std::string& path);

  const Scenario& scenario() const { return scenario_; }
  const Selection& selection() const { return selection_; }
  const std::string& path() const { return path_; }
  // Unsaved changes since the last open or save.
  bool dirty() const { return dirty_; }
  // What opening did that the user should know (an original MRSim file
  // converted, and where it saves); empty otherwise.
  const std::string& note() const { return note_; }
  // Grows by one on every change of the scenario (the preview rebuilds).
  long revision() const { return revision_; }

  // Selecting is not an edit: no undo step. Out-of-range selections clear.
  void Select(const Selection& selection);

  // Edits. Each is one undo step; each throws DesignError and leaves the
  // design unchanged when the result would not validate.
  // Inserts into the selected (or first) robot: after the selected module
  // or sensor module (at the tail when none is selected), at the front or
  // at the tail; selects the new part.
  void AddPart(NextPart part, Where where = Where::kAfterSelection);
  // In front of the first robot, next to earlier objects; selects it.
  void AddObject(ObjectKind kind);
  // Drag and drop. Inserts a new part at place `at` (front to back as the
  // chain list shows it, 0 = front, the part count = tail) of robot
  // `robot` (0 starts the first robot); selects it.
  void InsertPart(NextPart part, int robot, int at);
  // Moves the chain part at place `from` of robot `robot` to place `to`
  // (where it is once moved); selects it.
  void MovePart(int robot, int from, int to);
  // Moves a whole robot (a robot, module or sensor module selection names
  // it), an object, or a loose part with every loose part joined to it (a
  // loose frame, sensor module or joint selection names them) on the
  // ground: shifted and turned about its pivot (ground_move.h). Only poses
  // change.
  void MoveOnGround(const Selection& what, const GroundMove& move);
  // A second (third, ...) robot: one pitch module, named robot2, ...,
  // beside the others (0.3 m to the left of the leftmost); selects it.
  void AddRobot();
  void AddFluid(FluidKind kind);
  void AddContact();
  // A loose part (LoosePart) beside the robots (behind and to the right of
  // every robot, next to earlier loose parts), resting on the ground;
  // selects it (a hinge: its joint).
  void AddLoose(LoosePart part);
  // Removes the selected module, sensor module, object, fluid region,
  // contact pair, lock (as DetachLock) or loose part (a loose frame or
  // sensor module takes the loose joints naming it along).
  void RemoveSelected();
  // Removes the selected lock from its robot. Refused when it holds the
  // robot together (a chain's lock: the parts behind it would drift
  // apart); a loop-closing lock detaches.
  void DetachLock();
  // The parts of robot `robot`, frames and sensor modules in chain order,
  // that a lock may join.
  std::vector<LockEnd> LockEnds(int robot) const;
  // The parts of the selected robot part's robot that a lock from `from`
  // may join: not `from` itself, nor a part a hinge or lock joins it to
  // already.
  std::vector<LockEnd> AttachableTo(int robot, const std::string& from) const;
  // A lock between two parts (guids of frames or sensor modules) of robot
  // `robot` that nothing joins directly yet: a part of the chain's next to
  // another, or one that closes a loop (MuJoCo keeps the two at the pose
  // they have in the design: a weld). Selects it.
  void AttachLock(int robot, const std::string& a, const std::string& b);
  // The loose parts (frames and sensor modules) a loose joint may join,
  // named as the Design panel lists them ("loose frame loose/f0").
  std::vector<LockEnd> LooseEnds() const;
  // The loose parts a loose joint from `from` may join: not `from` itself,
  // nor a part a loose joint joins it to already.
  std::vector<LockEnd> LooseJoinableTo(const std::string& from) const;
  // A loose joint of `type` between two loose parts (guids of loose frames
  // or sensor modules): a Lock holds them at the pose they have in the
  // design (a loose sensor module locked to a loose frame rides on it); a
  // Hinge turns about the first part's y axis, through the point midway
  // between them, and turns freely until its servo is switched on. A hinge
  // that would close a loop is refused. Selects the joint.
  void JoinLoose(const std::string& a, const std::string& b, JointType type);
  // Moves the selected chain part `steps` places towards the back (> 0) or
  // the front (< 0).
  void MoveSelected(int steps);
  // The selected sensor module (a robot's or a loose one) gets a sensor of
  // `kind` (sensor_kind.h, a kind with SensorKind::set: the force plate,
  // the IMU) or loses it. A plate kind lays the chain out again: it rises
  // onto plates or comes down when the first arrives or the last goes; a
  // loose sensor module has no chain to rest on plates and refuses one.
  void SetSensorKind(const SensorKind& kind, bool on);
  // SetSensorKind of the force plate (on its bottom face).
  void SetForcePlate(bool on);
  // A distance sensor on face `face` (0..5: bottom, left, top, right,
  // front, back) of the selected sensor module (a robot's or a loose
  // one), looking out of that face; one per face, at most six.
  void AddDistanceSensor(int face);
  // The faces AddDistanceSensor would take on the selected sensor module
  // (free, and looking out of the robot), for the face picker's default.
  std::vector<int> OpenRayFaces() const;
  // Removes distance sensor `k` of the selected sensor module.
  void RemoveDistanceSensor(int k);
  // A camera (sensor_kind.h's "camera", default picture) on face `face`
  // of the selected sensor module (a robot's or a loose one) or scene
  // object (a face of the box around it; on a static object, a fixed view
  // of the world), looking out of that face; one per face, at most six.
  // Refused on a face that looks into the robot (it would see only its
  // neighbour).
  void AddCamera(int face);
  // The faces AddCamera would take on the selected sensor module or scene
  // object.
  std::vector<int> OpenCameraFaces() const;
  // Removes camera `k` of the selected sensor module or scene object.
  void RemoveCamera(int k);
  // Sets one field from text, e.g. SetField({sel, "joint", "Kp"}, "12").
  void SetField(const FieldAddress& address, const std::string& text);
  // Terrain: an image (empty: flat ground), brightest-pixel height and
  // metres per pixel, as one edit.
  void SetTerrain(const std::string& image, double height,
                  double meters_per_pixel);
  // The selected module's frames (every_of_kind: those of every module of
  // its axis) become the OBJ/STL `mesh`, as one edit; the chain restacks
  // to the mesh's length and new modules of that kind reuse it. Throws
  // DesignError when nothing is selected or the mesh cannot be read.
  void SetModuleMesh(const std::string& mesh, bool every_of_kind);
  // Every frame whose shape is `shape` (a mesh) has its scale multiplied by
  // `factor` (0.001: a mesh drawn in millimetres), as one edit; the chains
  // restack to the new lengths.
  void ScaleMesh(const std::string& shape, double factor);
  // Replaces everything with a template (undoable).
  void ApplyTemplate(const TemplateOptions& options);
  // Replaces everything with an empty scenario (undoable; path kept).
  void Clear();

  bool can_undo() const { return !undo_.empty(); }
  bool can_redo() const { return !redo_.empty(); }
  void Undo();
  void Redo();

  // How to run the design (saved with it, <run>). Not an undo step and no
  // rebuild of the preview: the model is unchanged; the design is dirty
  // when they differ from the file's. Throws DesignError for settings no
  // run could use (a Lua controller without a script, a bad name).
  void SetRunSettings(const RunSettings& run);
  // How to optimise the design (saved with it, <optimization>; none: not
  // saved), as SetRunSettings: not an undo step, dirty when it differs
  // from the file's. Throws DesignError for values the file cannot hold.
  void SetOptimizationSettings(
      const std::optional<OptimizationSettings>& setup);

  // Writes the file (atomically); throws std::runtime_error naming it.
  // With embed_assets, the file carries the terrain image and mesh files
  // as base64 (sim_core/scenario/embed_assets.h), the design on screen keeps
  // its paths.
  void Save(bool embed_assets = false);
  void SaveAs(const std::string& path, bool embed_assets = false);

  // The meshes (each shape once, in chain order) that some frame shows
  // longer than kMeshLooksLikeMillimetres on an axis: most CAD programs
  // export millimetres, which make a part 1000 times too big. Reads the
  // mesh files: call once per revision. An unreadable mesh is not listed
  // (the validator says why it cannot be read).
  struct OversizedMesh {
    std::string shape;
    double longest = 0;  // m, the longest side of its biggest frame
  };
  std::vector<OversizedMesh> OversizedMeshes() const;

  // The current value of a field as text, or throws DesignError.
  std::string FieldText(const FieldAddress& address) const;

 private:
  struct Snapshot {
    Scenario scenario;
    Selection selection;
  };
  // Validates `next` and makes it current as one undo step.
  void Commit(Scenario next, const Selection& selection);
  void Changed();
  int TargetRobot() const;
  // The selected sensor module in `next` (a robot's or a loose one), or
  // throws DesignError.
  SensorModule& SelectedSensorModule(Scenario* next) const;
  // Mounts a ray on `face` of `sm`, or throws DesignError (not validated).
  static void AddRay(SensorModule* sm, int face);
  // The cameras of the selected sensor module or scene object in `next`
  // and its guid (the new cameras' guids start with it), or throws
  // DesignError.
  std::vector<Camera>& SelectedCameras(Scenario* next,
                                       std::string* owner_guid) const;
  // Mounts a camera on `face` of a part carrying `cameras`, or throws
  // DesignError (not validated).
  static void MountCamera(std::vector<Camera>* cameras,
                          const std::string& owner_guid, int face);

  Scenario scenario_;
  Selection selection_;
  std::string path_;
  std::string saved_text_;
  std::string note_;
  bool dirty_ = false;
  long revision_ = 0;
  std::vector<Snapshot> undo_;
  std::vector<Snapshot> redo_;
};

}  // namespace mrsim::studio
