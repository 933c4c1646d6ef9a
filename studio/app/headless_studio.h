// The studio drawn off-screen (EGL, no display): for --screenshot and the
// benchmarks. The whole window (panels and 3-D view) goes into MuJoCo's
// off-screen buffer and can be written to a PNG.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "studio/ui/studio_app.h"
#include "viewer/gl_context.h"

namespace mrsim::studio {

class HeadlessStudio {
 public:
  // Makes the EGL context and ImGui. Throws std::runtime_error when
  // off-screen OpenGL is not available.
  HeadlessStudio(StudioApp* app, int width, int height);
  ~HeadlessStudio();
  HeadlessStudio(const HeadlessStudio&) = delete;
  HeadlessStudio& operator=(const HeadlessStudio&) = delete;

  // Draws one frame and waits until OpenGL finished it.
  void Frame();
  // Writes the last frame; throws std::runtime_error naming the path.
  void SavePng(const std::string& path);

 private:
  StudioApp* app_;
  int width_;
  int height_;
  GlContext gl_;
};

// mrsim-studio --screenshot: the whole window once, after the frames ImGui
// needs to lay itself out, written to `path` (PNG). `drag` (x0 y0 x1 y1 or
// empty): the left button pressed at the first point and moved to the
// second in steps, as a hand would, still held for the picture (a palette
// drag, a handle drag in progress).
void SaveScreenshot(StudioApp* app, int width, int height,
                    const std::string& path, const std::vector<int>& drag = {});

}  // namespace mrsim::studio
