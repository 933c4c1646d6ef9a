// The cameras of an in-process Simulation (Simulation.camera_image): the
// viewer's CameraImageRenderer over the simulation's own physics model,
// made the first time a picture is asked for (a simulation that never
// renders needs no OpenGL at all). Every simulation of the process shares
// one off-screen OpenGL context: EGL hands every context of a process the
// same display, and one context's teardown terminates it for all others.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "sim_core/physics/physics.h"
#include "viewer/camera_image_renderer.h"
#include "viewer/gl_context.h"

namespace mrsim::python {

class SimulationCameras {
 public:
  SimulationCameras() = default;
  ~SimulationCameras();
  SimulationCameras(const SimulationCameras&) = delete;
  SimulationCameras& operator=(const SimulationCameras&) = delete;

  // The cameras of `owner` in `scenario` (a robot's name, "loose" or
  // "scene"), camera_image_t's numbering (no OpenGL needed).
  static std::vector<ScenarioCamera> Of(const Scenario& scenario,
                                        const std::string& owner);

  // Which of `owner`'s cameras `camera` is (its index, or the MuJoCo name
  // "<owner>/sm<k>/camera<i>" when `name` is not empty). Throws
  // std::out_of_range naming the cameras the owner has.
  static int Resolve(const Scenario& scenario, const std::string& owner,
                     int camera, const std::string& name);

  // `owner`'s camera `camera` as the physics poses it now: height x
  // width x 3 bytes, red first, top row first. `seq` keys the pixel noise.
  // Makes the shared GL context current on the calling thread for the
  // render (any thread may render; renders of all simulations are
  // serialised). Throws
  // std::runtime_error naming what OpenGL could not make.
  std::vector<std::uint8_t> Render(const Physics& physics,
                                   const std::string& owner, int camera,
                                   std::int64_t seq);

 private:
  std::shared_ptr<GlContext> gl_;  // the process's, while anyone renders
  std::unique_ptr<CameraImageRenderer> renderer_;
  const mjModel* model_ = nullptr;  // the model renderer_ was made for
};

}  // namespace mrsim::python
