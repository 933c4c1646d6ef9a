// The WebSocket side of mrsim-foxglove: a websocketpp server on its own
// thread (asio) that speaks the Foxglove protocol through a FoxgloveBridge.
// The LCM loop hands it messages with OnLcm, which never waits for a
// socket: what each client is to get goes into its bounded ClientOutbox,
// and the server thread sends from there as fast as the client reads
// (a slow client loses its oldest data, the simulator never waits). Plain
// HTTP requests on the same port get the browser page (web_assets.h), or a
// short hint of where to connect when its files were not found.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include "foxglove/foxglove_bridge.h"
#include "foxglove/web_assets.h"

namespace mrsim::foxglove {

struct FoxgloveServerOptions {
  std::string bind = "0.0.0.0";
  uint16_t port = 8765;  // 0: any free port (port() says which)
  // The control key's token (control_access.h); empty: controls only from
  // this host.
  std::string control_token;
  size_t max_clients = 64;
  // Bytes a client's socket may have unsent before the server stops handing
  // it more (the rest waits in its outbox).
  size_t max_buffered = 256 * 1024;
  // Called on the server thread for each control to publish (thread-safe
  // publishing, as SignedLcm's).
  std::function<void(const sim_control_t&)> publish;
  // The browser page's files, served over HTTP (none: the hint).
  WebAssets web;
  // Warnings (a client closed, a listener error); may be empty.
  std::function<void(const std::string&)> warn;
};

class FoxgloveServer {
 public:
  struct Counts {
    int64_t connections = 0;         // accepted so far
    int64_t refused_handshakes = 0;  // no Foxglove subprotocol, too many
    int64_t dropped_frames = 0;      // by slow clients' outboxes
    int64_t too_big = 0;             // frames over the size websocketpp takes
    int64_t closed_overflow = 0;     // clients closed for a full outbox
  };

  // Listens (throws std::invalid_argument for a bind that is no IP
  // address, std::runtime_error naming bind:port when it cannot listen)
  // and starts the server thread.
  FoxgloveServer(FoxgloveBridgeOptions bridge, FoxgloveServerOptions options);
  ~FoxgloveServer();  // Stop()
  FoxgloveServer(const FoxgloveServer&) = delete;
  FoxgloveServer& operator=(const FoxgloveServer&) = delete;

  // Closes every connection (a second for clients to answer) and stops the
  // server thread once every connection's end was handled, so counts()
  // then includes all of them. Later calls do nothing.
  void Stop();

  uint16_t port() const;
  // One LCM message; returns at once. Not after Stop().
  void OnLcm(const std::string& channel, const void* data, size_t size);
  Counts counts() const;
  FoxgloveBridge::Counts bridge_counts() const;

 private:
  class Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace mrsim::foxglove
