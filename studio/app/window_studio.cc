#include "studio/app/window_studio.h"

#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include <memory>
#include <stdexcept>

#include "studio/app/frame_pacer.h"
#include "studio/design/panel_layout.h"
#include "studio/ui/widgets/gui_setup.h"
#include "studio/ui/view/software_gl.h"

namespace mrsim::studio {
namespace {

struct GlfwWindow {
  GLFWwindow* window = nullptr;
  ~GlfwWindow() {
    if (window) glfwDestroyWindow(window);
    glfwTerminate();
  }
};

}  // namespace

void RunWindow(StudioApp* app, int width, int height,
               const std::atomic<bool>* stop) {
  if (!glfwInit()) throw std::runtime_error("GLFW cannot initialise");
  GlfwWindow w;
  glfwWindowHint(GLFW_SAMPLES, 4);
  glfwWindowHint(GLFW_VISIBLE, GLFW_FALSE);
  w.window = glfwCreateWindow(width, height, "mrsim-studio", nullptr, nullptr);
  if (!w.window) throw std::runtime_error("GLFW cannot open a window");
  glfwMakeContextCurrent(w.window);
  if (IsSoftwareGl()) {
    // Mesa's software renderer multisamples too: every pixel of the
    // window drawn four times over, on the CPU. The window again, without
    // (as the preview's off-screen buffer there; docs/studio.md).
    glfwDestroyWindow(w.window);
    glfwWindowHint(GLFW_SAMPLES, 0);
    w.window =
        glfwCreateWindow(width, height, "mrsim-studio", nullptr, nullptr);
    if (!w.window) throw std::runtime_error("GLFW cannot open a window");
    glfwMakeContextCurrent(w.window);
  }
  glfwShowWindow(w.window);
  glfwSwapInterval(1);
  // Text and panels grow with the monitor's content scale (high-DPI), or
  // as --ui-scale says.
  float monitor_x = 1, monitor_y = 1;
  glfwGetWindowContentScale(w.window, &monitor_x, &monitor_y);
  const float scale = ChooseUiScale(app->requested_ui_scale(), monitor_x);
  app->SetUiScale(scale);
  if (!SetUpImGui(scale)) {
    throw std::runtime_error("cannot start ImGui's OpenGL3 renderer");
  }
  // Shortcuts through our own callback (ImGui's chains to it): a key press
  // and release within one frame still count.
  glfwSetWindowUserPointer(w.window, app);
  glfwSetKeyCallback(
      w.window, [](GLFWwindow* window, int key, int, int action, int mods) {
        if (action == GLFW_PRESS || action == GLFW_REPEAT) {
          static_cast<StudioApp*>(glfwGetWindowUserPointer(window))
              ->OnKey(key, mods);
        }
      });
  ImGui_ImplGlfw_InitForOpenGL(w.window, true);
  int redraws = 3;  // ImGui settles its layout over a couple of frames
  FramePacer pacer;
  while (!app->should_quit() && !(stop && *stop)) {
    if (app->animating()) {
      // Live: a steady frame rate, input handled while waiting.
      for (double wait = pacer.Wait(FramePacer::Clock::now()); wait > 0;
           wait = pacer.Wait(FramePacer::Clock::now())) {
        glfwWaitEventsTimeout(wait);
      }
      glfwPollEvents();
    } else if (redraws > 0) {
      glfwPollEvents();
      --redraws;
    } else {
      // Idle: wait for input instead of spinning the CPU.
      glfwWaitEventsTimeout(0.25);
      redraws = 2;
    }
    if (glfwWindowShouldClose(w.window)) {
      glfwSetWindowShouldClose(w.window, GLFW_FALSE);
      app->RequestClose();
    }
    int fb_width = 0, fb_height = 0;
    glfwGetFramebufferSize(w.window, &fb_width, &fb_height);
    if (fb_width < 16 || fb_height < 16) continue;
    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    app->Frame(fb_width, fb_height, false);
    glfwSwapBuffers(w.window);
  }
  ImGui_ImplGlfw_Shutdown();
  ShutDownImGui();
}

}  // namespace mrsim::studio
