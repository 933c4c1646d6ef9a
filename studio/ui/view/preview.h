// The studio's 3-D view: the MuJoCo model the physics builds from the
// design (sim_core Physics, so the same BuildMjcf, whose look gives the
// colours per kind of part, checker floor and sky), drawn with MuJoCo's
// renderer with module numbers and distance-sensor rays; orbit/pan/zoom
// and click-to-select as in mujoco-simulate. Needs a current OpenGL context.
#pragma once

#include <mujoco/mujoco.h>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "sim_core/physics/physics.h"
#include "sim_core/physics/scene_object_state.h"
#include "sim_core/scenario/robot_state.h"
#include "sim_core/scenario/scenario.h"
#include "studio/design/selection.h"
#include "studio/ui/view/part_map.h"
#include "viewer/renderer.h"

namespace mrsim {
class StatePoseMapper;
}

namespace mrsim::studio {

// Where a chain part appears in the window (pixels from the top left).
struct PartMarker {
  Selection part;
  double x = 0;
  double y = 0;
};

class Preview {
 public:
  // The off-screen buffer (for screenshots) is at least width x height.
  Preview(int width, int height);
  ~Preview();
  Preview(const Preview&) = delete;
  Preview& operator=(const Preview&) = delete;

  // Builds the model of `scenario`; on failure keeps the previous model and
  // returns the error ("" on success). Frames the camera on the first model,
  // and again when parts come or go until the user moves the camera (a
  // robot growing module by module stays in view).
  std::string Rebuild(const Scenario& scenario);
  bool has_model() const { return physics_ != nullptr; }
  // The model drawn (null before the first successful Rebuild).
  const mjModel* model() const {
    return physics_ ? physics_->model() : nullptr;
  }
  // The poses drawn (the design's, or a live run's after ShowStates); null
  // before the first successful Rebuild.
  mjData* data() { return data_; }
  // Grows by one on every successful Rebuild (a new model()).
  long builds() const { return builds_; }

  // Binds the window (or off-screen) framebuffer for drawing.
  void Bind(bool offscreen);
  // Draws into the window (or the off-screen buffer) inside `viewport`
  // (OpenGL pixels, origin bottom left).
  void Render(const mjrRect& viewport, bool offscreen,
              const Selection& selected);
  // Reads the whole off-screen buffer (RGB, bottom row first).
  void ReadPixels(int width, int height, std::vector<unsigned char>* rgb);

  // Mouse: dx, dy as fractions of the viewport height (as simulate does).
  void Orbit(double dx, double dy);
  void Pan(double dx, double dy);
  void Zoom(double amount);
  // Frames the whole scene (at the next render when first built).
  void FrameAll();
  void Reframe() { framed_ = false; }
  // The part under (x, y), viewport pixels from its top left.
  Selection Pick(const mjrRect& viewport, double x, double y) const;
  // Where each lock's marker is now (world), with the lock it stands for:
  // Pick takes a click on one, and window tests find them by it.
  std::vector<std::pair<Selection, Eigen::Vector3d>> LockPoints() const;
  // Module and sensor module centres and lock markers in window pixels
  // (top-left origin) for a window of height window_height.
  std::vector<PartMarker> Markers(const mjrRect& viewport,
                                  int window_height) const;

  // Dragging on the ground (ground_handles.h): the part `what` names (a
  // whole robot for a robot, module or sensor module; an object; for a
  // loose part, the parts of `loose_group`, ground_move.h's LooseGroup)
  // drawn moved by `transform`, no rebuild; EndDrag puts it back where the
  // design has it (the rebuild after the edit shows the moved design).
  void ShowDrag(const Selection& what, const Eigen::Isometry3d& transform,
                const std::vector<Selection>& loose_group = {});
  void EndDrag();
  // The point on the horizontal plane at height `z` under window pixel
  // (x, y) (top-left origin, window of height window_height), as the last
  // frame's camera sees it; false when the ray misses the plane.
  bool GroundPoint(const mjrRect& viewport, int window_height, double x,
                   double y, double z, Eigen::Vector3d* point) const;
  // Where a world point appears in the window (top-left origin); false
  // when it is behind the camera.
  bool ScreenPoint(const mjrRect& viewport, int window_height,
                   const Eigen::Vector3d& world, double* x, double* y) const;

  // Live view: poses the robots named in `states` (and the movable objects
  // in `scene`, when given) as a running simulation reports them, with the
  // viewer's StatePoseMapper, their distance rays at the measured length
  // (MeasuredRays). States that do not fit the design are left as built.
  // ShowDesign returns to the design's own pose (after every rebuild too).
  void ShowStates(const Scenario& scenario,
                  const std::map<std::string, RobotState>& states,
                  const std::vector<SceneObjectState>* scene);
  void ShowDesign();
  bool live() const { return live_; }
  // Live: the camera moves with the robots' mean centre of mass, as
  // simulate's tracking camera does, keeping the user's orbit, pan and zoom
  // (a fast robot otherwise leaves the view within seconds).
  void SetTracking(bool on) { tracking_ = on; }
  const mjvCamera& camera() const { return camera_; }

  // Bodies drawn red (parts overlapping at the start, overlap_check.h);
  // MuJoCo body ids of the current model.
  void SetFlaggedBodies(std::vector<int> bodies) {
    flagged_ = std::move(bodies);
  }

 private:
  void AddRays();
  // A small marker on each lock, brighter when selected.
  void AddLocks(const Selection& selected);

  int width_;
  int height_;
  std::unique_ptr<Physics> physics_;
  mjData* data_ = nullptr;  // owned by physics_
  long builds_ = 0;
  std::vector<GeomPart> geoms_;
  std::vector<int> flagged_;
  std::vector<RaySite> rays_;
  std::vector<LockSite> locks_;
  // Live: the measured rays, and which robots they stand for (the others
  // keep their designed rays).
  std::vector<Ray> live_rays_;
  std::vector<bool> live_robots_;
  std::vector<std::pair<int, std::string>> labels_;  // geom id, text
  mjvScene scene_;
  mjvOption option_;
  mjvCamera camera_;
  mjrContext context_;
  bool framed_ = false;
  bool camera_moved_ = false;  // by the user since the last FrameAll
  std::unique_ptr<StatePoseMapper> mapper_;  // for the current model
  bool live_ = false;
  bool dragging_ = false;          // ShowDrag moved geoms away from the design
  std::vector<double> drag_xpos_;  // the design's geom poses at its start
  std::vector<double> drag_xmat_;
  bool tracking_ = true;
  bool tracked_ = false;  // tracked_centre_ holds the last frame's centre
  Eigen::Vector3d tracked_centre_ = Eigen::Vector3d::Zero();
  double aspect_ = 1.0;
  bool software_ = false;  // llvmpipe: no MSAA, no shadows
  bool context_made_ = false;
  size_t upload_key_ = 0;  // what the context holds (UploadKey)
};

}  // namespace mrsim::studio
