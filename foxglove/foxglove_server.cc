#include "foxglove/foxglove_server.h"

#include <atomic>
#include <chrono>
#include <future>
#include <map>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <utility>
#include <vector>

// websocketpp over standalone asio (Debian's libasio-dev), not Boost's.
#ifndef ASIO_STANDALONE
#define ASIO_STANDALONE
#endif
#include <websocketpp/config/asio_no_tls.hpp>
#include <websocketpp/server.hpp>

#include "foxglove/client_outbox.h"
#include "foxglove/control_access.h"
#include "foxglove/foxglove_protocol.h"

namespace mrsim::foxglove {
namespace {

// A peer that breaks the protocol (a frame over kMaxMessageSize, a bad
// frame) is dropped at once. Closing politely would wait for a close
// handshake a hostile peer never answers, and the timeout that ends it
// overwrites the reason, so the count of frames too big came out 0 or 1
// by timing; dropped, the connection keeps its reason (get_ec()).
struct WsConfig : websocketpp::config::asio {
  typedef WsConfig type;
  static const bool drop_on_protocol_error = true;
};
using WsServer = websocketpp::server<WsConfig>;
using Hdl = websocketpp::connection_hdl;

// A frame larger than this drops the connection inside websocketpp before
// it is buffered; below it, the bridge's parsers refuse what is over their
// own limits.
constexpr size_t kMaxMessageSize = 1 << 20;
constexpr auto kTickPeriod = std::chrono::milliseconds(20);
constexpr int kSendBuffer = 128 * 1024;

uint64_t NowNs() {
  return static_cast<uint64_t>(
      std::chrono::duration_cast<std::chrono::nanoseconds>(
          std::chrono::system_clock::now().time_since_epoch())
          .count());
}

}  // namespace

class FoxgloveServer::Impl {
 public:
  Impl(FoxgloveBridgeOptions bridge, FoxgloveServerOptions options)
      : options_(std::move(options)), bridge_(std::move(bridge)) {
    if (!options_.warn) options_.warn = [](const std::string&) {};
    server_.clear_access_channels(websocketpp::log::alevel::all);
    server_.clear_error_channels(websocketpp::log::elevel::all);
    server_.set_max_message_size(kMaxMessageSize);
    server_.set_max_http_body_size(64 * 1024);
    asio::error_code ec;
    server_.init_asio(ec);
    if (ec) throw std::runtime_error("asio: " + ec.message());
    server_.set_reuse_addr(true);
    server_.set_validate_handler([this](Hdl h) { return Validate(h); });
    server_.set_open_handler([this](Hdl h) { Open(h); });
    server_.set_close_handler([this](Hdl h) { Closed(h); });
    server_.set_fail_handler([this](Hdl h) { Closed(h); });
    server_.set_message_handler(
        [this](Hdl h, WsServer::message_ptr m) { Message(h, m); });
    server_.set_http_handler([this](Hdl h) { Http(h); });
    // The kernel's buffer for a client is bounded too (Linux grows it to
    // megabytes otherwise): a client that stops reading is noticed, and
    // its frames dropped, within a fraction of a second of data.
    server_.set_socket_init_handler([](Hdl, asio::ip::tcp::socket& socket) {
      asio::error_code ignored;
      socket.set_option(asio::socket_base::send_buffer_size(kSendBuffer),
                        ignored);
      socket.set_option(asio::ip::tcp::no_delay(true), ignored);
    });
    const std::string where =
        options_.bind + ":" + std::to_string(options_.port);
    const asio::ip::address address = asio::ip::make_address(options_.bind, ec);
    if (ec) {
      throw std::invalid_argument("--bind " + options_.bind +
                                  ": not an IP address (" + ec.message() + ")");
    }
    server_.listen(asio::ip::tcp::endpoint(address, options_.port), ec);
    if (ec)
      throw std::runtime_error("cannot listen on " + where + ": " +
                               ec.message());
    const auto local = server_.get_local_endpoint(ec);
    if (ec) throw std::runtime_error(where + ": " + ec.message());
    port_ = local.port();
    server_.start_accept(ec);
    if (ec) throw std::runtime_error(where + ": " + ec.message());
    timer_ = std::make_unique<asio::steady_timer>(server_.get_io_service());
    ArmTimer();
    std::promise<void> done;
    stopped_ = done.get_future();
    thread_ = std::thread([this, done = std::move(done)]() mutable {
      try {
        server_.run();
      } catch (const std::exception& e) {
        options_.warn(std::string("server thread: ") + e.what());
      }
      done.set_value();
    });
  }

  ~Impl() { Stop(); }

