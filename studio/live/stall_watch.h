// Notices an optimisation that is alive but no longer moving (workers gone,
// a farm nobody serves): no new generation for longer than
// max(min_s, factor x the longest generation so far). Plain logic on a
// count and the time, so tests drive it with a fake clock.
#pragma once

#include <optional>

#include "lcmtypes/runtime/outbox.h"

namespace mrsim::studio {

class StallWatch {
 public:
  explicit StallWatch(double min_s = 30, double factor = 5)
      : min_s_(min_s), factor_(factor) {}

  // The run (re)starts now with `count` generations done.
  void Start(long count, WallTime now);
  // `count` generations are done now; a higher count is progress.
  void Update(long count, WallTime now);
  // How long without progress is still normal (s).
  double Bound() const;
  // Seconds since the last progress when that is over Bound(); nothing
  // before Start or while progress is normal.
  std::optional<double> Stalled(WallTime now) const;
  // The longest generation seen so far (s; 0 before the first).
  double longest() const { return longest_; }

 private:
  double min_s_;
  double factor_;
  bool started_ = false;
  long count_ = 0;
  WallTime last_;
  double longest_ = 0;
};

}  // namespace mrsim::studio
