// Renders the frames a FrameScheduler says are due and hands them to a
// FrameWriter and a LiveWindow: the heart of mrsim-view, as a class the
// tests drive. A repeated state (lost or late messages) reuses the last
// picture instead of rendering again. The output is opened on the first
// frame, so a run that renders nothing writes nothing.
#pragma once

#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <mutex>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "viewer/frame_scheduler.h"
#include "viewer/frame_writer.h"
#include "viewer/live_window.h"
#include "viewer/state_viewer.h"

namespace mrsim {

class FramePump {
 public:
  using WriterFactory = std::function<std::unique_ptr<FrameWriter>()>;
  // `make_writer` (may be empty: no output) opens the output on the first
  // frame; `window` may be null; `gait_text` (may be empty: the overlay
  // text stays fixed) gives the gait shown in the overlay. The scheduler
  // and gait source may be fed by another thread: they are only read under
  // `mutex`, and rendering works on copies of the states.
  FramePump(StateViewer* viewer, FrameScheduler* scheduler,
            WriterFactory make_writer, LiveWindow* window, int64_t max_frames,
            std::function<std::string()> gait_text, std::mutex* mutex);

  // Renders the frames that are due, at most `max_renders` pictures per
  // call; with a window its input is handled after every picture, and a
  // window asked to close ends the call, whatever the render rate. With a
  // window and no output, frames a slow render fell behind on are dropped
  // (counted in dropped()): only the newest due frame is drawn. Frames are
  // dropped, input never. Returns false once max_frames is reached. Throws what
  // the writer throws.
  // `stop` (may be empty), asked after every frame, ends the call early: a
  // stop signal is not kept waiting by a backlog of frames to write.
  bool Drain(int64_t max_renders = std::numeric_limits<int64_t>::max(),
             const std::function<bool()>& stop = nullptr);
  // Window only: handles input and redraws after camera moves or a resize
  // while no new frame is due.
  void Refresh();
  // Finishes the output (a playable MP4).
  void Close();

  bool Done() const { return max_frames_ > 0 && frames_ >= max_frames_; }
  int64_t frames() const { return frames_; }
  int64_t rendered() const { return rendered_; }
  // Window only: due frames skipped to show a newer one.
  int64_t dropped() const { return dropped_; }
  int64_t first_index() const { return first_index_; }
  double last_time() const { return last_time_; }
  // The output, once the first frame opened it; null before.
  const FrameWriter* writer() const { return writer_.get(); }

 private:
  void RenderLast();

  StateViewer* viewer_;
  FrameScheduler* scheduler_;
  WriterFactory make_writer_;
  std::unique_ptr<FrameWriter> writer_;
  LiveWindow* window_;
  int64_t max_frames_;
  std::function<std::string()> gait_text_;
  std::mutex* mutex_;
  std::string gait_;
  cv::Mat image_;
  bool have_image_ = false;
  std::vector<int64_t> last_key_;
  std::vector<RobotState> last_states_;
  std::vector<bool> last_valid_;
  int64_t last_scene_key_ = -1;
  std::vector<SceneObjectState> last_scene_;
  bool last_scene_valid_ = false;
  int64_t frames_ = 0;
  int64_t rendered_ = 0;
  int64_t dropped_ = 0;
  int64_t first_index_ = -1;
  double last_time_ = 0.0;
};

}  // namespace mrsim