  void Stop() {
    if (!thread_.joinable()) return;
    server_.get_io_service().post([this] {
      stopping_ = true;
      asio::error_code ec;
      server_.stop_listening(ec);
      timer_->cancel();
      std::lock_guard<std::mutex> lock(mutex_);
      for (auto& [id, peer] : peers_) {
        server_.close(peer.hdl, websocketpp::close::status::going_away,
                      "mrsim-foxglove stops", ec);
      }
    });
    // Clients get a second to answer the close; then the loop is stopped.
    if (stopped_.wait_for(std::chrono::seconds(1)) !=
        std::future_status::ready) {
      server_.stop();
    }
    thread_.join();
  }

  uint16_t port() const { return port_; }

  void OnLcm(const std::string& channel, const void* data, size_t size) {
    std::unique_lock<std::mutex> lock(mutex_);
    BridgeOutput out = bridge_.OnLcm(channel, data, size, NowNs());
    Deliver(std::move(out), lock);
  }

  Counts counts() const {
    std::lock_guard<std::mutex> lock(mutex_);
    Counts c = counts_;
    for (const auto& [id, peer] : peers_)
      c.dropped_frames += peer.outbox.dropped();
    return c;
  }
  FoxgloveBridge::Counts bridge_counts() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return bridge_.counts();
  }

 private:
  struct Peer {
    Hdl hdl;
    std::string address;
    ClientOutbox outbox;
    bool closing = false;
    bool told_dropping = false;
  };

  // Under mutex_ (released before publishing). Never touches a socket:
  // the frames wait in the outboxes for the server thread.
  void Deliver(BridgeOutput out, std::unique_lock<std::mutex>& lock) {
    for (Outgoing& frame : out.send) {
      auto it = peers_.find(frame.client);
      if (it == peers_.end() || it->second.closing) continue;
      Peer& peer = it->second;
      if (!peer.outbox.Push(std::move(frame))) {
        peer.closing = true;
        ++counts_.closed_overflow;
        options_.warn("client " + std::to_string(it->first) + " (" +
                      peer.address +
                      ") closed: its announcements alone overflow its queue");
      } else if (peer.outbox.dropped() > 0 && !peer.told_dropping) {
        peer.told_dropping = true;
        options_.warn("client " + std::to_string(it->first) + " (" +
                      peer.address +
                      ") reads slower than the simulation publishes: its "
                      "oldest frames are dropped");
      }
    }
    for (const ClientId id : out.close) {
      auto it = peers_.find(id);
      if (it != peers_.end()) it->second.closing = true;
    }
    lock.unlock();
    for (const sim_control_t& control : out.controls) {
      if (options_.publish) options_.publish(control);
    }
    if (!flush_posted_.exchange(true)) {
      server_.get_io_service().post([this] { Flush(); });
    }
  }

  // Server thread: hands each client what its socket has room for.
  void Flush() {
    flush_posted_ = false;
    std::lock_guard<std::mutex> lock(mutex_);
    for (auto& [id, peer] : peers_) {
      asio::error_code ec;
      WsServer::connection_ptr con = server_.get_con_from_hdl(peer.hdl, ec);
      if (ec || !con) continue;
      if (peer.closing) {
        if (con->get_state() == websocketpp::session::state::open) {
          con->close(websocketpp::close::status::policy_violation,
                     "refused input or too far behind", ec);
        }
        continue;
      }
      while (!peer.outbox.empty() &&
             con->get_buffered_amount() < options_.max_buffered) {
        Outgoing frame = *peer.outbox.Pop();
        ec = con->send(frame.data, frame.binary
                                       ? websocketpp::frame::opcode::binary
                                       : websocketpp::frame::opcode::text);
        if (ec) break;
      }
    }
  }

  void ArmTimer() {
    timer_->expires_after(kTickPeriod);
    timer_->async_wait([this](const asio::error_code& ec) {
      if (ec || stopping_) return;  // cancelled: stopping
      {
        std::unique_lock<std::mutex> lock(mutex_);
        Deliver(bridge_.Tick(NowNs()), lock);
      }
      Flush();
      ArmTimer();
    });
  }

  bool Validate(Hdl h) {
    WsServer::connection_ptr con = server_.get_con_from_hdl(h);
    const std::string protocol =
        ChooseSubprotocol(con->get_requested_subprotocols());
    std::lock_guard<std::mutex> lock(mutex_);
    if (protocol.empty()) {
      ++counts_.refused_handshakes;
      con->set_status(websocketpp::http::status_code::bad_request);
      con->set_body(std::string("mrsim-foxglove speaks the subprotocols ") +
                    kSubprotocolV1 + " and " + kSubprotocolSdk + "\n");
      return false;
    }
    if (peers_.size() >= options_.max_clients) {
      ++counts_.refused_handshakes;
      con->set_status(websocketpp::http::status_code::service_unavailable);
      con->set_body("mrsim-foxglove: too many clients\n");
      return false;
    }
    con->select_subprotocol(protocol);
    return true;
  }

