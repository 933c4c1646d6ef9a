#include "logger/process/log_command.h"

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <thread>

#include "CLI/CLI.hpp"
#include "common/lcm_url.h"
#include "lcmtypes/runtime/auth_flags.h"
#include "lcmtypes/runtime/channel_pattern.h"
#include "lcmtypes/runtime/decode.h"
#include "lcmtypes/runtime/lcm_loop.h"
#include "lcmtypes/runtime/simulator_watch.h"
#include "lcmtypes/runtime/stop_signal.h"
#include "logger/lcm_type_registry.h"
#include "logger/mcap/mcap_recorder.h"
#include "logger/message_queue.h"

namespace mrsim {
namespace {

using Clock = std::chrono::steady_clock;

// Messages queued per subscription before LCM drops them: 1 kHz of a large
// state for several seconds of a slow disk.
constexpr int kQueueCapacity = 20000;
// The writer takes what arrived every kWriterPeriod, or sooner once a
// quarter of the queue's room is used: a few wake-ups per second instead of
// one per message, with rows on disk at the same flush interval as before.
constexpr std::chrono::milliseconds kWriterPeriod(20);
// How long received messages wait in LCM's queue to be taken together.
// The subscription holds kQueueCapacity of them, and LCM's receive thread
// grows its buffer rather than drop one.
constexpr std::chrono::milliseconds kTakePeriod(4);

void OnLcm(const lcm::ReceiveBuffer* rbuf, const std::string& channel,
           MessageQueue* queue) {
  try {
    queue->Push(channel, rbuf->data, rbuf->data_size, rbuf->recv_utime);
  } catch (const std::exception&) {
    // Out of memory for one copy: the seq gap will show it; LCM's C code
    // must not see an exception.
  }
}

// Where messages go: one CSV per channel (Recorder) or one MCAP file
// (McapRecorder). Live logging and replay feed either the same way.
class LogSink {
 public:
  virtual ~LogSink() = default;
  // utime: when the message was received or logged (us since the epoch).
  virtual void OnMessage(const std::string& channel, const void* data,
                         size_t size, int64_t utime) = 0;
  // Called every writer wake-up: puts what is buffered on disk at the
  // sink's own pace. Never throws (failed() tells).
  virtual void Periodic() = 0;
  // At the end: flush (CSV) or write the summary and footer (MCAP).
  virtual void Finish() = 0;
  virtual bool failed() const = 0;
  virtual const std::string& error() const = 0;
  virtual int64_t messages() const = 0;
  virtual std::vector<ChannelStats> Stats() const = 0;
  virtual std::string Summary() const = 0;
  virtual std::string where() const = 0;
};

class CsvSink : public LogSink {
 public:
  CsvSink(const LcmTypeRegistry& registry, RecorderOptions options)
      : recorder_(registry, std::move(options)) {}
  void OnMessage(const std::string& channel, const void* data, size_t size,
                 int64_t) override {
    recorder_.OnMessage(channel, data, size);
  }
  void Periodic() override {
    const auto now = Clock::now();
    if (now - last_flush_ < std::chrono::milliseconds(500)) return;
    last_flush_ = now;
    try {
      recorder_.Flush();
    } catch (const std::exception&) {
      // recorder_.error() holds it.
    }
  }
  void Finish() override { recorder_.Flush(); }
  bool failed() const override { return recorder_.failed(); }
  const std::string& error() const override { return recorder_.error(); }
  int64_t messages() const override { return recorder_.messages(); }
  std::vector<ChannelStats> Stats() const override { return recorder_.Stats(); }
  std::string Summary() const override { return recorder_.Summary(); }
  std::string where() const override { return recorder_.out_dir(); }
  const Recorder& recorder() const { return recorder_; }

