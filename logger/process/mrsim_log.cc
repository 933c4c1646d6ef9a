// mrsim-log: writes every mrsim channel (or the chosen ones) to one CSV per
// channel, live from LCM or from an .lcmlog file, reports sequence gaps and
// optionally draws plots when it stops.
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <lcm/lcm-cpp.hpp>
#include <regex>
#include <string>
#include <thread>
#include <vector>

#include "CLI/CLI.hpp"
#include "common/version.h"
#include "lcmtypes/runtime/channels.h"
#include "lcmtypes/runtime/lcm_loop.h"
#include "lcmtypes/runtime/stop_signal.h"
#include "logger/lcm_type_registry.h"
#include "logger/log_plot_spec.h"
#include "logger/message_queue.h"
#include "logger/recorder.h"

namespace {

using Clock = std::chrono::steady_clock;

// Messages queued per subscription before LCM drops them: 1 kHz of a large
// state for several seconds of a slow disk.
constexpr int kQueueCapacity = 20000;

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
      for (char c : name) {
        if (std::string("\\^$.|?*+()[]{}").find(c) != std::string::npos) {
          out += '\\';
        }
        out += c;
      }
    }
    start = end + 1;
  }
  return out;
}

struct Options {
  std::string lcm_url;
  std::string prefix = mrsim::kDefaultChannelPrefix;
  std::string channels;
  std::string out_dir = ".";
  std::string from_log;
  std::vector<std::string> types;
  std::vector<std::string> plots;
  int64_t recv_buf_size = 8 << 20;
  int64_t max_queue_mb = 1024;
  bool quiet = false;
};

void OnLcm(const lcm::ReceiveBuffer* rbuf, const std::string& channel,
           mrsim::MessageQueue* queue) {
  try {
    queue->Push(channel, rbuf->data, rbuf->data_size);
  } catch (const std::exception&) {
    // Out of memory for one copy: the seq gap will show it; LCM's C code
    // must not see an exception.
  }
}

void Progress(const mrsim::Recorder& recorder, bool quiet) {
  if (quiet) return;
  int64_t missing = 0;
  const auto stats = recorder.Stats();
  for (const auto& s : stats) missing += s.missing;
  std::fprintf(stderr,
               "mrsim-log: %lld messages on %zu channels, %lld missing\n",
               static_cast<long long>(recorder.messages()), stats.size(),
               static_cast<long long>(missing));
}

// The URL with a large kernel receive buffer, unless it sets one: a 1 kHz
// stream of 12 kB states fills the default buffer in a few milliseconds of
// not being scheduled.
std::string WithReceiveBuffer(const std::string& url, int64_t bytes) {
  std::string u = url;
  if (u.empty()) {
    const char* env = std::getenv("LCM_DEFAULT_URL");
    u = env != nullptr ? env : "udpm://239.255.76.67:7667?ttl=0";
  }
  if (u.rfind("udpm://", 0) != 0 || bytes <= 0 ||
      u.find("recv_buf_size=") != std::string::npos) {
    return u;
  }
  return u + (u.find('?') == std::string::npos ? "?" : "&") +
         "recv_buf_size=" + std::to_string(bytes);
}

// Formats and writes what the LCM thread queued, so receiving never waits
// on the disk.
void WriteQueued(mrsim::MessageQueue& queue, mrsim::Recorder& recorder,
                 std::atomic<bool>& failed, bool quiet) {
  std::vector<mrsim::QueuedMessage> batch;
  auto last_flush = Clock::now();
  auto last_progress = Clock::now();
  while (queue.PopAll(&batch, std::chrono::milliseconds(100))) {
    for (const mrsim::QueuedMessage& m : batch) {
      recorder.OnMessage(m.channel, m.data.data(), m.data.size());
    }
    batch.clear();
    const auto now = Clock::now();
    if (now - last_flush > std::chrono::milliseconds(500)) {
      last_flush = now;
      try {
        recorder.Flush();
      } catch (const std::exception&) {
        // recorder.error() holds it.
      }
    }
    if (recorder.failed()) failed = true;
    if (now - last_progress > std::chrono::seconds(10)) {
      last_progress = now;
      Progress(recorder, quiet);
    }
  }
}

