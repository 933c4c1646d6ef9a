#include "studio/ui/panels/inspector_panel.h"

#include <imgui.h>
#include <imgui_stdlib.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include "sim_core/mesh/embedded_mesh.h"
#include "sim_core/scenario/sensor_face.h"
#include "sim_core/scenario/sensor_kind.h"
#include "studio/design/chain_edit.h"
#include "studio/design/euler_degrees.h"
#include "studio/design/inert_fields.h"
#include "studio/design/inspector_fields.h"
#include "studio/ui/widgets/panel_background.h"
#include "studio/ui/widgets/widgets.h"

namespace mrsim::studio {
namespace {

std::string Key(const Selection& s, const std::string& sub,
                const std::string& field) {
  return std::string(ToString(s.kind)) + " " + std::to_string(s.robot) + " " +
         std::to_string(s.index) + "/" + sub + "/" + field;
}

// The refusal of what was typed into the field `key`, in red under it.
void DrawFieldError(const std::map<std::string, std::string>& errors,
                    const std::string& key) {
  auto error = errors.find(key);
  if (error == errors.end()) return;
  ImGui::PushTextWrapPos(0);
  ImGui::TextColored(ImVec4(1, 0.35f, 0.35f, 1), "%s", error->second.c_str());
  ImGui::PopTextWrapPos();
}

// A combo labelled `label` picking one of `ends` into *index (kept in
// range), recorded for the layout dump as `record`.
void PickEnd(StudioContext& studio, const char* label,
             const std::string& record, const std::vector<LockEnd>& ends,
             int* index) {
  *index = std::clamp(*index, 0, static_cast<int>(ends.size()) - 1);
  ImGui::TextDisabled("%s", label);
  ImGui::SameLine(60);
  ImGui::SetNextItemWidth(-1);
  const std::string id = "##" + record;
  if (ImGui::BeginCombo(id.c_str(), ends[*index].name.c_str())) {
    for (int k = 0; k < static_cast<int>(ends.size()); ++k) {
      if (ImGui::Selectable(ends[k].name.c_str(), k == *index)) *index = k;
    }
    ImGui::EndCombo();
  }
  studio.Record(record);
}

}  // namespace

void InspectorPanel::Draw(StudioContext& studio, const PanelRect& rect) {
  const float x = rect.x, y = rect.y, w = rect.w, h = rect.h;
  ImGui::SetNextWindowPos(ImVec2(x, y));
  ImGui::SetNextWindowSize(ImVec2(w, h));
  SkipPanelBackground();
  ImGui::Begin("Inspector", nullptr, kPanelFlags);
  Scenario view = studio.design.scenario();
  const Selection sel = studio.design.selection();
  if (studio.design.revision() != fields_revision_ ||
      sel != fields_selection_) {
    // What was refused belongs to the design and part it was typed for.
    field_errors_.clear();
    field_edits_.clear();
    fields_revision_ = studio.design.revision();
    fields_selection_ = sel;
  }
  const std::vector<FieldGroup> groups = InspectorFields(view, sel);
  if (groups.empty()) {
    ImGui::TextWrapped(
        "Select a part in the list or click it in the 3-D view to see and "
        "edit every field.");
  }
  if (sel.kind == SelectionKind::kSensorModule ||
      sel.kind == SelectionKind::kLooseSensorModule) {
    DrawSensorMounts(studio, view, sel);
  }
  if (sel.kind == SelectionKind::kLock && !groups.empty()) {
    DrawLock(studio, view, sel);
  }
  if ((sel.kind == SelectionKind::kModule ||
       sel.kind == SelectionKind::kSensorModule) &&
      !groups.empty()) {
    DrawAttach(studio, view, sel);
  }
  if ((sel.kind == SelectionKind::kLooseFrame ||
       sel.kind == SelectionKind::kLooseSensorModule) &&
      !groups.empty()) {
    DrawLooseJoin(studio, view, sel);
  }
  if (sel.kind == SelectionKind::kLooseJoint && !groups.empty()) {
    DrawLooseJoint(studio, view, sel);
  }
  if (sel.kind == SelectionKind::kSceneObject && sel.index >= 0 &&
      sel.index < static_cast<int>(view.scene_objects.size())) {
    DrawCameras(studio, view.scene_objects[sel.index].cameras, sel);
    ImGui::Separator();
  }
  for (const FieldGroup& g : groups) {
    if (!ImGui::CollapsingHeader(g.title.c_str(),
                                 ImGuiTreeNodeFlags_DefaultOpen)) {
      continue;
    }
    ImGui::PushID(g.sub.c_str());
    for (const FieldRef& f : g.fields) {
      const FieldInfo& info = f.info();
      const std::string key = Key(sel, g.sub, info.xml);
      const FieldAddress address{sel, g.sub, info.xml};
      // Shown as degrees (DrawEulerDegrees), though the file keeps a
      // quaternion.
      const std::string label =
          FieldLabel(info) +
          (f.type() == FieldType::kQuaternion && !info.kept ? " (deg)" : "");
      ImGui::PushID(info.xml);
      ImGui::TextUnformatted(label.c_str());
      if (ImGui::IsItemHovered()) WrappedTooltip(FieldTooltip(info));
      ImGui::SameLine(w * 0.5f);
      ImGui::SetNextItemWidth(-1);
      const bool numbers = f.type() == FieldType::kNumber ||
                           f.type() == FieldType::kVector ||
                           f.type() == FieldType::kQuaternion;
      const std::string current =
          numbers ? ShortNumbers(f.GetText()) : f.GetText();
      if (*info.limits.meaning) {
        // An integer range whose values have names (a face): picked by
        // name, from the schema's own list.
        std::vector<std::string> names;
        std::stringstream meaning(info.limits.meaning);
        for (std::string n; std::getline(meaning, n, ',');) {
          names.push_back(n.substr(n.find_first_not_of(' ')));
        }
        const int value = std::atoi(current.c_str());
        const auto name_of = [&](int k) {
          const int i = k - static_cast<int>(info.limits.min);
          return std::to_string(k) +
                 (i >= 0 && i < static_cast<int>(names.size()) ? " " + names[i]
                                                               : "");
        };
        if (ImGui::BeginCombo("##v", name_of(value).c_str())) {
          for (int k = static_cast<int>(info.limits.min);
               k <= static_cast<int>(info.limits.max); ++k) {
            if (ImGui::Selectable(name_of(k).c_str(), k == value)) {
              studio.Try(
                  [&] { studio.design.SetField(address, std::to_string(k)); });
            }
          }
          ImGui::EndCombo();
        }
      } else if (info.kept) {
        ImGui::TextDisabled("%s", current.c_str());
      } else if (IsEmbeddedMesh(current)) {
        // Its bytes are no text to edit; the Print section's Mesh buttons
        // replace it.
        ImGui::TextUnformatted(ShapeSummary(current).c_str());
        if (ImGui::IsItemHovered()) {
          WrappedTooltip(
              "A mesh carried inside the design file (Embed terrain and "
              "meshes). The Print section's \"Mesh for module...\" "
              "replaces it.");
        }
      } else if (f.type() == FieldType::kBool) {
        bool on = current == "true";
        if (ImGui::Checkbox("##v", &on)) {
          studio.Try(
              [&] { studio.design.SetField(address, on ? "true" : "false"); });
        }
      } else if (f.type() == FieldType::kChoice) {
        if (ImGui::BeginCombo("##v", current.c_str())) {
          for (const std::string& c : f.choices()) {
            if (ImGui::Selectable(c.c_str(), c == current)) {
              studio.Try([&] { studio.design.SetField(address, c); });
            }
          }
          ImGui::EndCombo();
        }
      } else if (f.type() == FieldType::kQuaternion) {
        DrawEulerDegrees(studio, f, address, key, w * 0.5f);
      } else if (sel.kind == SelectionKind::kSceneObject && g.sub.empty() &&
                 std::string(info.xml) == "size") {
        DrawObjectSize(studio, view.scene_objects.at(sel.index), address, key,
                       w * 0.5f);
      } else {
        TextField(
            key, current, [&](const std::string& text) { f.SetText(text); },
            [&](const std::string& text) {
              studio.design.SetField(address, text);
            });
      }
      // A quaternion and an object's size record their rows themselves.
      const bool own_rows =
          (f.type() == FieldType::kQuaternion && !info.kept) ||
          (sel.kind == SelectionKind::kSceneObject && g.sub.empty() &&
           std::string(info.xml) == "size");
      if (!own_rows) {
        studio.Record("field " + g.sub + "/" + info.xml);
      }
      DrawFieldError(field_errors_, key);
      ImGui::PopID();
    }
    ImGui::PopID();
  }
  ImGui::End();
}

bool InspectorPanel::TextField(
    const std::string& key, const std::string& current,
    const std::function<void(const std::string&)>& check,
    const std::function<void(const std::string&)>& apply) {
  auto edit = field_edits_.find(key);
  std::string text = edit != field_edits_.end() ? edit->second : current;
  const bool enter = ImGui::InputText(
      "##v", &text,
      ImGuiInputTextFlags_EnterReturnsTrue | ImGuiInputTextFlags_AutoSelectAll);
  const bool active = ImGui::IsItemActive();
  if (active) {
    field_edits_[key] = text;
    // Checked as typed against the schema on a scratch copy.
    try {
      check(text);
      field_errors_.erase(key);
    } catch (const std::exception& e) {
      field_errors_[key] = e.what();
    }
  }
  if (enter || ImGui::IsItemDeactivatedAfterEdit()) {
    // Refused: the field shows the design's value again, so what is on
    // screen is what is saved and run.
    field_edits_.erase(key);
    try {
      apply(text);
      field_errors_.erase(key);
      return true;
    } catch (const std::exception& e) {
      field_errors_[key] = "not applied, still " + current + ": " + e.what();
    }
  } else if (!active && field_edits_.erase(key) > 0) {
    field_errors_.erase(key);  // typing abandoned (Escape)
  }
  return false;
}

void InspectorPanel::DrawEulerDegrees(StudioContext& studio, const FieldRef& f,
                                      const FieldAddress& address,
                                      const std::string& key, float left) {
  // Degrees are what a student thinks in; the quaternion the file keeps
  // (x y z w there, w x y z in messages) is written from them.
  const Eigen::Quaterniond stored = *std::get<Eigen::Quaterniond*>(f.value());
  const Eigen::Vector3d rpy = EulerDegreesFromQuaternion(stored);
  static constexpr const char* kAxes[3] = {"roll", "pitch", "yaw"};
  const float width = ImGui::GetContentRegionAvail().x;
  for (int k = 0; k < 3; ++k) {
    ImGui::PushID(k);
    if (k > 0) ImGui::SetCursorPosX(left);
    ImGui::TextDisabled("%s", kAxes[k]);
    if (ImGui::IsItemHovered()) WrappedTooltip(kEulerConvention);
    ImGui::SameLine(left + 50);
    ImGui::SetNextItemWidth(width - 50);
    const std::string component_key = key + " " + kAxes[k];
    const auto with = [&](const std::string& text) {
      Eigen::Vector3d next = rpy;
      next[k] = ParseNumber(text);
      if (!std::isfinite(next[k])) throw FieldError("expected a number");
      return next;
    };
    TextField(
        component_key, ShortNumbers(FormatNumber(rpy[k])),
        [&](const std::string& text) { with(text); },
        [&](const std::string& text) {
          const Eigen::Quaterniond q = QuaternionFromEulerDegrees(with(text));
          studio.design.SetField(
              address, FormatNumber(q.x()) + " " + FormatNumber(q.y()) + " " +
                           FormatNumber(q.z()) + " " + FormatNumber(q.w()));
        });
    studio.Record("field " + address.sub + "/" + address.field + " " +
                  kAxes[k]);
    // A refusal shows under the field the student typed in.
    DrawFieldError(field_errors_, component_key);
    ImGui::PopID();
  }
}

void InspectorPanel::DrawLock(StudioContext& studio, const Scenario& view,
                              const Selection& sel) {
  const Robot& robot = view.robots.at(sel.robot);
  const Joint& lock = robot.locks.at(sel.index);
  std::string a = lock.left_frame_guid, b = lock.right_frame_guid;
  for (const LockEnd& end : studio.design.LockEnds(sel.robot)) {
    if (end.guid == lock.left_frame_guid) a = end.name;
    if (end.guid == lock.right_frame_guid) b = end.name;
  }
  const bool chain = IsChainLock(robot, lock);
  ImGui::TextWrapped("%s lock between %s and %s", chain ? "Chain" : "Loop",
                     a.c_str(), b.c_str());
  if (studio.Button("Detach")) {
    studio.Try("detach the lock", [&] { studio.design.DetachLock(); });
  }
  if (ImGui::IsItemHovered()) {
    WrappedTooltip(
        chain ? "This lock holds the chain together: detaching it is "
                "refused. A breaking force lets it break during the run."
              : "Removes this lock from the design; the two parts stay "
                "joined through the rest of the chain.");
  }
  ImGui::Separator();
}

void InspectorPanel::DrawAttach(StudioContext& studio, const Scenario& view,
                                const Selection& sel) {
  // The selected part's own ends: a module's two frames, a sensor module.
  std::vector<LockEnd> own;
  std::vector<std::string> own_names;
  if (sel.kind == SelectionKind::kModule) {
    const Module& m = view.robots.at(sel.robot).modules.at(sel.index);
    for (int f = 0; f < 2; ++f) {
      own.push_back({m.frames[f].guid, FrameName(f)});
    }
  } else {
    own.push_back({view.robots.at(sel.robot).sensor_modules.at(sel.index).guid,
                   "sensor module"});
  }
  attach_from_ = std::clamp(attach_from_, 0, static_cast<int>(own.size()) - 1);
  const std::vector<LockEnd> to =
      studio.design.AttachableTo(sel.robot, own[attach_from_].guid);
  if (RecordedHeader(&studio.layout, "Attach lock", false)) {
    PickEnd(studio, "from", "attach from", own, &attach_from_);
    if (to.empty()) {
      ImGui::TextWrapped("joined to every part of its robot already");
    } else {
      PickEnd(studio, "to", "attach to", to, &attach_to_);
      if (studio.Button("Attach")) {
        studio.Try("attach the lock", [&] {
          studio.design.AttachLock(sel.robot, own[attach_from_].guid,
                                   to[attach_to_].guid);
        });
      }
      if (ImGui::IsItemHovered()) {
        WrappedTooltip(
            "A rigid lock between the two parts; between parts that are not "
            "next to each other it closes a loop and holds them at the pose "
            "they have in the design.");
      }
    }
  }
  ImGui::Separator();
}

void InspectorPanel::DrawLooseJoin(StudioContext& studio, const Scenario& view,
                                   const Selection& sel) {
  const std::string from = sel.kind == SelectionKind::kLooseFrame
                               ? view.loose_frames.at(sel.index).guid
                               : view.loose_sensor_modules.at(sel.index).guid;
  const std::vector<LockEnd> to = studio.design.LooseJoinableTo(from);
  if (RecordedHeader(&studio.layout, "Join to a loose part", false)) {
    if (to.empty()) {
      ImGui::TextWrapped(
          "no other loose part to join: add a loose frame or sensor module "
          "first");
    } else {
      PickEnd(studio, "to", "join to", to, &join_to_);
      if (studio.Button("Join with a lock")) {
        studio.Try("join the loose parts", [&] {
          studio.design.JoinLoose(from, to[join_to_].guid, JointType::kLock);
        });
      }
      if (ImGui::IsItemHovered()) {
        WrappedTooltip(
            "A rigid lock: the two parts keep the pose they have in the "
            "design and move as one (a sensor module rides on a frame). A "
            "breaking force lets it break during the run.");
      }
      ImGui::SameLine();
      if (studio.Button("Join with a hinge")) {
        studio.Try("join the loose parts", [&] {
          studio.design.JoinLoose(from, to[join_to_].guid, JointType::kHinge);
        });
      }
      if (ImGui::IsItemHovered()) {
        WrappedTooltip(
            "A hinge about this part's y axis, midway between the two; it "
            "turns freely until its servo is switched on.");
      }
    }
  }
  ImGui::Separator();
}

void InspectorPanel::DrawLooseJoint(StudioContext& studio, const Scenario& view,
                                    const Selection& sel) {
  const Joint& j = view.loose_joints.at(sel.index);
  std::string a = j.left_frame_guid, b = j.right_frame_guid;
  for (const LockEnd& end : studio.design.LooseEnds()) {
    if (end.guid == j.left_frame_guid) a = end.name;
    if (end.guid == j.right_frame_guid) b = end.name;
  }
  ImGui::TextWrapped("%s between %s and %s",
                     j.type == JointType::kLock ? "Loose lock" : "Loose hinge",
                     a.c_str(), b.c_str());
  ImGui::Separator();
}

void InspectorPanel::DrawObjectSize(StudioContext& studio,
                                    const SceneObject& object,
                                    const FieldAddress& address,
                                    const std::string& key, float left) {
  const float width = ImGui::GetContentRegionAvail().x;
  const std::vector<SizeComponent> parts = SizeComponents(object.shape);
  for (size_t k = 0; k < parts.size(); ++k) {
    const SizeComponent& part = parts[k];
    ImGui::PushID(static_cast<int>(k));
    if (k > 0) ImGui::SetCursorPosX(left);
    ImGui::TextDisabled("%s", part.label);
    ImGui::SameLine(left + 60);
    ImGui::SetNextItemWidth(width - 60);
    const std::string component_key = key + " " + part.label;
    const auto with = [&](const std::string& text) {
      Eigen::Vector3d next = object.size;
      next[part.axis] = ParseNumber(text);
      if (!(next[part.axis] > 0)) throw FieldError("expected a positive size");
      return SizeFor(object.shape, next);
    };
    TextField(
        component_key, ShortNumbers(FormatNumber(object.size[part.axis])),
        [&](const std::string& text) { with(text); },
        [&](const std::string& text) {
          const Eigen::Vector3d size = with(text);
          studio.design.SetField(address, FormatNumber(size.x()) + " " +
                                              FormatNumber(size.y()) + " " +
                                              FormatNumber(size.z()));
        });
    studio.Record("field /size " + std::string(part.label));
    DrawFieldError(field_errors_, component_key);
    ImGui::PopID();
  }
}

void InspectorPanel::DrawSensorMounts(StudioContext& studio,
                                      const Scenario& view,
                                      const Selection& sel) {
  const bool loose = sel.kind == SelectionKind::kLooseSensorModule;
  const SensorModule& sm =
      loose ? view.loose_sensor_modules.at(sel.index)
            : view.robots.at(sel.robot).sensor_modules.at(sel.index);
  // A checkbox per kind a module carries at most one of (force plate,
  // IMU); distance sensors are added per face below.
  for (const SensorKind& kind : SensorKinds()) {
    if (kind.set == nullptr) continue;
    // A plate is what a robot's chain rests on: a loose module has none.
    if (loose && kind.mount == SensorMount::kPlate) continue;
    bool on = kind.count(sm) > 0;
    if (ImGui::Checkbox(kind.label, &on)) {
      studio.Try(std::string(on ? "add the " : "remove the ") + kind.label,
                 [&] { studio.design.SetSensorKind(kind, on); });
    }
    studio.Record(kind.label);
  }
  if (studio.design.revision() != ray_face_revision_ ||
      !(sel == ray_face_selection_)) {
    ray_face_revision_ = studio.design.revision();
    ray_face_selection_ = sel;
    const std::vector<int> open = studio.design.OpenRayFaces();
    // Front first (a sensor looking ahead), else the first face open.
    if (!open.empty() &&
        std::find(open.begin(), open.end(), ray_face_) == open.end()) {
      ray_face_ = std::find(open.begin(), open.end(), 4) != open.end()
                      ? 4
                      : open.front();
    }
  }
  ImGui::SetNextItemWidth(90);
  ImGui::Combo("##face", &ray_face_, kSensorFaceNames.data(),
               static_cast<int>(kSensorFaceNames.size()));
  ImGui::SameLine();
  if (studio.Button("add distance sensor")) {
    studio.Try("add the distance sensor",
               [&] { studio.design.AddDistanceSensor(ray_face_); });
  }
  for (size_t k = 0; k < sm.distance_sensors.size(); ++k) {
    const int face = sm.distance_sensors[k].sensor_position;
    ImGui::PushID(static_cast<int>(k));
    ImGui::Text("ray %zu: %s", k,
                face >= 0 && face < static_cast<int>(kSensorFaceNames.size())
                    ? kSensorFaceNames[face]
                    : "?");
    ImGui::SameLine();
    if (ImGui::SmallButton("remove")) {
      studio.Try(
          [&] { studio.design.RemoveDistanceSensor(static_cast<int>(k)); });
    }
    ImGui::PopID();
  }
  DrawCameras(studio, sm.cameras, sel);
  ImGui::Separator();
}

void InspectorPanel::DrawCameras(StudioContext& studio,
                                 const std::vector<Camera>& cameras,
                                 const Selection& sel) {
  if (studio.design.revision() != camera_face_revision_ ||
      !(sel == camera_face_selection_)) {
    camera_face_revision_ = studio.design.revision();
    camera_face_selection_ = sel;
    const std::vector<int> open = studio.design.OpenCameraFaces();
    // Front first (a camera looking ahead), else the first face open.
    if (!open.empty() &&
        std::find(open.begin(), open.end(), camera_face_) == open.end()) {
      camera_face_ = std::find(open.begin(), open.end(), 4) != open.end()
                         ? 4
                         : open.front();
    }
  }
  ImGui::SetNextItemWidth(90);
  ImGui::Combo("##camera face", &camera_face_, kSensorFaceNames.data(),
               static_cast<int>(kSensorFaceNames.size()));
  ImGui::SameLine();
  if (studio.Button("add camera")) {
    studio.Try("add the camera",
               [&] { studio.design.AddCamera(camera_face_); });
  }
  for (size_t k = 0; k < cameras.size(); ++k) {
    const Camera& c = cameras[k];
    ImGui::PushID(static_cast<int>(100 + k));
    ImGui::Text(
        "camera %zu: %s, %dx%d", k,
        c.sensor_position >= 0 &&
                c.sensor_position < static_cast<int>(kSensorFaceNames.size())
            ? kSensorFaceNames[c.sensor_position]
            : "?",
        c.width, c.height);
    ImGui::SameLine();
    if (ImGui::SmallButton("remove")) {
      studio.Try([&] { studio.design.RemoveCamera(static_cast<int>(k)); });
    }
    studio.Record("remove camera " + std::to_string(k));
    ImGui::PopID();
  }
}

}  // namespace mrsim::studio
