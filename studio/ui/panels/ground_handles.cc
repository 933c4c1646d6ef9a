#include "studio/ui/panels/ground_handles.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "studio/design/chain_edit.h"
#include "studio/ui/panels/chain_drag.h"

namespace mrsim::studio {
namespace {

constexpr double kGrabPixels = 12;   // how near the cursor must be
constexpr double kSnapShift = 0.05;  // m, with Shift
constexpr double kSnapTurn = M_PI / 12;
constexpr double kFine = 0.1;  // with Ctrl

bool IsRobotPart(const Selection& s) {
  return s.kind == SelectionKind::kRobot || s.kind == SelectionKind::kModule ||
         s.kind == SelectionKind::kSensorModule;
}

// What the handles stand on: the pivot, the ring's radius and the heading.
struct Target {
  Eigen::Vector3d pivot = Eigen::Vector3d::Zero();
  double radius = 0.1;
  double heading = 0.0;
};

bool TargetOf(const Scenario& s, const Selection& sel, Target* t) {
  if (IsRobotPart(sel) && sel.robot >= 0 &&
      sel.robot < static_cast<int>(s.robots.size())) {
    const Robot& r = s.robots[sel.robot];
    if (r.modules.empty()) return false;
    t->pivot = RobotPivot(r);
    t->heading = RobotHeading(r);
    double far = 0;
    for (const Module& m : r.modules) {
      far = std::max(far, (m.position - t->pivot).head<2>().norm());
    }
    for (const SensorModule& m : r.sensor_modules) {
      far = std::max(far, (m.position - t->pivot).head<2>().norm());
    }
    t->radius = far + 0.08;
    return true;
  }
  const std::vector<Selection> loose = LooseGroup(s, sel);
  if (!loose.empty()) {
    t->pivot = LoosePivot(s, loose);
    const Selection& first = loose.front();
    const Eigen::Quaterniond q =
        first.kind == SelectionKind::kLooseFrame
            ? s.loose_frames.at(first.index).quat_rotation
            : s.loose_sensor_modules.at(first.index).quat_rotation;
    const Eigen::Vector3d x = q * Eigen::Vector3d::UnitX();
    t->heading = std::hypot(x.x(), x.y()) < 1e-9 ? 0 : std::atan2(x.y(), x.x());
    double far = 0;
    for (const Selection& p : loose) {
      const Eigen::Vector3d at =
          p.kind == SelectionKind::kLooseFrame
              ? s.loose_frames.at(p.index).position
              : s.loose_sensor_modules.at(p.index).position;
      far = std::max(far, (at - t->pivot).head<2>().norm());
    }
    t->radius = far + 0.08;
    return true;
  }
  if (sel.kind == SelectionKind::kSceneObject && sel.index >= 0 &&
      sel.index < static_cast<int>(s.scene_objects.size())) {
    const SceneObject& o = s.scene_objects[sel.index];
    t->pivot = o.position;
    const Eigen::Vector3d x = o.quat_rotation * Eigen::Vector3d::UnitX();
    t->heading = std::atan2(x.y(), x.x());
    t->radius = o.size.head<2>().norm() / 2 + 0.06;
    return true;
  }
  return false;
}

std::string Pixels(double x, double y) {
  char text[48];
  std::snprintf(text, sizeof(text), "%.0f %.0f", x, y);
  return text;
}

double Wrap(double a) { return std::remainder(a, 2 * M_PI); }

}  // namespace

bool GroundHandles::DropNewPart(StudioContext& studio, const mjrRect& view,
                                int window_height) {
  NextPart part;
  if (!DraggedNewPart(&part)) return false;
  // Said here too: an empty design has no chain rows to say it.
  studio.layout.State("drag", "new");
  const ImVec2 p = ImGui::GetMousePos();
  const double left = view.left,
               top = window_height - view.bottom - view.height;
  if (p.x < left || p.x >= left + view.width || p.y < top ||
      p.y >= top + view.height || !ImGui::IsMouseReleased(0)) {
    return false;
  }
  // Over a panel: the chain list's own targets take it.
  if (ImGui::GetIO().WantCaptureMouse &&
      ImGui::IsWindowHovered(ImGuiHoveredFlags_AnyWindow)) {
    return false;
  }
  Preview& preview = *studio.preview;
  const Selection hit = preview.Pick(view, p.x - left, p.y - top);
  if (hit.kind != SelectionKind::kModule &&
      hit.kind != SelectionKind::kSensorModule) {
    // No robot to drop it onto: the part starts one, as the palette's
    // buttons would.
    const std::vector<Robot>& robots = studio.design.scenario().robots;
    const bool no_robot =
        std::all_of(robots.begin(), robots.end(), [](const Robot& r) {
          return r.modules.empty() && r.sensor_modules.empty();
        });
    if (no_robot) {
      studio.Try("start a robot",
                 [&] { studio.design.InsertPart(part, 0, 0); });
    } else {
      studio.message = "drop it onto the robot, between two parts";
    }
    return true;
  }
  const Robot& robot = studio.design.scenario().robots.at(hit.robot);
  const std::vector<ChainSlot> slots = ChainOrder(robot);
  int place = -1;
  for (int i = 0; i < static_cast<int>(slots.size()); ++i) {
    if (slots[i].source == hit.index &&
        slots[i].sensor == (hit.kind == SelectionKind::kSensorModule)) {
      place = i;
    }
  }
  if (place < 0) return true;
  // In front of or behind the part: the side of the neighbour nearer the
  // cursor, along the chain as it appears on screen.
  std::vector<PartMarker> markers = preview.Markers(view, window_height);
  auto where = [&](int i, Eigen::Vector2d* at) {
    if (i < 0 || i >= static_cast<int>(slots.size())) return false;
    const Selection s{
        slots[i].sensor ? SelectionKind::kSensorModule : SelectionKind::kModule,
        hit.robot, slots[i].source};
    for (const PartMarker& m : markers) {
      if (m.part == s) {
        *at = Eigen::Vector2d(m.x, m.y);
        return true;
      }
    }
    return false;
  };
  Eigen::Vector2d here, next, previous;
  int at = place + 1;
  if (where(place, &here)) {
    const Eigen::Vector2d cursor(p.x, p.y);
    if (where(place + 1, &next)) {
      at = (cursor - here).dot(next - here) > 0 ? place + 1 : place;
    } else if (where(place - 1, &previous)) {
      at = (cursor - here).dot(previous - here) > 0 ? place : place + 1;
    }
  }
  studio.Try("insert the part",
             [&] { studio.design.InsertPart(part, hit.robot, at); });
  return true;
}

bool GroundHandles::Update(StudioContext& studio, const mjrRect& view,
                           int window_height) {
  if (DropNewPart(studio, view, window_height)) return true;
  Preview& preview = *studio.preview;
  const Design& design = studio.design;
  LayoutRecorder& layout = studio.layout;
  Target target;
  const bool shown = !preview.live() &&
                     TargetOf(design.scenario(), design.selection(), &target);
  if (!shown) {
    if (mode_ != Mode::kNone) preview.EndDrag();
    mode_ = Mode::kNone;
    return false;
  }
  const ImGuiIO& io = ImGui::GetIO();
  const double left = view.left;
  const double top = window_height - view.bottom - view.height;
  const ImVec2 mouse = io.MousePos;
  const Eigen::Vector2d cursor(mouse.x, mouse.y);

  // Where the handles are on screen (the design's pose, or the drag's).
  const Eigen::Isometry3d moved = GroundTransform(target.pivot, move_);
  const Eigen::Vector3d pivot =
      mode_ == Mode::kNone ? target.pivot : Eigen::Vector3d(moved * pivot_);
  const double heading =
      target.heading + (mode_ == Mode::kNone ? 0.0 : move_.turn);
  auto ring_point = [&](double angle) {
    return Eigen::Vector3d(
        pivot +
        target.radius * Eigen::Vector3d(std::cos(angle), std::sin(angle), 0));
  };
  double cx = 0, cy = 0, kx = 0, ky = 0;
  if (!preview.ScreenPoint(view, window_height, pivot, &cx, &cy) ||
      !preview.ScreenPoint(view, window_height, ring_point(heading), &kx,
                           &ky)) {
    return mode_ != Mode::kNone;
  }
  ImDrawList* draw = ImGui::GetBackgroundDrawList();
  draw->PushClipRect(ImVec2(static_cast<float>(left), static_cast<float>(top)),
                     ImVec2(static_cast<float>(left + view.width),
                            static_cast<float>(top + view.height)));
  std::vector<ImVec2> ring;
  for (int i = 0; i < 64; ++i) {
    double x = 0, y = 0;
    if (preview.ScreenPoint(view, window_height,
                            ring_point(heading + i * 2 * M_PI / 64), &x, &y)) {
      ring.emplace_back(static_cast<float>(x), static_cast<float>(y));
    }
  }
  const ImU32 ring_colour = mode_ == Mode::kTurn ? IM_COL32(255, 255, 120, 255)
                                                 : IM_COL32(90, 220, 255, 220);
  draw->AddPolyline(ring.data(), static_cast<int>(ring.size()), ring_colour,
                    ImDrawFlags_Closed, 2.0f);
  draw->AddCircleFilled(ImVec2(static_cast<float>(kx), static_cast<float>(ky)),
                        7, ring_colour);
  const ImU32 move_colour = mode_ == Mode::kMove ? IM_COL32(255, 255, 120, 255)
                                                 : IM_COL32(255, 255, 255, 230);
  draw->AddCircleFilled(ImVec2(static_cast<float>(cx), static_cast<float>(cy)),
                        8, move_colour);
  draw->AddCircle(ImVec2(static_cast<float>(cx), static_cast<float>(cy)), 9,
                  IM_COL32(0, 0, 0, 200), 0, 2.0f);
  draw->PopClipRect();

  if (layout.enabled()) {
    layout.State("handle move", Pixels(cx, cy));
    layout.State("handle turn", Pixels(kx, ky));
    // For tests: where 0.3 m along +x, and a quarter turn, are on screen.
    double x = 0, y = 0;
    if (preview.ScreenPoint(view, window_height,
                            pivot + Eigen::Vector3d(0.3, 0, 0), &x, &y)) {
      layout.State("handle +0.3x", Pixels(x, y));
    }
    if (preview.ScreenPoint(view, window_height, ring_point(heading + M_PI / 2),
                            &x, &y)) {
      layout.State("handle turn+90", Pixels(x, y));
    }
    layout.State("handle drag", mode_ == Mode::kMove   ? "move"
                                : mode_ == Mode::kTurn ? "turn"
                                                       : "none");
  }

  if (mode_ == Mode::kNone) {
    if (io.WantCaptureMouse || !ImGui::IsMouseClicked(0)) return false;
    const bool on_move =
        (cursor - Eigen::Vector2d(cx, cy)).norm() < kGrabPixels;
    bool on_ring = (cursor - Eigen::Vector2d(kx, ky)).norm() < kGrabPixels;
    for (size_t i = 0; i < ring.size() && !on_ring; ++i) {
      on_ring = (cursor - Eigen::Vector2d(ring[i].x, ring[i].y)).norm() < 6;
    }
    if (!on_move && !on_ring) return false;
    if (!preview.GroundPoint(view, window_height, mouse.x, mouse.y,
                             target.pivot.z(), &grab_)) {
      return false;
    }
    mode_ = on_move ? Mode::kMove : Mode::kTurn;
    what_ = design.selection();
    loose_group_ = LooseGroup(design.scenario(), what_);
    pivot_ = target.pivot;
    grab_angle_ = std::atan2(grab_.y() - pivot_.y(), grab_.x() - pivot_.x());
    move_ = GroundMove();
    return true;
  }

  // Dragging.
  Eigen::Vector3d at;
  if (preview.GroundPoint(view, window_height, mouse.x, mouse.y, pivot_.z(),
                          &at)) {
    const double scale = io.KeyCtrl ? kFine : 1.0;
    move_ = GroundMove();
    if (mode_ == Mode::kMove) {
      move_.shift = (at - grab_).head<2>() * scale;
      if (io.KeyShift) {
        move_.shift = (move_.shift / kSnapShift).array().round() * kSnapShift;
      }
    } else {
      move_.turn = Wrap(std::atan2(at.y() - pivot_.y(), at.x() - pivot_.x()) -
                        grab_angle_) *
                   scale;
      if (io.KeyShift)
        move_.turn = std::round(move_.turn / kSnapTurn) * kSnapTurn;
    }
    preview.ShowDrag(what_, GroundTransform(pivot_, move_), loose_group_);
    char text[96];
    std::snprintf(text, sizeof(text), "moving: %+.3f m, %+.3f m, %+.1f deg",
                  move_.shift.x(), move_.shift.y(), move_.turn * 180 / M_PI);
    studio.message = text;
    studio.message_is_error = false;
  }
  if (!ImGui::IsMouseDown(0)) {
    const GroundMove move = move_;
    const Selection what = what_;
    mode_ = Mode::kNone;
    move_ = GroundMove();
    preview.EndDrag();
    if (!move.empty()) {
      const char* moving = what.kind == SelectionKind::kSceneObject
                               ? "move the object"
                           : loose_group_.empty() ? "move the robot"
                                                  : "move the loose parts";
      studio.Try(moving, [&] { studio.design.MoveOnGround(what, move); });
    }
  }
  return true;
}

}  // namespace mrsim::studio
