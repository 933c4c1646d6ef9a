// Dear ImGui set-up shared by the window and the off-screen shell: no
// imgui.ini (a library writes no stray files), a readable font, the style.
#pragma once

namespace mrsim::studio {

// Creates the ImGui context and the OpenGL3 renderer backend (a GL context
// must be current), text and widgets at `ui_scale` (1: 15 px text).
// Returns false when the renderer cannot start.
bool SetUpImGui(float ui_scale = 1);
void ShutDownImGui();

// Asks Mesa's software renderer (llvmpipe) for one render thread unless
// LP_NUM_THREADS is set already; call before any OpenGL context exists.
// Why: by default llvmpipe renders on every core, and on a small machine
// the studio's frames then take CPU from the simulator it shows (measured:
// a fast-clock run 23% slower with the studio attached; with one thread,
// no slower, and still above 30 frames/s). Other drivers ignore it.
void PreferOneSoftwareRenderThread();

}  // namespace mrsim::studio
