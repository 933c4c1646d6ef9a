// The 3-D view's handles for placing things on the ground: a move handle
// (a disc at the centre of the selected robot, object or loose part, a
// loose part with every loose part joined to it; drag it to slide it) and a
// heading ring around it (drag its knob to turn it). Ctrl makes a drag ten
// times finer, Shift snaps to 5 cm and 15 degrees. While dragging only the
// drawn poses change (Preview::ShowDrag, no rebuild); the release is one edit
// (Design::MoveOnGround), one undo step. Also takes a pitch, yaw or sensor
// module dragged from the palette and dropped onto the robot: it lands between
// the part under the cursor and its neighbour nearer the cursor
// (Design::InsertPart). With no robot in the design, a module dropped anywhere
// in the view starts one.
#pragma once

#include <mujoco/mujoco.h>

#include <Eigen/Core>
#include <vector>

#include "studio/design/ground_move.h"
#include "studio/design/selection.h"
#include "studio/ui/studio_context.h"

namespace mrsim::studio {

class GroundHandles {
 public:
  // Once a frame, before the view's own mouse handling: draws the handles
  // over `view` (OpenGL viewport of a window `window_height` high) and
  // takes the mouse on them; true while it has the mouse (no orbit).
  bool Update(StudioContext& studio, const mjrRect& view, int window_height);

 private:
  enum class Mode { kNone, kMove, kTurn };
  bool DropNewPart(StudioContext& studio, const mjrRect& view,
                   int window_height);

  Mode mode_ = Mode::kNone;
  Selection what_;
  std::vector<Selection> loose_group_;  // the loose parts what_ drags along
  Eigen::Vector3d pivot_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d grab_ = Eigen::Vector3d::Zero();
  double grab_angle_ = 0.0;
  GroundMove move_;
};

}  // namespace mrsim::studio
