#include "viewer/frame_scheduler.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

namespace mrsim {

FrameScheduler::FrameScheduler(double fps, int robot_count, size_t history)
    : fps_(fps), history_(history < 2 ? 2 : history) {
  if (!(fps > 0.0 && fps <= 1000.0)) {
    throw std::invalid_argument("frame rate " + std::to_string(fps) +
                                " outside (0, 1000] frames/s");
  }
  if (robot_count < 1) {
    throw std::invalid_argument("FrameScheduler: no robots to show");
  }
  robots_.resize(robot_count);
}

int64_t FrameScheduler::FrameUtime(int64_t index) const {
  return std::llround(static_cast<double>(index) * 1e6 / fps_);
}

int64_t FrameScheduler::FirstIndexAtOrAfter(int64_t utime) const {
  int64_t k = static_cast<int64_t>(
      std::ceil(static_cast<double>(utime) * fps_ / 1e6 - 1e-6));
  while (k > 0 && FrameUtime(k - 1) >= utime) --k;
  while (FrameUtime(k) < utime) ++k;
  return k;
}

bool FrameScheduler::Superseded(int64_t older, int64_t newer) const {
  if (!started_) return false;
  // The frames still to come that would show `older` are those whose time
  // is in [older, newer): none, and no frame ever shows it.
  const int64_t k = std::max(next_index_, FirstIndexAtOrAfter(older));
  return FrameUtime(k) >= newer;
}

bool FrameScheduler::Push(int robot, int64_t utime, RobotState state) {
  if (robot < 0 || robot >= static_cast<int>(robots_.size())) return false;
  std::deque<Entry>& h = robots_[robot];
  if (started_ && utime < clock_ - FrameUtime(1)) {
    // The simulation went back (reset or checkpoint load): start over.
    for (auto& r : robots_) r.clear();
    // Scene states of the new run (sent before this state) stay.
    while (!scene_.empty() && scene_.back().utime > utime) scene_.pop_back();
    started_ = false;
    ++restarts_;
  }
  if (!h.empty() && utime < h.back().utime) return false;
  if (!h.empty() && utime == h.back().utime) {
    h.back().state = std::move(state);  // a resend replaces
  } else {
    if (!h.empty() && Superseded(h.back().utime, utime)) h.pop_back();
    h.push_back(Entry{utime, std::move(state)});
  }
  while (h.size() > history_) h.pop_front();
  if (!started_) {
    started_ = true;
    clock_ = utime;
    next_index_ = FirstIndexAtOrAfter(utime);
  }
  if (utime > clock_) clock_ = utime;
  return true;
}

bool FrameScheduler::PushScene(int64_t utime,
                               std::vector<SceneObjectState> objects) {
  if (!scene_.empty() && utime < scene_.back().utime) {
    if (utime >= scene_.back().utime - FrameUtime(1)) return false;
    scene_.clear();  // the simulation went back
  }
  if (!scene_.empty() && utime == scene_.back().utime) {
    scene_.back().objects = std::move(objects);  // a resend replaces
  } else {
    if (!scene_.empty() && Superseded(scene_.back().utime, utime)) {
      scene_.pop_back();
    }
    scene_.push_back(SceneEntry{utime, std::move(objects)});
  }
  while (scene_.size() > history_) scene_.pop_front();
  return true;
}

bool FrameScheduler::NextFrame(Frame* frame) {
  if (!started_) return false;
  const int64_t t = FrameUtime(next_index_);
  if (clock_ < t) return false;
  frame->index = next_index_;
  frame->utime = t;
  frame->states.assign(robots_.size(), nullptr);
  frame->key.assign(robots_.size(), -1);
  for (size_t r = 0; r < robots_.size(); ++r) {
    std::deque<Entry>& h = robots_[r];
    // Older entries are never needed again: later frames want newer ones.
    while (h.size() > 1 && h[1].utime <= t) h.pop_front();
    // The newest state at or before t; when history no longer reaches back
    // that far (a burst evicted it), the oldest one kept is the closest.
    if (!h.empty()) {
      frame->states[r] = &h.front().state;
      frame->key[r] = h.front().utime;
    }
  }
  while (scene_.size() > 1 && scene_[1].utime <= t) scene_.pop_front();
  frame->scene = nullptr;
  frame->scene_key = -1;
  if (!scene_.empty()) {
    frame->scene = &scene_.front().objects;
    frame->scene_key = scene_.front().utime;
  }
  ++next_index_;
  return true;
}

}  // namespace mrsim
