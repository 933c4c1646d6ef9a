// The Run panel's camera picture: one camera of the scenario the 3-D view
// shows, rendered in process by the renderer mrsim-camera and Python use
// (viewer/camera_image_renderer.h) from the very poses the view draws (the
// design's, or a live run's states), at the camera's rate in simulated
// time, into an OpenGL texture the panel shows with ImGui::Image. Not the
// picture mrsim-camera publishes: the same camera from the states the
// studio heard, without waiting for a picture to come over the wire.
// Needs the window's OpenGL context current (a GlContext in tests), for
// every call and for its destruction.
#pragma once

#include <mujoco/mujoco.h>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "sim_core/scenario/scenario.h"
#include "viewer/camera_image_renderer.h"

namespace mrsim::studio {

// The picture shown: what the chosen camera saw at `sim_time` (the state
// `seq`; -1 and 0 s for the design's own pose).
struct FeedPicture {
  int camera = -1;  // index in CameraFeed::cameras()
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgb;  // height x width x 3, top row first
  double sim_time = 0;
  std::int64_t seq = -1;
};

class CameraFeed {
 public:
  CameraFeed();
  ~CameraFeed();
  CameraFeed(const CameraFeed&) = delete;
  CameraFeed& operator=(const CameraFeed&) = delete;

  // The model the view draws, built from `scenario`; `key` changes with
  // every rebuild. A new key makes the renderer again and forgets the
  // picture, keeping the chosen camera when the new model has it (same
  // owner, same camera number). `model` must outlive the next SetModel.
  // A renderer OpenGL cannot make leaves no cameras and says why (error()).
  void SetModel(const mjModel* model, const Scenario& scenario, long key);
  // Forgets the model (no cameras) until the next SetModel.
  void Clear();
  long key() const { return key_; }

  // Every camera of the scenario, as camera_image_t numbers them.
  const std::vector<ScenarioCamera>& cameras() const;
  // Words for the chooser: "snake camera 0: S1 front, 160x120".
  std::vector<std::string> Labels() const;
  int selected() const { return selected_; }
  // Chooses cameras()[index] (clamped); its picture is due at once.
  void Select(int index);

  // Renders the chosen camera from the poses in `data` (the view's mjData)
  // when a picture is due: the first one, after a new model or choice,
  // when simulated time reaches the camera's next frame (frame k at k /
  // rate) or goes back (a new run). Returns whether the picture changed.
  bool Update(mjData* data, double sim_time, std::int64_t seq);
  const FeedPicture& picture() const { return picture_; }
  // The texture holding picture() (RGB, linear filtering); 0 before it.
  unsigned int texture() const { return texture_; }
  // Pictures rendered since the feed was made.
  std::int64_t rendered() const { return rendered_; }
  // Why there is no picture ("" when there is, or no camera).
  const std::string& error() const { return error_; }

 private:
  void Upload();

  std::unique_ptr<CameraImageRenderer> renderer_;
  std::vector<ScenarioCamera> none_;
  long key_ = -1;
  int selected_ = 0;
  bool due_ = true;
  double next_time_ = 0;  // sim time of the chosen camera's next frame
  FeedPicture picture_;
  unsigned int texture_ = 0;
  std::int64_t rendered_ = 0;
  std::string error_;
};

}  // namespace mrsim::studio
