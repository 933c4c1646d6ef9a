// Dear ImGui set-up shared by the window and the off-screen shell: no
// imgui.ini (a library writes no stray files), a readable font, the style.
#pragma once

namespace mrsim::studio {

// Creates the ImGui context and the OpenGL3 renderer backend (a GL context
// must be current). Returns false when the renderer cannot start.
bool SetUpImGui();
void ShutDownImGui();

}  // namespace mrsim::studio