 private:
  Recorder recorder_;
  Clock::time_point last_flush_ = Clock::now();
};

class McapSink : public LogSink {
 public:
  explicit McapSink(McapRecorderOptions options)
      : recorder_(std::move(options)) {}
  void OnMessage(const std::string& channel, const void* data, size_t size,
                 int64_t utime) override {
    recorder_.OnMessage(
        channel, data, size,
        static_cast<uint64_t>(std::max<int64_t>(utime, 0)) * 1000);
  }
  void Periodic() override {
    // A chunk on disk at least every second, so a killed logger loses at
    // most that.
    const auto now = std::chrono::system_clock::now().time_since_epoch();
    recorder_.Tick(static_cast<uint64_t>(
        std::chrono::duration_cast<std::chrono::nanoseconds>(now).count()));
  }
  void Finish() override { recorder_.Finish(); }
  bool failed() const override { return recorder_.failed(); }
  const std::string& error() const override { return recorder_.error(); }
  int64_t messages() const override { return recorder_.messages(); }
  std::vector<ChannelStats> Stats() const override { return recorder_.Stats(); }
  std::string Summary() const override { return recorder_.Summary(); }
  std::string where() const override { return recorder_.path(); }

 private:
  McapRecorder recorder_;
};

// --exit-with-sim: the simulator's statuses, heard on LCM's thread (the
// one that also runs the loop below), tell the watch when it stops.
struct StatusFollower {
  SimulatorWatch watch;
  std::vector<std::string> log;

