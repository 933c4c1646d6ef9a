#include "studio/live/plot_series.h"

#include <cmath>
#include <utility>

namespace mrsim::studio {

PlotSeries::PlotSeries(std::string channel, std::string column, double window_s)
    : channel_(std::move(channel)),
      column_(std::move(column)),
      window_s_(window_s > 0 ? window_s : 10.0) {}

void PlotSeries::Add(double t, double value) {
  if (paused_) return;
  if (!times_.empty() && t <= times_.back()) {
    if (IsResend(t, value)) return;
    Clear();
  }
  times_.push_back(t);
  values_.push_back(value);
  ++received_;
  while (!times_.empty() && times_.front() < t - window_s_) {
    times_.pop_front();
    values_.pop_front();
  }
}

bool PlotSeries::IsResend(double t, double value) const {
  // A lockstep simulator re-sends the states it awaits (pipelined: the
  // older one first), so a re-send can be a few samples back.
  constexpr size_t kDepth = 8;
  for (size_t k = 0; k < kDepth && k < times_.size(); ++k) {
    const size_t i = times_.size() - 1 - k;
    if (times_[i] < t) return false;
    const double v = values_[i];
    if (times_[i] == t &&
        (v == value || (std::isnan(v) && std::isnan(value)))) {
      return true;
    }
  }
  return false;
}

void PlotSeries::Clear() {
  times_.clear();
  values_.clear();
}

}  // namespace mrsim::studio
