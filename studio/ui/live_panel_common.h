// What the files of the Run panel (LivePanel, live_panel.h, and its
// live_*_section.cc) share: the widgets, the clock names of the form and
// how a request's state reads. Included by those files only.
#pragma once

#include <fmt/format.h>
#include <imgui.h>
#include <imgui_stdlib.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <exception>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "studio/live/live_session.h"
#include "studio/ui/widgets.h"

namespace mrsim::studio {

// The form's clock choices, in mrsim-sim's words (--clock).
inline const char* const kClocks[] = {"realtime", "fast", "lockstep"};
// A click in a number field selects it whole: typing replaces the value.
constexpr ImGuiInputTextFlags kNumberFlags = ImGuiInputTextFlags_AutoSelectAll;

inline const char* RequestText(LiveRequest::State s) {
  switch (s) {
    case LiveRequest::State::kPending:
      return "sent";
    case LiveRequest::State::kDone:
      return "done";
    case LiveRequest::State::kRefused:
      return "refused";
    case LiveRequest::State::kNoAnswer:
      return "no answer";
  }
  return "";
}

}  // namespace mrsim::studio
