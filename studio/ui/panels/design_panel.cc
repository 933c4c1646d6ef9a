#include "studio/ui/panels/design_panel.h"

#include <imgui.h>

#include <string>

#include "sim_core/scenario/part_look.h"
#include "studio/design/chain_edit.h"
#include "studio/ui/dialogs/print_section.h"
#include "studio/ui/panels/chain_drag.h"
#include "studio/ui/widgets/panel_background.h"
#include "studio/ui/widgets/widgets.h"

namespace mrsim::studio {
namespace {

// The colour the preview shows a kind of part in (the MJCF look's hue).
ImVec4 Swatch(Look look) {
  PartLook kind = PartLook::kLooseFrame;
  switch (look) {
    case Look::kPitchModule:
      kind = PartLook::kPitchModule;
      break;
    case Look::kYawModule:
      kind = PartLook::kYawModule;
      break;
    case Look::kSensorModule:
      kind = PartLook::kSensorModule;
      break;
    case Look::kForcePlate:
      kind = PartLook::kForcePlate;
      break;
    case Look::kDistanceSensor:
      kind = PartLook::kDistanceSensor;
      break;
    case Look::kObject:
      kind = PartLook::kSceneObject;
      break;
    default:
      break;
  }
  const Eigen::Vector3d c = PartLookRgb(kind);
  return ImVec4(static_cast<float>(c.x()), static_cast<float>(c.y()),
                static_cast<float>(c.z()), 1.0f);
}

}  // namespace

void DesignPanel::ScrollToNewSelection(StudioContext& studio,
                                       const Selection& row) {
  if (studio.design.selection() != row || scrolled_to_ == row) return;
  ImGui::SetScrollHereY(0.5f);
  scrolled_to_ = row;
}

void DesignPanel::Draw(StudioContext& studio, const PanelRect& rect) {
  const float x = rect.x, y = rect.y, w = rect.w, h = rect.h;
  ImGui::SetNextWindowPos(ImVec2(x, y));
  ImGui::SetNextWindowSize(ImVec2(w, h));
  SkipPanelBackground();
  ImGui::Begin("Design", nullptr, kPanelFlags);
  const float third = (w - 32) / 3;
  if (studio.Button("New", third / 1.5f)) studio.Guard(Pending::kNew);
  ImGui::SameLine();
  if (studio.Button("Open", third / 1.5f)) studio.Guard(Pending::kOpen);
  ImGui::SameLine();
  if (studio.Button("Save", third / 1.5f)) studio.SaveFile();
  ImGui::SameLine();
  if (studio.Button("Save As", third / 1.5f + 4)) {
    studio.BrowseSaveAs();
  }
  ImGui::Checkbox("Embed terrain and meshes", &studio.embed_on_save);
  studio.Record("embed on save");
  if (ImGui::IsItemHovered()) {
    ImGui::SetTooltip(
        "Save writes the height image and mesh files into the design "
        "(base64), so it opens and runs on another computer alone");
  }
  if (studio.Button("Undo", third)) studio.design.Undo();
  ImGui::SameLine();
  if (studio.Button("Redo", third)) studio.design.Redo();
  ImGui::SameLine();
  if (studio.Button("Help (F1)", third)) studio.show_help = !studio.show_help;
  if (studio.Button("New robot from template...", -1))
    studio.Guard(Pending::kTemplate);
  if (!studio.recent.paths().empty() &&
      ImGui::CollapsingHeader("Recent files")) {
    for (const std::string& p : studio.recent.paths()) {
      if (ImGui::Selectable(p.c_str())) {
        studio.pending_path = p;
        if (studio.design.dirty()) {
          studio.pending = Pending::kOpen;
          studio.ask_unsaved = true;
        } else {
          studio.OpenFile(p);
        }
      }
    }
  }

  ImGui::Separator();
  ImGui::TextUnformatted("Next part");
  int where = static_cast<int>(where_);
  ImGui::RadioButton("after selected", &where, 0);
  ImGui::SameLine();
  ImGui::RadioButton("front", &where, 1);
  ImGui::SameLine();
  ImGui::RadioButton("tail", &where, 2);
  where_ = static_cast<Where>(where);
  const struct {
    const char* label;
    NextPart part;
    Look look;
  } parts[] = {{"pitch module", NextPart::kPitchModule, Look::kPitchModule},
               {"yaw module", NextPart::kYawModule, Look::kYawModule},
               {"sensor module", NextPart::kSensorModule, Look::kSensorModule}};
  for (const auto& p : parts) {
    ImGui::PushStyleColor(ImGuiCol_Button, Swatch(p.look));
    ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(0, 0, 0, 1));
    if (studio.Button(p.label, third)) {
      studio.Try(std::string("add the ") + p.label,
                 [&] { studio.design.AddPart(p.part, where_); });
    }
    PaletteDragSource(p.part, p.label);
    ImGui::PopStyleColor(2);
    if (&p != &parts[2]) ImGui::SameLine();
  }
  if (studio.Button("another robot", third)) {
    studio.Try("add a robot", [&] { studio.design.AddRobot(); });
  }
  ImGui::SameLine();
  // Parts without a robot, beside the robots: a frame, a hinge (two
  // frames and their joint) or a sensor module.
  if (studio.Button("Add loose part...", 2 * third + 4)) {
    ImGui::OpenPopup("add loose part");
  }
  if (ImGui::BeginPopup("add loose part")) {
    const struct {
      const char* label;
      LoosePart part;
    } looses[] = {{"loose frame", LoosePart::kFrame},
                  {"loose hinge (two frames)", LoosePart::kHinge},
                  {"loose sensor module", LoosePart::kSensorModule}};
    for (const auto& l : looses) {
      if (ImGui::Selectable(l.label)) {
        studio.Try(std::string("add a ") + l.label,
                   [&] { studio.design.AddLoose(l.part); });
      }
      studio.Record(l.label);
    }
    ImGui::EndPopup();
  }