int RunLive(const Options& opt, const std::string& regex,
            mrsim::Recorder& recorder) {
  const std::string url = WithReceiveBuffer(opt.lcm_url, opt.recv_buf_size);
  lcm::LCM lcm(url);
  if (!lcm.good()) {
    throw std::runtime_error("cannot open LCM at '" + url + "'");
  }
  mrsim::MessageQueue queue(static_cast<size_t>(opt.max_queue_mb) << 20);
  std::atomic<bool> failed{false};
  std::thread writer(WriteQueued, std::ref(queue), std::ref(recorder),
                     std::ref(failed), opt.quiet);
  lcm::Subscription* sub = lcm.subscribeFunction(regex, &OnLcm, &queue);
  sub->setQueueCapacity(kQueueCapacity);
  if (!opt.quiet) {
    std::fprintf(stderr, "mrsim-log: recording channels matching '%s' to %s\n",
                 regex.c_str(), recorder.out_dir().c_str());
  }
  try {
    while (!mrsim::StopRequested() && !failed) mrsim::HandleFor(lcm, 100);
    // Take what already arrived before stopping, but do not wait on a
    // publisher that never pauses.
    const auto drain_end = Clock::now() + std::chrono::milliseconds(300);
    while (!failed && Clock::now() < drain_end &&
           mrsim::HandleFor(lcm, 20) > 0) {
    }
  } catch (...) {
    queue.Close();
    writer.join();
    throw;
  }
  lcm.unsubscribe(sub);
  queue.Close();
  writer.join();
  if (queue.dropped() > 0) {
    std::fprintf(stderr,
                 "mrsim-log: %lld messages dropped: the writer fell behind by "
                 "more than --max-queue-mb (%lld MB)\n",
                 static_cast<long long>(queue.dropped()),
                 static_cast<long long>(opt.max_queue_mb));
  }
  return 0;
}

void RunFromLog(const Options& opt, const std::string& regex,
                mrsim::Recorder& recorder) {
  lcm::LogFile log(opt.from_log, "r");
  if (!log.good()) {
    throw std::runtime_error("cannot read LCM log " + opt.from_log);
  }
  const std::regex re(regex, std::regex::ECMAScript);
  auto last_progress = Clock::now();
  int64_t events = 0;
  while (!mrsim::StopRequested() && !recorder.failed()) {
    const lcm::LogEvent* ev = log.readNextEvent();
    if (ev == nullptr) break;
    ++events;
    if (!std::regex_match(ev->channel, re)) continue;
    recorder.OnMessage(ev->channel, ev->data, static_cast<size_t>(ev->datalen));
    if ((events & 1023) == 0 &&
        Clock::now() - last_progress > std::chrono::seconds(5)) {
      last_progress = Clock::now();
      Progress(recorder, opt.quiet);
    }
  }
}

