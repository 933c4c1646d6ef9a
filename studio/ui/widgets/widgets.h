// The widgets every panel and dialog of the studio window shares: a button
// or header whose rectangle goes to the layout dump (so an X test can click
// it by name), a fixed modal, a wrapped tooltip and the flags of the docked
// panels. Dear ImGui underneath; the one place these are spelled.
#pragma once

#include <imgui.h>

#include <string>

#include "studio/ui/widgets/layout_recorder.h"

namespace mrsim::studio {

// The panels fill fixed places of the window: never moved, resized or
// raised over the dialogs.
constexpr ImGuiWindowFlags kPanelFlags =
    ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize |
    ImGuiWindowFlags_NoCollapse | ImGuiWindowFlags_NoSavedSettings |
    ImGuiWindowFlags_NoBringToFrontOnFocus;

// Records the last item's rectangle under `name` for --layout-dump, and
// whether it takes typed text (a test types only once it is this one).
// Nothing when `layout` is null or records nowhere.
void RecordItem(LayoutRecorder* layout, const std::string& name);

// ImGui::Button, recorded under its label.
bool RecordedButton(LayoutRecorder* layout, const char* label, float width = 0);

// A collapsing header recorded as "header <label>".
bool RecordedHeader(LayoutRecorder* layout, const char* label,
                    bool open_at_start);

// A dialog of fixed size (height 0: as its text needs), centred across
// the window at height `top`: where a modal is expected, never dragged off.
bool BeginFixedModal(const char* title, float width, float height, float top);

// A tooltip for a message too long for its line, wrapped to a readable
// width instead of running off the window.
void WrappedTooltip(const std::string& text);

}  // namespace mrsim::studio
