#include "viewer/live_window.h"

#include <GLFW/glfw3.h>

#include <cstdlib>
#include <stdexcept>

namespace mrsim {

struct LiveWindow::Impl {
  GLFWwindow* window = nullptr;
  CameraControl* camera = nullptr;
  bool changed = false;
  bool left = false;
  bool right = false;
  double last_x = 0.0;
  double last_y = 0.0;

  static Impl* From(GLFWwindow* w) {
    return static_cast<Impl*>(glfwGetWindowUserPointer(w));
  }

  static void OnKey(GLFWwindow* w, int key, int, int action, int) {
    if (action == GLFW_RELEASE) return;
    Impl* self = From(w);
    if (key == GLFW_KEY_Q || key == GLFW_KEY_ESCAPE) {
      glfwSetWindowShouldClose(w, GLFW_TRUE);
      return;
    }
    if (self->camera == nullptr) return;
    CameraControl& cam = *self->camera;
    switch (key) {
      case GLFW_KEY_LEFT:
        cam.Orbit(5.0, 0.0);
        break;
      case GLFW_KEY_RIGHT:
        cam.Orbit(-5.0, 0.0);
        break;
      case GLFW_KEY_UP:
        cam.Orbit(0.0, 5.0);
        break;
      case GLFW_KEY_DOWN:
        cam.Orbit(0.0, -5.0);
        break;
      case GLFW_KEY_A:
        cam.Pan(-0.05, 0.0);
        break;
      case GLFW_KEY_D:
        cam.Pan(0.05, 0.0);
        break;
      case GLFW_KEY_W:
        cam.Pan(0.0, 0.05);
        break;
      case GLFW_KEY_S:
        cam.Pan(0.0, -0.05);
        break;
      case GLFW_KEY_EQUAL:
      case GLFW_KEY_KP_ADD:
      case GLFW_KEY_PAGE_UP:
        cam.Zoom(0.9);
        break;
      case GLFW_KEY_MINUS:
      case GLFW_KEY_KP_SUBTRACT:
      case GLFW_KEY_PAGE_DOWN:
        cam.Zoom(1.0 / 0.9);
        break;
      case GLFW_KEY_F:
        cam.ToggleMode();
        break;
      case GLFW_KEY_R:
        cam.Reset();
        break;
      default:
        return;
    }
    self->changed = true;
  }

  static void OnButton(GLFWwindow* w, int button, int action, int mods) {
    Impl* self = From(w);
    const bool down = action == GLFW_PRESS;
    const bool shift = (mods & GLFW_MOD_SHIFT) != 0;
    if (button == GLFW_MOUSE_BUTTON_LEFT) {
      self->left = down && !shift;
      self->right = down && shift;
    } else if (button == GLFW_MOUSE_BUTTON_RIGHT) {
      self->right = down;
    }
    glfwGetCursorPos(w, &self->last_x, &self->last_y);
  }

  static void OnMove(GLFWwindow* w, double x, double y) {
    Impl* self = From(w);
    const double dx = x - self->last_x;
    const double dy = y - self->last_y;
    self->last_x = x;
    self->last_y = y;
    if (self->camera == nullptr) return;
    int width = 1;
    int height = 1;
    glfwGetWindowSize(w, &width, &height);
    if (height < 1) height = 1;
    if (self->left) {
      self->camera->Orbit(-180.0 * dx / height, 180.0 * dy / height);
      self->changed = true;
    } else if (self->right) {
      self->camera->Pan(-dx / height, dy / height);
      self->changed = true;
    }
  }

  static void OnScroll(GLFWwindow* w, double, double dy) {
    Impl* self = From(w);
    if (self->camera == nullptr) return;
    self->camera->Zoom(dy > 0 ? 0.9 : 1.0 / 0.9);
    self->changed = true;
  }
  // A resized window is drawn again at once at its new framebuffer size,
  // not only when the next new state arrives.
  static void OnResize(GLFWwindow* w, int, int) { From(w)->changed = true; }
};

bool LiveWindow::DisplayAvailable() {
  const char* x11 = std::getenv("DISPLAY");
  const char* wayland = std::getenv("WAYLAND_DISPLAY");
  return (x11 != nullptr && *x11 != '\0') ||
         (wayland != nullptr && *wayland != '\0');
}

LiveWindow::LiveWindow(const std::string& title, int width, int height,
                       CameraControl* camera)
    : impl_(std::make_unique<Impl>()) {
  impl_->camera = camera;
  if (!glfwInit()) {
    throw std::runtime_error("window: glfwInit failed (no usable display?)");
  }
  glfwWindowHint(GLFW_VISIBLE, GLFW_TRUE);
  impl_->window =
      glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
  if (impl_->window == nullptr) {
    glfwTerminate();
    throw std::runtime_error("window: glfwCreateWindow failed");
  }
  glfwSetWindowUserPointer(impl_->window, impl_.get());
  glfwSetKeyCallback(impl_->window, &Impl::OnKey);
  glfwSetMouseButtonCallback(impl_->window, &Impl::OnButton);
  glfwSetCursorPosCallback(impl_->window, &Impl::OnMove);
  glfwSetScrollCallback(impl_->window, &Impl::OnScroll);
  glfwSetFramebufferSizeCallback(impl_->window, &Impl::OnResize);
  MakeCurrent();
  glfwSwapInterval(0);  // never wait for vsync: the stream sets the pace
}

LiveWindow::~LiveWindow() {
  if (impl_->window != nullptr) glfwDestroyWindow(impl_->window);
  glfwTerminate();
}

void LiveWindow::SetCamera(CameraControl* camera) { impl_->camera = camera; }
void LiveWindow::MakeCurrent() { glfwMakeContextCurrent(impl_->window); }
void LiveWindow::PollEvents() { glfwPollEvents(); }
void LiveWindow::SwapBuffers() { glfwSwapBuffers(impl_->window); }
bool LiveWindow::ShouldClose() const {
  return glfwWindowShouldClose(impl_->window) != 0;
}
int LiveWindow::width() const {
  int w = 0;
  int h = 0;
  glfwGetFramebufferSize(impl_->window, &w, &h);
  return w;
}
int LiveWindow::height() const {
  int w = 0;
  int h = 0;
  glfwGetFramebufferSize(impl_->window, &w, &h);
  return h;
}
bool LiveWindow::TakeCameraChanged() {
  const bool changed = impl_->changed;
  impl_->changed = false;
  return changed;
}

}  // namespace mrsim
