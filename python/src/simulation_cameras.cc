#include "python/src/simulation_cameras.h"

#include <EGL/egl.h>
#include <dlfcn.h>

#include <mutex>
#include <stdexcept>

namespace mrsim::python {
namespace {

// MuJoCo's OpenGL loader finds eglGetProcAddress among the process's
// global symbols; an extension module's libraries are loaded local to it,
// so libEGL is promoted to global once, before the first context.
void MakeEglGlobal() {
  static const bool done = [] {
    dlopen("libEGL.so.1", RTLD_NOW | RTLD_GLOBAL | RTLD_NOLOAD);
    return true;
  }();
  (void)done;
}

// One GL context for the process, alive while a simulation renders.
std::mutex& RenderMutex() {
  static std::mutex mutex;
  return mutex;
}

std::shared_ptr<GlContext> SharedGlContext() {
  static std::weak_ptr<GlContext> shared;
  std::shared_ptr<GlContext> gl = shared.lock();
  if (gl == nullptr) {
    MakeEglGlobal();
    gl = std::make_shared<GlContext>();
    shared = gl;
  }
  return gl;
}

// The shared context current on the calling thread while it lives, then
// released, so that the next render may come from another Python thread
// (EGL refuses a context current on another thread).
class CurrentGl {
 public:
  explicit CurrentGl(GlContext& gl) { gl.MakeCurrent(); }
  ~CurrentGl() {
    eglMakeCurrent(eglGetCurrentDisplay(), EGL_NO_SURFACE, EGL_NO_SURFACE,
                   EGL_NO_CONTEXT);
  }
  CurrentGl(const CurrentGl&) = delete;
  CurrentGl& operator=(const CurrentGl&) = delete;
};

std::string Listing(const std::vector<ScenarioCamera>& cameras) {
  std::string out;
  for (const ScenarioCamera& c : cameras) {
    out += (out.empty() ? "" : ", ") + std::to_string(c.camera) + " '" +
           c.name + "' " + std::to_string(c.part.width) + "x" +
           std::to_string(c.part.height);
  }
  return out;
}

// "robot 'snake' has", "the scene objects have", ...
std::string OwnerHas(const std::string& owner) {
  if (owner == kSceneOwnerName) return "the scene objects have";
  if (owner == kLooseOwnerName) return "the loose sensor modules have";
  return "robot '" + owner + "' has";
}

}  // namespace

SimulationCameras::~SimulationCameras() {
  if (renderer_ == nullptr) return;
  // The renderer's OpenGL objects are freed in the shared context.
  std::lock_guard<std::mutex> lock(RenderMutex());
  try {
    CurrentGl current(*gl_);
    renderer_.reset();
  } catch (const std::exception&) {
    // No context to free them in: they go with the process.
    static_cast<void>(renderer_.release());
  }
}

std::vector<ScenarioCamera> SimulationCameras::Of(const Scenario& scenario,
                                                  const std::string& owner) {
  std::vector<ScenarioCamera> out;
  for (ScenarioCamera& c : ScenarioCameras(scenario)) {
    if (c.owner == owner) out.push_back(std::move(c));
  }
  return out;
}

int SimulationCameras::Resolve(const Scenario& scenario,
                               const std::string& owner, int camera,
                               const std::string& name) {
  const std::vector<ScenarioCamera> cameras = Of(scenario, owner);
  if (cameras.empty()) {
    throw std::out_of_range(OwnerHas(owner) +
                            " no camera (a <Camera> in a sensor module's or "
                            "a scene object's <cameras>: docs/camera.md)");
  }
  for (const ScenarioCamera& c : cameras) {
    if (name.empty() ? c.camera == camera : c.name == name) return c.camera;
  }
  throw std::out_of_range(
      "camera " + (name.empty() ? std::to_string(camera) : "'" + name + "'") +
      ": " + OwnerHas(owner) + " " + std::to_string(cameras.size()) +
      " camera(s): " + Listing(cameras));
}

std::vector<std::uint8_t> SimulationCameras::Render(const Physics& physics,
                                                    const std::string& owner,
                                                    int camera,
                                                    std::int64_t seq) {
  std::lock_guard<std::mutex> lock(RenderMutex());
  if (gl_ == nullptr) gl_ = SharedGlContext();
  CurrentGl current(*gl_);
  // A reset or a checkpoint loaded may rebuild the model (a released lock).
  if (renderer_ == nullptr || model_ != physics.model()) {
    renderer_.reset();
    renderer_ = std::make_unique<CameraImageRenderer>(physics.model(),
                                                      physics.scenario());
    model_ = physics.model();
  }
  const int index = renderer_->Find(owner, camera);
  if (index < 0) {
    throw std::out_of_range("camera " + std::to_string(camera) + " of '" +
                            owner + "' is not in the model");
  }
  std::vector<std::uint8_t> rgb;
  // data(), not mutable_data(): rendering reads the poses and changes no
  // state, so a split world's view is not marked as poked.
  renderer_->Render(index, const_cast<mjData*>(physics.data()), seq, &rgb);
  return rgb;
}

}  // namespace mrsim::python
