#include "studio/live/plot_series.h"

#include <utility>

namespace mrsim {

PlotSeries::PlotSeries(std::string channel, std::string column, double window_s)
    : channel_(std::move(channel)),
      column_(std::move(column)),
      window_s_(window_s > 0 ? window_s : 10.0) {}

void PlotSeries::Add(double t, double value) {
  if (paused_) return;
  if (!times_.empty() && t < times_.back()) Clear();
  times_.push_back(t);
  values_.push_back(value);
  ++received_;
  while (!times_.empty() && times_.front() < t - window_s_) {
    times_.pop_front();
    values_.pop_front();
  }
}

void PlotSeries::Clear() {
  times_.clear();
  values_.clear();
}

}  // namespace mrsim
