// What the files of the Run panel (LivePanel, live_panel.h, and its
// live_*_section.cc) share: the widgets, a combo over an enum's words and
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

#include "common/enum_table.h"
#include "lcmtypes/runtime/clock_mode.h"
#include "studio/live/live_session.h"
#include "studio/ui/widgets/widgets.h"

namespace mrsim::studio {

// A combo over an enum's table (common/enum_table.h): the words in table
// order, `index` into EnumTable::entries().
template <typename E>
bool EnumCombo(const char* label, int* index, const EnumTable<E>& table) {
  return ImGui::Combo(
      label, index,
      +[](void* data, int i, const char** text) {
        *text = static_cast<const EnumTable<E>*>(data)->entries().at(i).name;
        return true;
      },
      const_cast<EnumTable<E>*>(&table),
      static_cast<int>(table.entries().size()));
}
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
