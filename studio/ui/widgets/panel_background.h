// The docked panels' background without drawing it: the frame is cleared
// to the colour a panel's background gives (ImGui's WindowBg over the
// window's base colour) and the panels draw no background quad of their
// own. The same picture, but on software GL (llvmpipe) the panels'
// backgrounds were most of the 800,000 blended pixels ImGui drew a frame
// at 1280x800, a third of a drag frame's time (bench/studio_drag).
#pragma once

#include <imgui.h>

namespace mrsim::studio {

// The colour to clear the frame to (opaque): what a panel's background
// looks like. Needs the ImGui context (the style).
ImVec4 PanelClearColour();

// Call right before ImGui::Begin of a docked panel: the window draws no
// background (the cleared frame shows through). Not for dialogs or
// windows over the 3-D view.
void SkipPanelBackground();

}  // namespace mrsim::studio
