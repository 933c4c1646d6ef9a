// mrsim-log as library code: its flags, the channel selection, recording
// live (LCM handler -> queue -> writer thread) or from an .lcmlog, the
// summary and the plots at stop. main parses, owns the SignedLcm and calls
// RunLogCommand.
#pragma once

#include <cstdint>
#include <cstdio>
#include <lcm/lcm-cpp.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "lcmtypes/runtime/channels.h"
#include "lcmtypes/runtime/message_key.h"
#include "lcmtypes/runtime/signed_lcm.h"
#include "logger/log_plot_spec.h"
#include "logger/recorder.h"

namespace CLI {
class App;
}

namespace mrsim {

struct LogCommand {
  std::string lcm_url;
  AuthFlags auth;  // --key-file, --accept-replays
  std::string prefix = kDefaultChannelPrefix;
  std::string channels;
  std::string out_dir = ".";
  std::string from_log;
  std::string mcap;  // --mcap FILE: one MCAP file instead of the CSVs
  // --mcap-compression: "zstd" or "none" (the chunks as they are).
  std::string mcap_compression = "zstd";
  // --mcap-encoding: "protobuf" or "json" (for readers without protobuf).
  std::string mcap_encoding = "protobuf";
  std::vector<std::string> types;
  std::vector<std::string> plots;
  int64_t recv_buf_size = 8 << 20;
  int64_t max_queue_mb = 1024;
  bool quiet = false;
  // Live only: stop when the simulator says it stops (or is silent for
  // SimulatorWatch::kSimulatorSilence), after taking what already arrived.
  bool exit_with_sim = false;
};

void AddLogFlags(CLI::App& app, LogCommand& command);

// Bad input (flags, plot specs, a file that is not an LCM log, nothing to
// record in it): exit status 2.
class LogInputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A comma-separated list of channel names becomes an alternation of
// literal names; anything else is used as a regular expression.
std::string ChannelRegex(const std::string& channels);

// The checked parts of a command: the channel regex (whole-name match) and
// the parsed plots. Throws LogInputError.
struct LogPlan {
  std::string regex;
  std::vector<LogPlotSpec> plots;
};
LogPlan PlanLog(const LogCommand& command);

// Records until a stop is requested (live) or the log ends, then flushes,
// prints the summary on `err` and draws the plots. `lcm` is the open
// connection for a live run (unused with --from-log). Returns the exit
// status: 0, 1 (a write failed) or 2 (a plot could not be drawn from its
// input). Throws LogInputError (a file that is not an LCM log, no message
// on the channels asked) or std::runtime_error.
int RunLogCommand(const LogCommand& command, const LogPlan& plan,
                  SignedLcm* lcm, std::FILE* err);

}  // namespace mrsim
