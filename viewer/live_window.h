// A desktop window (GLFW) showing the rendered scene live, with the camera
// driven by mouse and keyboard. Its OpenGL context also serves the
// off-screen frames, so a windowed viewer needs no EGL context.
//
// Mouse: left drag orbits, right (or shift+left) drag pans, wheel zooms.
// Keys: arrows orbit, W/A/S/D pan, +/- (or PageUp/PageDown) zoom,
// F toggles follow/fixed, R resets the view, Q or Esc closes.
#pragma once

#include <memory>
#include <string>

#include "viewer/camera_control.h"

namespace mrsim {

class LiveWindow {
 public:
  // True when a display can be opened (DISPLAY or WAYLAND_DISPLAY set).
  static bool DisplayAvailable();

  // Opens the window and makes its context current. `camera` (may be null,
  // see SetCamera) must outlive the window. Throws std::runtime_error when
  // GLFW cannot open it.
  LiveWindow(const std::string& title, int width, int height,
             CameraControl* camera);
  ~LiveWindow();
  LiveWindow(const LiveWindow&) = delete;
  LiveWindow& operator=(const LiveWindow&) = delete;

  // The camera that mouse and keys move from now on.
  void SetCamera(CameraControl* camera);
  void MakeCurrent();
  // Handles pending input; camera moves go to the CameraControl.
  void PollEvents();
  // Shows what was rendered into the window framebuffer.
  void SwapBuffers();
  bool ShouldClose() const;
  // Framebuffer size in pixels.
  int width() const;
  int height() const;
  // True (once) after the camera was moved from the window or the window
  // was resized: time to draw again.
  bool TakeCameraChanged();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace mrsim
