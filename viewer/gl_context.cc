#include "viewer/gl_context.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <cstdio>
#include <map>
#include <mutex>
#include <stdexcept>
#include <string>

namespace mrsim {
namespace {

std::string EglError(const char* call) {
  char code[16];
  std::snprintf(code, sizeof(code), "0x%04x", eglGetError());
  return std::string("off-screen OpenGL: ") + call + " failed (EGL error " +
         code +
         "); is Mesa's EGL installed (libegl1, libegl-mesa0)? See "
         "docs/viewer.md";
}

// The surfaceless platform needs no X server, no GPU and no DRM device; the
// default display is the fallback for drivers without it (e.g. NVIDIA).
EGLDisplay OpenDisplay(std::string* platform) {
  auto get_platform_display = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
      eglGetProcAddress("eglGetPlatformDisplayEXT"));
  if (get_platform_display != nullptr) {
    EGLDisplay display = get_platform_display(EGL_PLATFORM_SURFACELESS_MESA,
                                              EGL_DEFAULT_DISPLAY, nullptr);
    if (display != EGL_NO_DISPLAY && eglInitialize(display, nullptr, nullptr)) {
      *platform = "surfaceless";
      return display;
    }
  }
  EGLDisplay display = eglGetDisplay(EGL_DEFAULT_DISPLAY);
  if (display == EGL_NO_DISPLAY) {
    throw std::runtime_error(EglError("eglGetDisplay"));
  }
  if (!eglInitialize(display, nullptr, nullptr)) {
    throw std::runtime_error(EglError("eglInitialize"));
  }
  *platform = "default display";
  return display;
}

// EGL hands every caller the same display, and eglTerminate ends every
// context on it: contexts alive at once (two simulations rendering
// cameras, a studio and its renderer) count their display's users, and
// the last one terminates it.
std::mutex& DisplayUsersMutex() {
  static std::mutex mutex;
  return mutex;
}
std::map<EGLDisplay, int>& DisplayUsers() {
  static std::map<EGLDisplay, int> users;
  return users;
}

}  // namespace

struct GlContext::Impl {
  EGLDisplay display = EGL_NO_DISPLAY;
  EGLContext context = EGL_NO_CONTEXT;
  EGLSurface surface = EGL_NO_SURFACE;
  std::string description;

  ~Impl() {
    if (display == EGL_NO_DISPLAY) return;
    eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    if (surface != EGL_NO_SURFACE) eglDestroySurface(display, surface);
    if (context != EGL_NO_CONTEXT) eglDestroyContext(display, context);
    const std::lock_guard<std::mutex> lock(DisplayUsersMutex());
    if (--DisplayUsers()[display] <= 0) {
      DisplayUsers().erase(display);
      eglTerminate(display);
    }
  }
};

GlContext::GlContext() : impl_(std::make_unique<Impl>()) {
  std::string platform;
  {
    const std::lock_guard<std::mutex> lock(DisplayUsersMutex());
    impl_->display = OpenDisplay(&platform);
    ++DisplayUsers()[impl_->display];
  }
  // The default surface type is a window; off-screen configs only offer
  // pbuffers, so ask for one (MuJoCo renders into its own framebuffer).
  const EGLint config_attributes[] = {EGL_RED_SIZE,
                                      8,
                                      EGL_GREEN_SIZE,
                                      8,
                                      EGL_BLUE_SIZE,
                                      8,
                                      EGL_ALPHA_SIZE,
                                      8,
                                      EGL_DEPTH_SIZE,
                                      24,
                                      EGL_STENCIL_SIZE,
                                      8,
                                      EGL_RENDERABLE_TYPE,
                                      EGL_OPENGL_BIT,
                                      EGL_SURFACE_TYPE,
                                      EGL_PBUFFER_BIT,
                                      EGL_NONE};
  EGLConfig config;
  EGLint count = 0;
  if (!eglChooseConfig(impl_->display, config_attributes, &config, 1, &count) ||
      count < 1) {
    throw std::runtime_error(EglError("eglChooseConfig (RGBA8, depth 24)"));
  }
  if (!eglBindAPI(EGL_OPENGL_API)) {
    throw std::runtime_error(EglError("eglBindAPI(EGL_OPENGL_API)"));
  }
  impl_->context =
      eglCreateContext(impl_->display, config, EGL_NO_CONTEXT, nullptr);
  if (impl_->context == EGL_NO_CONTEXT) {
    throw std::runtime_error(EglError("eglCreateContext"));
  }
  // Without EGL_KHR_surfaceless_context a tiny pbuffer stands in.
  const char* extensions = eglQueryString(impl_->display, EGL_EXTENSIONS);
  const bool surfaceless =
      extensions != nullptr &&
      std::string(extensions).find("EGL_KHR_surfaceless_context") !=
          std::string::npos;
  if (!surfaceless) {
    const EGLint pbuffer_attributes[] = {EGL_WIDTH, 16, EGL_HEIGHT, 16,
                                         EGL_NONE};
    impl_->surface =
        eglCreatePbufferSurface(impl_->display, config, pbuffer_attributes);
    if (impl_->surface == EGL_NO_SURFACE) {
      throw std::runtime_error(EglError("eglCreatePbufferSurface"));
    }
  }
  MakeCurrent();
  const char* vendor = eglQueryString(impl_->display, EGL_VENDOR);
  const char* version = eglQueryString(impl_->display, EGL_VERSION);
  impl_->description = std::string("EGL ") + (version ? version : "?") + " (" +
                       (vendor ? vendor : "?") + "), platform " + platform;
}

GlContext::~GlContext() = default;

void GlContext::MakeCurrent() {
  if (!eglMakeCurrent(impl_->display, impl_->surface, impl_->surface,
                      impl_->context)) {
    throw std::runtime_error(EglError("eglMakeCurrent"));
  }
}

const std::string& GlContext::description() const { return impl_->description; }

}  // namespace mrsim