  void Open(Hdl h) {
    WsServer::connection_ptr con = server_.get_con_from_hdl(h);
    asio::error_code ec;
    const asio::ip::address peer =
        con->get_raw_socket().remote_endpoint(ec).address();
    bool loopback = !ec && peer.is_loopback();
    if (!ec && peer.is_v6() && peer.to_v6().is_v4_mapped()) {
      loopback = asio::ip::make_address_v4(asio::ip::v4_mapped, peer.to_v6())
                     .is_loopback();
    }
    const bool may_control = MayControl(loopback, con->get_uri()->get_query(),
                                        options_.control_token);
    std::unique_lock<std::mutex> lock(mutex_);
    const ClientId id = next_id_++;
    ids_[h] = id;
    peers_.emplace(
        id, Peer{h, ec ? "?" : peer.to_string(), ClientOutbox(), false, false});
    ++counts_.connections;
    Deliver(bridge_.Connect(id, may_control, NowNs()), lock);
  }

  void Closed(Hdl h) {
    WsServer::connection_ptr con = server_.get_con_from_hdl(h);
    std::lock_guard<std::mutex> lock(mutex_);
    if (con &&
        con->get_ec() == websocketpp::processor::error::make_error_code(
                             websocketpp::processor::error::message_too_big)) {
      ++counts_.too_big;
    }
    const auto it = ids_.find(h);
    if (it == ids_.end()) return;
    const auto peer = peers_.find(it->second);
    if (peer != peers_.end()) {
      counts_.dropped_frames += peer->second.outbox.dropped();
      peers_.erase(peer);
    }
    bridge_.Disconnect(it->second);
    ids_.erase(it);
  }

  void Message(Hdl h, WsServer::message_ptr m) {
    std::unique_lock<std::mutex> lock(mutex_);
    const auto it = ids_.find(h);
    if (it == ids_.end()) return;
    const std::string& payload = m->get_payload();
    BridgeOutput out =
        m->get_opcode() == websocketpp::frame::opcode::text
            ? bridge_.OnClientText(it->second, payload, NowNs())
            : bridge_.OnClientBinary(it->second, payload, NowNs());
    Deliver(std::move(out), lock);
  }

  void Http(Hdl h) {
    WsServer::connection_ptr con = server_.get_con_from_hdl(h);
    const std::string& method = con->get_request().get_method();
    HttpReply reply;
    if (method == "GET" || method == "HEAD") {
      reply = options_.web.Serve(con->get_request().get_uri(), port_);
    } else {
      reply = {405, "text/plain; charset=utf-8", "GET only\n"};
      con->append_header("Allow", "GET, HEAD");
    }
    con->set_status(
        static_cast<websocketpp::http::status_code::value>(reply.status));
    con->append_header("Content-Type", reply.content_type);
    con->append_header("X-Content-Type-Options", "nosniff");
    con->append_header("Cache-Control", "no-cache");
    con->set_body(std::move(reply.body));
  }

  FoxgloveServerOptions options_;
  WsServer server_;
  mutable std::mutex mutex_;
  FoxgloveBridge bridge_;
  std::map<ClientId, Peer> peers_;
  std::map<Hdl, ClientId, std::owner_less<Hdl>> ids_;
  ClientId next_id_ = 1;
  Counts counts_;
  std::atomic<bool> flush_posted_{false};
  bool stopping_ = false;  // server thread only
  std::unique_ptr<asio::steady_timer> timer_;
  uint16_t port_ = 0;
  std::future<void> stopped_;
  std::thread thread_;
};

FoxgloveServer::FoxgloveServer(FoxgloveBridgeOptions bridge,
                               FoxgloveServerOptions options)
    : impl_(std::make_unique<Impl>(std::move(bridge), std::move(options))) {}
FoxgloveServer::~FoxgloveServer() = default;
void FoxgloveServer::Stop() { impl_->Stop(); }
uint16_t FoxgloveServer::port() const { return impl_->port(); }
void FoxgloveServer::OnLcm(const std::string& channel, const void* data,
                           size_t size) {
  impl_->OnLcm(channel, data, size);
}
FoxgloveServer::Counts FoxgloveServer::counts() const {
  return impl_->counts();
}
FoxgloveBridge::Counts FoxgloveServer::bridge_counts() const {
  return impl_->bridge_counts();
}

}  // namespace mrsim::foxglove
