// One live plot: a numeric column of one channel against the message time,
// scrolling over a time window. Holds exactly the values the messages
// carried (parsed from the same shortest round-trip text mrsim-log writes).
#pragma once

#include <cstdint>
#include <deque>
#include <string>

namespace mrsim::studio {

class PlotSeries {
 public:
  PlotSeries(std::string channel, std::string column, double window_s);

  // A point at message time t (s). Points older than the newest minus the
  // window are dropped; a paused plot takes none. A point the plot already
  // holds (same time, same value: a re-sent state) is ignored; any other
  // time not after the newest (a reset or a loaded checkpoint) starts the
  // plot afresh.
  void Add(double t, double value);
  void Clear();

  const std::string& channel() const { return channel_; }
  const std::string& column() const { return column_; }
  double window_s() const { return window_s_; }
  void set_window_s(double s) { window_s_ = s > 0 ? s : window_s_; }
  bool paused() const { return paused_; }
  void set_paused(bool paused) { paused_ = paused; }
  const std::deque<double>& times() const { return times_; }
  const std::deque<double>& values() const { return values_; }
  int64_t received() const { return received_; }

 private:
  bool IsResend(double t, double value) const;

  std::string channel_;
  std::string column_;
  double window_s_;
  bool paused_ = false;
  std::deque<double> times_;
  std::deque<double> values_;
  int64_t received_ = 0;
};

}  // namespace mrsim::studio
