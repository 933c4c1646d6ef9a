// The Run panel's controller choice: the gait (mrsim-gait, as before), a
// Lua script edited in the window (templates; its syntax checked as it is
// typed, the error shown with its line before Run) or an external
// controller by name (Run starts the simulator in lockstep waiting for it).
// Fill() turns the choice into RunOptions for LiveRunner.
#pragma once

#include <optional>
#include <string>

#include "lua_controller/lua_script.h"
#include "studio/live/live_runner.h"
#include "studio/ui/widgets/layout_recorder.h"

namespace mrsim::studio {

class ControllerPanel {
 public:
  ControllerPanel();
  void Draw(LayoutRecorder* layout);
  // Sets o->controller and what it needs. For a Lua script, writes it
  // beside the design ("<design>.controller.lua"), so a user can run the
  // same with mrsim-lua. Throws std::invalid_argument when the script does
  // not load (naming its line) or the external name is not one.
  void Fill(RunOptions* o, const std::string& design_path) const;

  ControllerKind kind() const { return static_cast<ControllerKind>(kind_); }
  const std::string& lua_source() const { return source_; }
  // What a design file brings along (its run settings); an empty script or
  // name keeps the editor's.
  void Set(ControllerKind kind, const std::string& gait,
           const std::string& lua_source, const std::string& external_name);
  std::string gait() const;
  const std::string& external_name() const { return external_; }

  // Where Fill writes the script for a design at `design_path`.
  static std::string ScriptPathFor(const std::string& design_path);

 private:
  void CheckNow();

  // ControllerKind as the radio buttons' int (ControllerKinds() order).
  int kind_ = static_cast<int>(ControllerKind::kGait);
  // A preset's index, or kDesignGait: design_gait_, a gait the opened
  // design names that is no preset.
  static constexpr int kDesignGait = -1;
  int gait_ = 0;
  std::string design_gait_;
  int template_ = 0;
  std::string source_;
  std::string checked_;  // the source error_ is for
  std::optional<LuaScriptError> error_;
  std::string external_ = "my-controller";
};

}  // namespace mrsim::studio
