#include "viewer/frame_pump.h"

#include <utility>

namespace mrsim {

FramePump::FramePump(StateViewer* viewer, FrameScheduler* scheduler,
                     WriterFactory make_writer, LiveWindow* window,
                     int64_t max_frames, std::function<std::string()> gait_text,
                     std::mutex* mutex)
    : viewer_(viewer),
      scheduler_(scheduler),
      make_writer_(std::move(make_writer)),
      window_(window),
      max_frames_(max_frames),
      gait_text_(std::move(gait_text)),
      mutex_(mutex) {}

bool FramePump::Drain(int64_t max_renders, const std::function<bool()>& stop) {
  // Only a window shows frames nobody keeps: those may be skipped.
  const bool newest_only = window_ != nullptr && !make_writer_;
  int64_t renders = 0;
  while (!Done() && renders < max_renders) {
    FrameScheduler::Frame frame;
    bool changed = window_ != nullptr && window_->TakeCameraChanged();
    {
      std::lock_guard<std::mutex> lock(*mutex_);
      if (gait_text_) {
        std::string gait = gait_text_();
        if (gait != gait_) {
          gait_ = std::move(gait);
          viewer_->set_gait(gait_);
          changed = true;
        }
      }
      if (!scheduler_->NextFrame(&frame)) return true;
      // Pointers of an earlier frame stay valid until the next Push, which
      // needs the mutex held here.
      for (FrameScheduler::Frame newer;
           newest_only && scheduler_->NextFrame(&newer);) {
        frame = std::move(newer);
        ++dropped_;
      }
      // A repeated state (lost or late messages) gives the same picture.
      changed = changed || !have_image_ || frame.key != last_key_ ||
                frame.scene_key != last_scene_key_;
      if (changed) {
        last_scene_valid_ = frame.scene != nullptr;
        last_scene_ =
            frame.scene ? *frame.scene : std::vector<SceneObjectState>();
        last_states_.clear();
        last_valid_.clear();
        for (const RobotState* s : frame.states) {
          last_states_.push_back(s ? *s : RobotState());
          last_valid_.push_back(s != nullptr);
        }
      }
    }
    if (changed) {
      RenderLast();
      last_key_ = frame.key;
      last_scene_key_ = frame.scene_key;
      ++rendered_;
      ++renders;
    }
    if (first_index_ < 0) first_index_ = frame.index;
    last_time_ = frame.utime * 1e-6;
    if (!writer_ && make_writer_) writer_ = make_writer_();
    if (writer_) writer_->Write(image_, frame.index);
    ++frames_;
    if (stop && stop()) return true;
    if (changed && window_ != nullptr) {
      // Input between pictures, however many are due: q and Esc act at
      // once, drags and zoom apply to the next picture.
      window_->PollEvents();
      if (window_->ShouldClose()) return true;
    }
  }
  return false;
}

void FramePump::Refresh() {
  if (window_ == nullptr) return;
  window_->PollEvents();
  if (!have_image_ || !window_->TakeCameraChanged()) return;
  RenderLast();
}

void FramePump::Close() {
  if (writer_) writer_->Close();
}

void FramePump::RenderLast() {
  std::vector<const RobotState*> states;
  for (size_t r = 0; r < last_states_.size(); ++r) {
    states.push_back(last_valid_[r] ? &last_states_[r] : nullptr);
  }
  viewer_->Render(states, &image_, last_scene_valid_ ? &last_scene_ : nullptr);
  have_image_ = true;
  if (window_ != nullptr) {
    viewer_->RenderToWindow(window_->width(), window_->height());
    window_->SwapBuffers();
  }
}

}  // namespace mrsim