// Draws the --plot charts from the CSVs just written. Returns the exit
// status: 0, or 2 when a chart could not be drawn from its input.
int WritePlots(const std::vector<mrsim::LogPlotSpec>& plots,
               const mrsim::Recorder& recorder) {
  int status = 0;
  for (const mrsim::LogPlotSpec& spec : plots) {
    const std::string csv = recorder.CsvPath(spec.channel);
    if (csv.empty()) {
      std::fprintf(stderr,
                   "mrsim-log: plot of %s: nothing was recorded on "
                   "that channel\n",
                   spec.channel.c_str());
      status = 2;
      continue;
    }
    const std::string out = spec.out.front() == '/'
                                ? spec.out
                                : recorder.out_dir() + "/" + spec.out;
    try {
      mrsim::PlotCsvToPng(csv, spec.options, out);
      std::fprintf(stderr, "mrsim-log: wrote plot %s\n", out.c_str());
    } catch (const mrsim::PlotInputError& e) {
      std::fprintf(stderr, "mrsim-log: plot: %s\n", e.what());
      status = 2;
    } catch (const std::exception& e) {
      std::fprintf(stderr, "mrsim-log: plot: %s\n", e.what());
      status = 1;
    }
  }
  return status;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "Writes mrsim LCM channels to one CSV per channel (DIR/<channel>.csv), "
      "live or from an .lcmlog file, and reports sequence gaps."};
  app.set_version_flag("--version",
                       std::string("mrsim-log ") + mrsim::kVersion);
  Options opt;
  app.add_option("--lcm-url", opt.lcm_url,
                 "LCM URL (default: LCM's default or $LCM_DEFAULT_URL)");
  app.add_option("--prefix", opt.prefix,
                 "channel prefix; by default every channel starting with "
                 "PREFIX_ is recorded")
      ->capture_default_str();
  app.add_option("--channels", opt.channels,
                 "channels to record: a regular expression (whole name) or "
                 "a comma-separated list of names");
  app.add_option("--out", opt.out_dir, "output folder (created if needed)")
      ->capture_default_str();
  app.add_option("--from-log", opt.from_log,
                 "read this .lcmlog (from lcm-logger) instead of the network");
  app.add_option("--types", opt.types,
                 "extra .lcm files or folders with message definitions");
  app.add_option("--plot", opt.plots,
                 "draw a PNG when logging stops (repeatable): "
                 "CHANNEL:y=COL[,COL...][:x=COL][:title=TEXT]"
                 "[:style=auto|lines|points][:size=WxH][:out=FILE.png]; "
                 "x defaults to time, a relative FILE is in --out");
  app.add_option("--recv-buf-size", opt.recv_buf_size,
                 "kernel receive buffer (bytes) asked for on udpm URLs that "
                 "do not set recv_buf_size (capped by net.core.rmem_max); 0 "
                 "keeps the URL as given")
      ->capture_default_str();
  app.add_option("--max-queue-mb", opt.max_queue_mb,
                 "messages received but not yet written, at most (MB)")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  app.add_flag("--quiet", opt.quiet, "no progress lines");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;
  }

  const std::string regex =
      opt.channels.empty() ? opt.prefix + "_.*" : ChannelRegex(opt.channels);
  try {
    std::regex check(regex, std::regex::ECMAScript);
  } catch (const std::regex_error& e) {
    std::fprintf(stderr,
                 "mrsim-log: --channels '%s' is not a valid regular "
                 "expression: %s\n",
                 opt.channels.c_str(), e.what());
    return 2;
  }

  std::vector<mrsim::LogPlotSpec> plots;
  for (const std::string& p : opt.plots) {
    try {
      plots.push_back(mrsim::ParseLogPlotSpec(p));
    } catch (const std::exception& e) {
      std::fprintf(stderr, "mrsim-log: %s\n", e.what());
      return 2;
    }
  }

  if (!opt.from_log.empty() && !std::ifstream(opt.from_log)) {
    std::fprintf(stderr, "mrsim-log: cannot read LCM log file %s\n",
                 opt.from_log.c_str());
    return 2;
  }

  mrsim::InstallStopHandlers();
  try {
    mrsim::LcmTypeRegistry registry =
        mrsim::LcmTypeRegistry::WithBuiltinTypes();
    for (const std::string& w : registry.warnings()) {
      std::fprintf(stderr, "mrsim-log: warning: %s\n", w.c_str());
    }
    for (const std::string& t : opt.types) {
      try {
        registry.AddPath(t);
      } catch (const std::exception& e) {
        std::fprintf(stderr, "mrsim-log: %s\n", e.what());
        return 2;
      }
    }
    mrsim::Recorder recorder(registry, {opt.out_dir, nullptr});
    if (opt.from_log.empty()) {
      RunLive(opt, regex, recorder);
    } else {
      RunFromLog(opt, regex, recorder);
    }
    // Files that did not fail keep everything, even after another failed.
    try {
      recorder.Flush();
    } catch (const std::exception&) {
      // recorder.error() holds it.
    }
    std::fprintf(stderr, "mrsim-log: summary\n%s\n",
                 recorder.Summary().c_str());
    if (recorder.failed()) {
      std::fprintf(stderr, "mrsim-log: error: %s\n", recorder.error().c_str());
      return 1;
    }
    return WritePlots(plots, recorder);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mrsim-log: error: %s\n", e.what());
    return 1;
  }
}