  // The chain, front to back. Rows are written in their part's colour, so
  // the selection is marked in grey: ImGui's blue would hide a blue yaw
  // row.
  ImGui::BeginChild("parts", ImVec2(0, h * 0.28f), true);
  ImGui::PushStyleColor(ImGuiCol_Header, ImVec4(0.32f, 0.33f, 0.36f, 1));
  ImGui::PushStyleColor(ImGuiCol_HeaderHovered, ImVec4(0.25f, 0.26f, 0.28f, 1));
  ImGui::PushStyleColor(ImGuiCol_HeaderActive, ImVec4(0.40f, 0.41f, 0.44f, 1));
  const Scenario& s = studio.design.scenario();
  for (int r = 0; r < static_cast<int>(s.robots.size()); ++r) {
    const Robot& robot = s.robots[r];
    const Selection robot_sel{SelectionKind::kRobot, r, 0};
    if (ImGui::Selectable(("robot " + robot.name).c_str(),
                          studio.design.selection() == robot_sel)) {
      studio.design.Select(robot_sel);
    }
    studio.Record("row robot " + std::to_string(r));
    int place = 0;
    for (const ChainSlot& slot : ChainOrder(robot)) {
      const Selection sel{
          slot.sensor ? SelectionKind::kSensorModule : SelectionKind::kModule,
          r, slot.source};
      std::string label;
      Look look;
      if (slot.sensor) {
        const SensorModule& sm = robot.sensor_modules[slot.source];
        label = "  S" + std::to_string(slot.source) + "  sensor module" +
                (sm.force_sensor ? " +plate" : "") +
                (sm.distance_sensors.empty() ? "" : " +ray") +
                (sm.cameras.empty() ? "" : " +cam");
        look = Look::kSensorModule;
      } else {
        label = "  " + std::to_string(slot.source) + "  " +
                (slot.axis == Axis::kPitch ? "pitch" : "yaw") + " module";
        look =
            slot.axis == Axis::kPitch ? Look::kPitchModule : Look::kYawModule;
      }
      ImGui::PushStyleColor(ImGuiCol_Text, Swatch(look));
      if (ImGui::Selectable(label.c_str(), studio.design.selection() == sel)) {
        studio.design.Select(sel);
      }
      ImGui::PopStyleColor();
      studio.Record("row " + std::string(ToString(sel.kind)) + " " +
                    std::to_string(r) + " " + std::to_string(sel.index));
      ChainRowDragDrop(studio, r, place++, label.c_str());
    }
    // Its locks, each named by the parts it joins: selected here, edited
    // and detached in the inspector.
    const std::vector<LockEnd> ends = studio.design.LockEnds(r);
    auto end_name = [&](const std::string& guid) {
      for (const LockEnd& e : ends) {
        if (e.guid == guid) return e.name;
      }
      return guid;
    };
    ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(0.7f, 0.7f, 0.7f, 1));
    for (int k = 0; k < static_cast<int>(robot.locks.size()); ++k) {
      const Joint& lock = robot.locks[k];
      const Selection sel{SelectionKind::kLock, r, k};
      const std::string label =
          "    " +
          std::string(IsChainLock(robot, lock) ? "lock " : "loop lock ") +
          std::to_string(k) + ": " + end_name(lock.left_frame_guid) + " + " +
          end_name(lock.right_frame_guid) +
          (lock.break_force > 0 ? " (breaks)" : "") + "##lock" +
          std::to_string(r) + "_" + std::to_string(k);
      if (ImGui::Selectable(label.c_str(), studio.design.selection() == sel)) {
        studio.design.Select(sel);
      }
      ScrollToNewSelection(studio, sel);
      studio.Record("row lock " + std::to_string(r) + " " + std::to_string(k));
    }
    ImGui::PopStyleColor();
  }
  // Parts without a robot.
  const struct {
    SelectionKind kind;
    size_t count;
    const char* name;
  } loose[] = {{SelectionKind::kLooseFrame, s.loose_frames.size(), "frame"},
               {SelectionKind::kLooseJoint, s.loose_joints.size(), "joint"},
               {SelectionKind::kLooseSensorModule,
                s.loose_sensor_modules.size(), "sensor module"}};
  for (const auto& group : loose) {
    for (int i = 0; i < static_cast<int>(group.count); ++i) {
      const Selection sel{group.kind, 0, i};
      std::string guid;
      if (group.kind == SelectionKind::kLooseFrame)
        guid = s.loose_frames[i].guid;
      if (group.kind == SelectionKind::kLooseJoint) {
        const Joint& j = s.loose_joints[i];
        guid = j.guid + " (" + ToString(j.type) + ")";
      }
      if (group.kind == SelectionKind::kLooseSensorModule) {
        guid = s.loose_sensor_modules[i].guid;
      }
      const std::string label = "  loose " + std::string(group.name) + " " +
                                guid + "##" + ToString(group.kind) +
                                std::to_string(i);
      if (ImGui::Selectable(label.c_str(), studio.design.selection() == sel)) {
        studio.design.Select(sel);
      }
      ScrollToNewSelection(studio, sel);
      studio.Record("row " + std::string(ToString(group.kind)) + " " +
                    std::to_string(i));
    }
  }
  if (s.robots.empty()) {
    ImGui::TextWrapped(
        "No robot yet: add a pitch or yaw module, or drag one into the 3-D "
        "view.");
  }
  ImGui::PopStyleColor(3);
  ImGui::EndChild();
  if (studio.Button("Move to front", third)) {
    studio.Try("move the part to the front",
               [&] { studio.design.MoveSelected(-1); });
  }
  ImGui::SameLine();
  if (studio.Button("Move to back", third)) {
    studio.Try("move the part to the back",
               [&] { studio.design.MoveSelected(1); });
  }
  ImGui::SameLine();
  if (studio.Button("Remove", third)) {
    studio.Try("remove the part", [&] { studio.design.RemoveSelected(); });
  }

  ImGui::Separator();
  ImGui::TextUnformatted("Add object (in front of the robot)");
  const struct {
    const char* label;
    ObjectKind kind;
  } objects[] = {{"ball", ObjectKind::kBall},
                 {"box", ObjectKind::kBox},
                 {"cylinder", ObjectKind::kCylinder},
                 {"capsule", ObjectKind::kCapsule},
                 {"ramp", ObjectKind::kRamp}};
  const float fifth = (w - 40) / 5;
  for (const auto& o : objects) {
    if (studio.Button(o.label, fifth)) {
      studio.Try(std::string("add a ") + o.label,
                 [&] { studio.design.AddObject(o.kind); });
    }
    if (&o != &objects[4]) ImGui::SameLine();
  }
  for (int i = 0; i < static_cast<int>(s.scene_objects.size()); ++i) {
    const Selection sel{SelectionKind::kSceneObject, 0, i};
    const SceneObject& o = s.scene_objects[i];
    ImGui::PushStyleColor(ImGuiCol_Text, Swatch(Look::kObject));
    if (ImGui::Selectable(
            ("  " + o.guid + " (" + ToString(o.shape) + ")").c_str(),
            studio.design.selection() == sel)) {
      studio.design.Select(sel);
    }
    studio.Record("row object " + std::to_string(i));
    ImGui::PopStyleColor();
  }

  ImGui::Separator();
  ImGui::TextUnformatted("World");
  if (studio.Button("Terrain", third))
    studio.design.Select({SelectionKind::kScene, 0, 0});
  ImGui::SameLine();
  if (studio.Button("flat ground", third)) {
    studio.Try([&] {
      studio.design.SetTerrain("", 0.0,
                               studio.design.scenario().scene.meters_per_pixel);
    });
  }
  ImGui::SameLine();
  if (studio.Button("height image...", third)) {
    studio.browse_for = BrowseFor::kHeightImage;
    studio.browser.Open("Height image (grey PNG)", studio.StartFolder(), ".png",
                        false);
  }
  if (studio.Button("water", third)) {
    studio.Try("add water", [&] { studio.design.AddFluid(FluidKind::kWater); });
  }
  ImGui::SameLine();
  if (studio.Button("air", third)) {
    studio.Try("add air", [&] { studio.design.AddFluid(FluidKind::kAir); });
  }
  ImGui::SameLine();
  if (studio.Button("contact pair", third)) {
    studio.Try("add a contact pair", [&] { studio.design.AddContact(); });
  }
  for (int i = 0; i < static_cast<int>(s.fluid_regions.size()); ++i) {
    const Selection sel{SelectionKind::kFluidRegion, 0, i};
    if (ImGui::Selectable(("  " + s.fluid_regions[i].guid).c_str(),
                          studio.design.selection() == sel)) {
      studio.design.Select(sel);
    }
  }
  for (int i = 0; i < static_cast<int>(s.contact_frictions.size()); ++i) {
    const Selection sel{SelectionKind::kContactFriction, 0, i};
    const ContactFriction& c = s.contact_frictions[i];
    if (ImGui::Selectable(("  contact " + c.material1 + " / " + c.material2 +
                           "##" + std::to_string(i))
                              .c_str(),
                          studio.design.selection() == sel)) {
      studio.design.Select(sel);
    }
  }
  DrawPrintSection(studio);
  if (studio.Button("Simulation settings", -1)) {
    studio.design.Select({SelectionKind::kSettings, 0, 0});
  }
  ImGui::End();
}

}  // namespace mrsim::studio
