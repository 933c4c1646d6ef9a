// The studio in a desktop window (GLFW + Dear ImGui's GLFW backend).
#pragma once

#include <atomic>
#include <string>

#include "studio/ui/studio_app.h"

namespace mrsim::studio {

// Runs until the app quits or *stop becomes true (signals). Redraws on
// input and a few times a second otherwise. Throws std::runtime_error when
// the window cannot open.
void RunWindow(StudioApp* app, int width, int height,
               const std::atomic<bool>* stop);

}  // namespace mrsim::studio