  static void On(const lcm::ReceiveBuffer* rbuf, const std::string&,
                 StatusFollower* self) {
    try {
      sim_status_t status;
      if (DecodeMessage(rbuf, &status)) {
        self->watch.OnStatus(status, WallClock::now(), &self->log);
      }
    } catch (const std::exception&) {
      // A status that cannot be decoded is no word from the simulator;
      // LCM's C code must not see an exception.
    }
  }
};

void Progress(const LogSink& recorder, bool quiet, std::FILE* err) {
  if (quiet) return;
  int64_t missing = 0;
  const auto stats = recorder.Stats();
  for (const auto& s : stats) missing += s.missing;
  std::fprintf(err, "mrsim-log: %lld messages on %zu channels, %lld missing\n",
               static_cast<long long>(recorder.messages()), stats.size(),
               static_cast<long long>(missing));
}

// Formats and writes what the LCM thread queued, so receiving never waits
// on the disk.
void WriteQueued(MessageQueue& queue, LogSink& recorder,
                 std::atomic<bool>& failed, bool quiet, std::FILE* err) {
  std::vector<QueuedMessage> batch;
  auto last_progress = Clock::now();
  while (queue.PopAll(&batch, kWriterPeriod)) {
    for (const QueuedMessage& m : batch) {
      recorder.OnMessage(m.channel, m.data.data(), m.data.size(), m.recv_utime);
    }
    batch.clear();
    recorder.Periodic();
    if (recorder.failed()) failed = true;
    const auto now = Clock::now();
    if (now - last_progress > std::chrono::seconds(10)) {
      last_progress = now;
      Progress(recorder, quiet, err);
    }
  }
}

void RunLive(const LogCommand& opt, const std::string& regex, LogSink& recorder,
             SignedLcm& lcm, std::FILE* err) {
  if (!lcm.good()) {
    throw std::runtime_error(
        CannotOpenLcm(LcmUrlWithReceiveBuffer(opt.lcm_url, opt.recv_buf_size)));
  }
  const size_t max_queue_bytes = static_cast<size_t>(opt.max_queue_mb) << 20;
  MessageQueue queue(max_queue_bytes, max_queue_bytes / 4);
  std::atomic<bool> failed{false};
  std::thread writer(WriteQueued, std::ref(queue), std::ref(recorder),
                     std::ref(failed), opt.quiet, err);
  lcm::Subscription* sub = lcm.subscribeFunction(regex, &OnLcm, &queue);
  sub->setQueueCapacity(kQueueCapacity);
  StatusFollower follower{SimulatorWatch(SimStatusChannel(opt.prefix),
                                         opt.exit_with_sim, WallClock::now()),
                          {}};
  lcm::Subscription* status_sub =
      opt.exit_with_sim ? lcm.subscribeFunction(SimStatusChannel(opt.prefix),
                                                &StatusFollower::On, &follower)
                        : nullptr;
  const auto sim_gone = [&] {
    if (!opt.exit_with_sim) return false;
    follower.watch.Tick(WallClock::now(), &follower.log);
    for (const std::string& line : follower.log) {
      std::fprintf(err, "mrsim-log: %s\n", line.c_str());
    }
    follower.log.clear();
    return follower.watch.stopped();
  };
  if (!opt.quiet) {
    std::fprintf(err, "mrsim-log: recording channels matching '%s' to %s\n",
                 regex.c_str(), recorder.where().c_str());
  }
  try {
    while (!StopRequested() && !failed && !sim_gone()) {
      // Messages wait in LCM's queue for a few milliseconds and are taken
      // together: this thread wakes a few hundred times a second, not once
      // per message.
      if (HandleFor(lcm, 100) > 0) std::this_thread::sleep_for(kTakePeriod);
    }
    // Take what already arrived before stopping, but do not wait on a
    // publisher that never pauses.
    const auto drain_end = Clock::now() + std::chrono::milliseconds(300);
    while (!failed && Clock::now() < drain_end && HandleFor(lcm, 20) > 0) {
    }
  } catch (...) {
    queue.Close();
    writer.join();
    throw;
  }
  lcm.unsubscribe(sub);
  if (status_sub != nullptr) lcm.unsubscribe(status_sub);
  queue.Close();
  writer.join();
  if (queue.dropped() > 0) {
    std::fprintf(err,
                 "mrsim-log: %lld messages dropped: the writer fell behind by "
                 "more than --max-queue-mb (%lld MB)\n",
                 static_cast<long long>(queue.dropped()),
                 static_cast<long long>(opt.max_queue_mb));
  }
}

// Replays an .lcmlog. A file with no LCM event in it (not a log) or with
// none on the channels asked is bad input: nothing is written.
void RunFromLog(const LogCommand& opt, const std::string& regex,
                LogSink& recorder, std::FILE* err) {
  lcm::LogFile log(opt.from_log, "r");
  if (!log.good()) {
    throw LogInputError("cannot read LCM log " + opt.from_log);
  }
  const std::regex re(regex, std::regex::ECMAScript);
  auto last_progress = Clock::now();
  int64_t events = 0, matched = 0;
  std::vector<std::string> seen;  // channels in the log, for the error
  while (!StopRequested() && !recorder.failed()) {
    const lcm::LogEvent* ev = log.readNextEvent();
    if (ev == nullptr) break;
    ++events;
    if (!std::regex_match(ev->channel, re)) {
      if (seen.size() < 20 &&
          std::find(seen.begin(), seen.end(), ev->channel) == seen.end()) {
        seen.push_back(ev->channel);
      }
      continue;
    }
    ++matched;
    recorder.OnMessage(ev->channel, ev->data, static_cast<size_t>(ev->datalen),
                       ev->timestamp);
    if ((events & 1023) == 0 &&
        Clock::now() - last_progress > std::chrono::seconds(5)) {
      last_progress = Clock::now();
      Progress(recorder, opt.quiet, err);
    }
  }
  if (events == 0 && !StopRequested()) {
    throw LogInputError(opt.from_log +
                        ": not an LCM log (no LCM event found in it; record "
                        "one with lcm-logger)");
  }
  if (matched == 0 && !StopRequested()) {
    std::string list;
    for (const std::string& c : seen) list += (list.empty() ? "" : ", ") + c;
    throw LogInputError(opt.from_log + ": no message on channels matching '" +
                        regex + "' (the log has " + std::to_string(events) +
                        " messages on: " + list +
                        "; choose with --prefix or --channels)");
  }
}

// Draws the --plot charts from the CSVs just written. Returns the exit
// status: 0, or 2 when a chart could not be drawn from its input.
int WritePlots(const std::vector<LogPlotSpec>& plots, const Recorder& recorder,
               std::FILE* err) {
  int status = 0;
  for (const LogPlotSpec& spec : plots) {
    const std::string csv = recorder.CsvPath(spec.channel);
    if (csv.empty()) {
      std::fprintf(err,
                   "mrsim-log: plot of %s: nothing was recorded on "
                   "that channel\n",
                   spec.channel.c_str());
      status = 2;
      continue;
    }
    // Lexically normal: "out/csv/../front.png" is printed as "out/front.png".
    const std::string out =
        spec.out.front() == '/'
            ? spec.out
            : (std::filesystem::path(recorder.out_dir()) / spec.out)
                  .lexically_normal()
                  .string();
    try {
      PlotCsvToPng(csv, spec.options, out);
      std::fprintf(err, "mrsim-log: wrote plot %s\n", out.c_str());
    } catch (const PlotInputError& e) {
      std::fprintf(err, "mrsim-log: plot: %s\n", e.what());
      status = 2;
    } catch (const std::exception& e) {
      std::fprintf(err, "mrsim-log: plot: %s\n", e.what());
      status = 1;
    }
  }
  return status;
}

}  // namespace

// A comma-separated list of channel names becomes an alternation of
// literal names; anything else is used as a regular expression.
std::string ChannelRegex(const std::string& channels) {
  if (channels.find(',') == std::string::npos) return channels;
  std::string out;
  size_t start = 0;
  while (start <= channels.size()) {
    size_t end = channels.find(',', start);
    if (end == std::string::npos) end = channels.size();
    std::string name = channels.substr(start, end - start);
    if (!name.empty()) {
      if (!out.empty()) out += "|";
      out += LiteralChannelPattern(name);
    }
    start = end + 1;
  }
  return out;
}

void AddLogFlags(CLI::App& app, LogCommand& opt) {
  app.add_option("--lcm-url", opt.lcm_url,
                 "LCM URL (default: LCM's default or $LCM_DEFAULT_URL)");
  AddAuthFlags(app, opt.auth);
  app.add_option("--prefix", opt.prefix,
                 "channel prefix; by default every channel starting with "
                 "PREFIX_ is recorded")
      ->capture_default_str();
  app.add_option("--channels", opt.channels,
                 "channels to record: a regular expression (whole name) or "
                 "a comma-separated list of names");
  app.add_option("--out", opt.out_dir, "output folder (created if needed)")
      ->capture_default_str();
  app.add_option("--from-log,--from", opt.from_log,
                 "read this .lcmlog (from lcm-logger) instead of the network");
  auto* mcap =
      app.add_option("--mcap", opt.mcap,
                     "write one indexed MCAP file (protobuf or JSON messages "
                     "with their schemas, for Foxglove and PlotJuggler) "
                     "instead of CSVs");
  app.add_option("--mcap-compression", opt.mcap_compression,
                 "how --mcap stores its chunks: zstd (a file about a third "
                 "of the .lcmlog's size) or none (no compression CPU, a file "
                 "about 2.4 times the .lcmlog's); every MCAP reader reads both")
      ->capture_default_str()
      ->check(CLI::IsMember({"zstd", "none"}))
      ->needs(mcap);
  app.add_option("--mcap-encoding", opt.mcap_encoding,
                 "how --mcap stores each message: protobuf (schemas made "
                 "from the .lcm definitions; the least CPU and the smallest "
                 "file) or json (with JSON Schemas, for readers without "
                 "protobuf)")
      ->capture_default_str()
      ->check(CLI::IsMember({"protobuf", "json"}))
      ->needs(mcap);
  app.add_option("--types", opt.types,
                 "extra .lcm files or folders with message definitions "
                 "(CSV only)")
      ->excludes(mcap);
  app.add_option("--plot", opt.plots,
                 "draw a PNG when logging stops (repeatable): "
                 "CHANNEL:y=COL[,COL...][:x=COL][:title=TEXT]"
                 "[:style=auto|lines|points][:size=WxH][:out=FILE.png]; "
                 "x defaults to time, a relative FILE is in --out")
      ->excludes(mcap);
  app.add_option("--recv-buf-size", opt.recv_buf_size,
                 "kernel receive buffer (bytes) asked for on udpm URLs that "
                 "do not set recv_buf_size (capped by net.core.rmem_max); 0 "
                 "keeps the URL as given")
      ->capture_default_str();
  app.add_option("--max-queue-mb", opt.max_queue_mb,
                 "messages received but not yet written, at most (MB)")
      ->capture_default_str()
      ->check(CLI::Validator(
          [](std::string& text) {
            char* end = nullptr;
            const double mb = std::strtod(text.c_str(), &end);
            return *end == '\0' && mb > 0 && std::isfinite(mb)
                       ? std::string()
                       : "expected a number of MB > 0, got " + text;
          },
          "MB > 0"));
  app.add_flag("--quiet", opt.quiet, "no progress lines");
  app.add_flag("--exit-with-sim", opt.exit_with_sim,
               "stop when the simulator stops (or is silent for 5 s), after "
               "writing what already arrived")
      ->excludes("--from-log");
  mcap->excludes("--out");
}

LogPlan PlanLog(const LogCommand& opt) {
  LogPlan plan;
  plan.regex =
      opt.channels.empty() ? opt.prefix + "_.*" : ChannelRegex(opt.channels);
  try {
    std::regex check(plan.regex, std::regex::ECMAScript);
  } catch (const std::regex_error& e) {
    throw LogInputError("--channels '" + opt.channels +
                        "' is not a valid regular expression: " + e.what());
  }
  for (const std::string& p : opt.plots) {
    try {
      plan.plots.push_back(ParseLogPlotSpec(p));
    } catch (const std::exception& e) {
      throw LogInputError(e.what());
    }
  }
  if (!opt.from_log.empty() && !std::ifstream(opt.from_log)) {
    throw LogInputError("cannot read LCM log file " + opt.from_log);
  }
  return plan;
}

int RunLogCommand(const LogCommand& opt, const LogPlan& plan, SignedLcm* lcm,
                  std::FILE* err) {
  LcmTypeRegistry registry = LcmTypeRegistry::WithBuiltinTypes();
  for (const std::string& w : registry.warnings()) {
    std::fprintf(err, "mrsim-log: warning: %s\n", w.c_str());
  }
  for (const std::string& t : opt.types) {
    try {
      registry.AddPath(t);
    } catch (const std::exception& e) {
      throw LogInputError(e.what());
    }
  }
  const auto report = [err](const std::string& text) {
    std::fprintf(err, "mrsim-log: %s\n", text.c_str());
  };
  const bool out_dir_existed = std::filesystem::exists(opt.out_dir);
  std::unique_ptr<LogSink> sink;
  CsvSink* csv = nullptr;
  if (opt.mcap.empty()) {
    RecorderOptions recorder_options;
    recorder_options.out_dir = opt.out_dir;
    recorder_options.report = report;
    auto made = std::make_unique<CsvSink>(registry, recorder_options);
    csv = made.get();
    sink = std::move(made);
  } else {
    McapRecorderOptions mcap_options;
    mcap_options.path = opt.mcap;
    mcap_options.report = report;
    mcap_options.compression = opt.mcap_compression == "none"
                                   ? mcap::ChunkCompression::kNone
                                   : mcap::ChunkCompression::kZstd;
    mcap_options.encoding = opt.mcap_encoding == "json"
                                ? McapEncoding::kJson
                                : McapEncoding::kProtobuf;
    sink = std::make_unique<McapSink>(mcap_options);
  }
  LogSink& recorder = *sink;
  if (opt.from_log.empty()) {
    if (lcm == nullptr) throw std::logic_error("live logging needs an LCM");
    RunLive(opt, plan.regex, recorder, *lcm, err);
  } else {
    try {
      RunFromLog(opt, plan.regex, recorder, err);
    } catch (const LogInputError&) {
      // Bad input writes nothing: not even the folder or file made for it.
      std::error_code ec;
      if (!opt.mcap.empty()) {
        sink.reset();
        std::filesystem::remove(opt.mcap, ec);
      } else if (!out_dir_existed &&
                 std::filesystem::is_empty(opt.out_dir, ec)) {
        std::filesystem::remove(opt.out_dir, ec);
      }
      throw;
    }
  }
  // Files that did not fail keep everything, even after another failed.
  try {
    recorder.Finish();
  } catch (const std::exception&) {
    // recorder.error() holds it.
  }
  std::fprintf(err, "mrsim-log: summary\n%s\n", recorder.Summary().c_str());
  if (recorder.failed()) {
    std::fprintf(err, "mrsim-log: error: %s\n", recorder.error().c_str());
    return 1;
  }
  if (opt.from_log.empty() && recorder.messages() == 0) {
    // Most often a --prefix or --lcm-url that is not the simulator's.
    std::fprintf(err,
                 "mrsim-log: nothing recorded: no message on channels "
                 "matching '%s' (is mrsim-sim running, with the same "
                 "--lcm-url and --prefix?)\n",
                 plan.regex.c_str());
    return 1;
  }
  if (csv == nullptr) return 0;
  return WritePlots(plan.plots, csv->recorder(), err);
}

}  // namespace mrsim
