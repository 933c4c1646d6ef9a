// The one place a farm node meets LCM and the clock (as Drake's DrakeLcm
// is for its systems): owns the SignedLcm, decodes the farm's channels into
// handler calls, publishes a core's FarmOutbox, and re-connects with
// back-off when the connection fails (a tcpq hub that went away) or when
// asked to re-join (a worker that lost its multicast membership).
#pragma once

#include <cstdint>
#include <functional>
#include <lcm/lcm-cpp.hpp>
#include <memory>
#include <string>
#include <vector>

#include "common/wake_fd.h"
#include "lcmtypes/runtime/signed_lcm.h"
#include "optimizer/farm/farm_channels.h"
#include "optimizer/farm/farm_outbox.h"

namespace mrsim {

class FarmLink {
 public:
  // Messages per channel LCM keeps waiting for Handle() before it drops
  // (LCM's default is 30): several seconds of the busiest channel of a
  // farm of thousands, a few MB at most.
  static constexpr int kQueueCapacity = 1 << 16;
  // Kernel receive buffer asked for on udpm/mpudpm unless the URL names one
  // (capped at net.core.rmem_max; the kernel grants twice the request). At
  // LCM's 208 KB default a burst of ~250 small datagrams (a generation's
  // jobs, the results of hundreds of workers ending together) overflows it.
  static constexpr std::int64_t kReceiveBuffer = 4 << 20;

  // Handlers for the channels a node listens to (unset: not subscribed).
  // Undecodable messages on a subscribed channel go to `malformed`.
  struct Handlers {
    std::function<void(const opt_run_t&)> run;
    std::function<void(const opt_chunk_t&)> chunk;
    std::function<void(const opt_chunk_request_t&)> chunk_request;
    std::function<void(const opt_heartbeat_t&)> heartbeat;
    std::function<void(const opt_job_t&)> job;
    // With `job`: the workers whose job channels to subscribe to (each
    // id's shard, FarmChannels::JobChannel); empty: every shard.
    std::vector<std::string> job_workers;
    std::function<void(const opt_result_t&)> result;
    std::function<void()> malformed;
  };

  // Opens `url` (with a larger receive buffer, above), signing and checking
  // messages with `auth`'s key if it has one; throws naming the URL when
  // the first attempt fails.
  FarmLink(std::string url, const std::string& prefix, Handlers handlers,
           AuthConfig auth = {});
  // Uses a connection the caller owns (no re-connecting).
  FarmLink(SignedLcm& borrowed, const std::string& prefix, Handlers handlers);
  ~FarmLink();
  FarmLink(const FarmLink&) = delete;
  FarmLink& operator=(const FarmLink&) = delete;

  // Handles what arrives within timeout_ms. A failed connection is
  // re-opened with back-off (0.1 s doubling to 5 s) meanwhile.
  void Handle(int timeout_ms);
  // Ends Handle's wait when signalled, e.g. when an episode finishes: its
  // result goes out at once, not at the next timeout. Handle drains it.
  // Null: none. Must outlive this link.
  void SetWake(const WakeFd* wake) { wake_ = wake; }
  void Publish(FarmOutbox& out);
  // Closes and re-opens the connection now (re-joins multicast groups).
  void Rejoin();
  bool connected() const { return lcm_ != nullptr; }
  // Seconds on a monotonic clock.
  static double Now();
  std::vector<std::string> TakeLog();

 private:
  void Open();
  void Close(const std::string& why);
  void Subscribe();
  template <class Message>
  void Deliver(const lcm::ReceiveBuffer* rbuf,
               const std::function<void(const Message&)>& handler);
  void OnRun(const lcm::ReceiveBuffer* b, const std::string&);
  void OnChunk(const lcm::ReceiveBuffer* b, const std::string&);
  void OnChunkRequest(const lcm::ReceiveBuffer* b, const std::string&);
  void OnHeartbeat(const lcm::ReceiveBuffer* b, const std::string&);
  void OnJob(const lcm::ReceiveBuffer* b, const std::string&);
  void OnResult(const lcm::ReceiveBuffer* b, const std::string&);

  std::string url_;
  FarmChannels channels_;
  Handlers handlers_;
  AuthConfig auth_;
  std::unique_ptr<SignedLcm> owned_;
  SignedLcm* lcm_ = nullptr;
  std::vector<lcm::Subscription*> subscriptions_;
  double backoff_ = 0.1;
  double next_attempt_ = 0;
  std::vector<std::string> log_;
  const WakeFd* wake_ = nullptr;  // not owned
};

}  // namespace mrsim
