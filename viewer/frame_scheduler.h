// Turns robot-state streams into video frames at fixed simulation-time
// steps of 1/fps: frame k (time k/fps) shows, for every robot, the newest
// state at or before that time, and is due once any state reaches it. A
// viewer that joins late starts at the first frame time after its first
// state; lost states just mean a frame repeats the newest one. It keeps
// only states a frame still to come will show (one per frame at most), so
// a viewer that renders slower than the simulation runs writes every frame
// with its own state once it catches up, up to `history` frames behind.
#pragma once

#include <cstdint>
#include <deque>
#include <vector>

#include "sim_core/scenario/robot_state.h"
#include "sim_core/physics/scene_object_state.h"

namespace mrsim {

class FrameScheduler {
 public:
  struct Frame {
    int64_t index = 0;  // k: frame time is k / fps from simulation time 0
    int64_t utime = 0;  // frame time, us
    // Per robot: the state shown, or null when none has arrived yet.
    std::vector<const RobotState*> states;
    // Per robot: utime of that state (-1 when null); equal keys mean an
    // identical picture for an unchanged camera.
    std::vector<int64_t> key;
    // The scene objects shown (newest scene state at or before the frame
    // time, same rule as robots), or null when none has arrived: then they
    // stay as built. scene_key is its utime, -1 when null.
    const std::vector<SceneObjectState>* scene = nullptr;
    int64_t scene_key = -1;
  };

  // Throws std::invalid_argument for fps outside (0, 1000] or no robots.
  FrameScheduler(double fps, int robot_count, size_t history = 64);

  // Adds a robot's state at simulation time `utime` (us). A state older than
  // the robot's newest is dropped (returns false); a stream that jumps back
  // more than one frame (a simulator reset) restarts the schedule.
  bool Push(int robot, int64_t utime, RobotState state);

  // Adds the scene objects' poses at `utime`. They never make a frame due
  // (robot states do), so the simulator sends them first. An older one than
  // the newest is dropped (false) unless it jumps back more than a frame (a
  // reset), which starts the scene history over.
  bool PushScene(int64_t utime, std::vector<SceneObjectState> objects);

  // The next frame whose time the streams have reached, or false. Pointers
  // in `frame` stay valid until the next Push.
  bool NextFrame(Frame* frame);

  int64_t FrameUtime(int64_t index) const;
  int64_t restarts() const { return restarts_; }

 private:
  struct Entry {
    int64_t utime;
    RobotState state;
  };
  struct SceneEntry {
    int64_t utime;
    std::vector<SceneObjectState> objects;
  };
  int64_t FirstIndexAtOrAfter(int64_t utime) const;
  // True when a state at `older` is shown by no frame still to come once
  // one at `newer` arrived.
  bool Superseded(int64_t older, int64_t newer) const;

  double fps_;
  size_t history_;
  std::vector<std::deque<Entry>> robots_;
  std::deque<SceneEntry> scene_;
  bool started_ = false;
  int64_t next_index_ = 0;
  int64_t clock_ = 0;  // newest utime of any robot
  int64_t restarts_ = 0;
};

}  // namespace mrsim
