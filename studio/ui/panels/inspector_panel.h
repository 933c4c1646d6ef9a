// The right column of the studio window (unless the Run panel is shown):
// every field of the selected part, straight from the scenario schema,
// checked as typed; a sensor module's force plate, distance sensors and
// cameras, a scene object's cameras; a lock's Detach, a chain part's
// Attach lock.
#pragma once

#include <functional>
#include <map>
#include <string>
#include <vector>

#include "studio/ui/studio_context.h"
#include "studio/ui/widgets/panel.h"

namespace mrsim::studio {

class InspectorPanel {
 public:
  void Draw(StudioContext& studio, const PanelRect& rect);

 private:
  // Force plate on/off and distance sensors of the selected sensor module.
  void DrawSensorMounts(StudioContext& studio, const Scenario& view,
                        const Selection& sel);
  // The cameras of the selected sensor module or scene object: a face
  // picker, "add camera", and each camera with its remove button (its
  // fields are a group below).
  void DrawCameras(StudioContext& studio, const std::vector<Camera>& cameras,
                   const Selection& sel);

  // A selected lock: what it joins and its Detach button.
  void DrawLock(StudioContext& studio, const Scenario& view,
                const Selection& sel);
  // A selected module or sensor module: "Attach lock" from one of its
  // parts to another part of its robot that nothing joins it to yet.
  // "Join to a loose part": a loose lock or hinge from the selected loose
  // frame or sensor module to another loose part.
  void DrawLooseJoin(StudioContext& studio, const Scenario& view,
                     const Selection& sel);
  // Which parts the selected loose joint joins, in words.
  void DrawLooseJoint(StudioContext& studio, const Scenario& view,
                      const Selection& sel);
  void DrawAttach(StudioContext& studio, const Scenario& view,
                  const Selection& sel);
  // A scene object's size as its shape reads it: a sphere's diameter, a
  // cylinder's diameter and length, a box's three sides.
  void DrawObjectSize(StudioContext& studio, const SceneObject& object,
                      const FieldAddress& address, const std::string& key,
                      float left);

  // An InputText for `key` that keeps what is typed until Enter or leaving
  // the field: `check` throws on text it refuses (shown as typed), `apply`
  // writes the text to the design. True when applied.
  bool TextField(const std::string& key, const std::string& current,
                 const std::function<void(const std::string&)>& check,
                 const std::function<void(const std::string&)>& apply);
  // A quaternion field as roll, pitch and yaw in degrees, one row each.
  void DrawEulerDegrees(StudioContext& studio, const FieldRef& f,
                        const FieldAddress& address, const std::string& key,
                        float left);

  std::map<std::string, std::string> field_errors_;  // by field key
  std::map<std::string, std::string> field_edits_;   // text being typed
  long fields_revision_ = -1;  // the design the two maps above are for
  Selection fields_selection_;
  int ray_face_ = 4;  // face for "add distance sensor": front
  // The design revision and selection ray_face_ was last defaulted for:
  // it moves to a face that would be accepted when they change.
  long ray_face_revision_ = -1;
  Selection ray_face_selection_;
  int camera_face_ = 4;  // face for "add camera", defaulted as ray_face_
  long camera_face_revision_ = -1;
  Selection camera_face_selection_;
  int attach_from_ = 0;  // the selected part's frame a new lock starts at
  int attach_to_ = 0;    // index into Design::AttachableTo
  int join_to_ = 0;      // index into Design::LooseJoinableTo
};

}  // namespace mrsim::studio
