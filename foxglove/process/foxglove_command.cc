#include "foxglove/process/foxglove_command.h"

#include <chrono>

#include "common/lcm_url.h"
#include "foxglove/control_access.h"
#include "foxglove/foxglove_server.h"
#include "lcmtypes/runtime/channel_pattern.h"
#include "lcmtypes/runtime/channels.h"
#include "lcmtypes/runtime/lcm_loop.h"
#include "lcmtypes/runtime/stop_signal.h"

namespace mrsim {
namespace {

int64_t WallMicros() {
  return std::chrono::duration_cast<std::chrono::microseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

}  // namespace

void AddFoxgloveFlags(CLI::App& app, FoxgloveCommand& c) {
  app.add_option("--lcm-url", c.lcm_url,
                 "LCM URL (default: LCM's default or $LCM_DEFAULT_URL)");
  AddAuthFlags(app, c.auth);
  app.add_option("--prefix", c.prefix,
                 "channel prefix: every channel starting with PREFIX_ is "
                 "served")
      ->capture_default_str();
  app.add_option("--port", c.port, "WebSocket port (0: any free one)")
      ->capture_default_str()
      ->check(CLI::Range(0, 65535));
  app.add_option("--bind", c.bind,
                 "address to listen on (127.0.0.1: this host only)")
      ->capture_default_str();
  app.add_option("--control-key", c.control_key,
                 "a key file (mrsim keygen PATH): clients that connect with "
                 "?token=<its hex key> may pause, resume, step, reset and set "
                 "the speed, from anywhere (default: only clients on this "
                 "host may)");
  app.add_option("--max-clients", c.max_clients, "clients served at once")
      ->capture_default_str()
      ->check(CLI::Range(1, 1024));
}

int RunFoxglove(const FoxgloveCommand& c, SignedLcm& lcm, std::FILE* err) {
  if (!lcm.good()) throw std::runtime_error(CannotOpenLcm(c.lcm_url));
  foxglove::FoxgloveBridgeOptions bridge;
  bridge.prefix = c.prefix;
  bridge.first_control_seq = WallMicros();
  foxglove::FoxgloveServerOptions server_options;
  server_options.bind = c.bind;
  server_options.port = static_cast<uint16_t>(c.port);
  server_options.max_clients = static_cast<size_t>(c.max_clients);
  if (!c.control_key.empty()) {
    server_options.control_token =
        foxglove::ControlTokenFromKeyFile(c.control_key);
  }
  server_options.web = foxglove::WebAssets(foxglove::WebAssets::FindDir());
  const std::string control_channel = SimControlChannel(c.prefix);
  server_options.publish = [&lcm, control_channel](const sim_control_t& m) {
    lcm.publish(control_channel, &m);
  };
  server_options.warn = [err](const std::string& line) {
    std::fprintf(err, "mrsim-foxglove: %s\n", line.c_str());
  };
  foxglove::FoxgloveServer server(bridge, server_options);
  lcm::Subscription* sub = lcm.Subscribe(
      LiteralChannelPattern(c.prefix) + "_.*",
      [&server](const lcm::ReceiveBuffer* rbuf, const std::string& channel) {
        server.OnLcm(channel, rbuf->data, rbuf->data_size);
      });
  // A slow bridge drops LCM's oldest messages rather than growing.
  sub->setQueueCapacity(1000);
  std::fprintf(err,
               "mrsim-foxglove: listening on ws://%s:%u for channels %s_* "
               "(%s; controls: %s)\n",
               c.bind.c_str(), static_cast<unsigned>(server.port()),
               c.prefix.c_str(), lcm.Describe().c_str(),
               c.control_key.empty() ? "clients on this host"
                                     : "clients with the token");
  if (server_options.web.available()) {
    std::fprintf(err, "mrsim-foxglove: the browser page: http://%s:%u/\n",
                 c.bind == "0.0.0.0" ? "<this host>" : c.bind.c_str(),
                 static_cast<unsigned>(server.port()));
  } else {
    std::fprintf(err, "mrsim-foxglove: no browser page: %s\n",
                 server_options.web.why().c_str());
  }
  std::fflush(err);
  while (!StopRequested()) HandleFor(lcm, 100);
  lcm.unsubscribe(sub);
  // Every connection's end counted (a client dropped a moment ago
  // included) before the counts are read.
  server.Stop();
  const auto s = server.counts();
  const auto b = server.bridge_counts();
  std::fprintf(err,
               "mrsim-foxglove: stopped: %lld connections, %lld handshakes "
               "refused, %lld frames dropped for slow clients, %lld client "
               "messages malformed (%lld unknown ops, %lld too big), %lld "
               "subscriptions and %lld service calls refused, %lld clients "
               "closed, %lld LCM messages malformed\n",
               static_cast<long long>(s.connections),
               static_cast<long long>(s.refused_handshakes),
               static_cast<long long>(s.dropped_frames),
               static_cast<long long>(b.malformed),
               static_cast<long long>(b.unknown_op),
               static_cast<long long>(s.too_big),
               static_cast<long long>(b.refused_subscriptions),
               static_cast<long long>(b.refused_calls),
               static_cast<long long>(b.closed + s.closed_overflow),
               static_cast<long long>(b.lcm_malformed));
  return 0;
}

}  // namespace mrsim
