#include "optimizer/farm/farm_link.h"

#include <fmt/format.h>
#include <poll.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <stdexcept>
#include <thread>

#include "common/lcm_url.h"
#include "common/wall_time.h"
#include "lcmtypes/runtime/decode.h"

namespace mrsim {

double FarmLink::Now() {
  return std::chrono::duration<double>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

FarmLink::FarmLink(std::string url, const std::string& prefix,
                   Handlers handlers, AuthConfig auth)
    : url_(LcmUrlWithReceiveBuffer(
          url, std::min(kReceiveBuffer, KernelReceiveBufferMax()))),
      channels_(prefix),
      handlers_(std::move(handlers)),
      auth_(std::move(auth)) {
  const std::int64_t max = KernelReceiveBufferMax();
  if (url_ != ResolveLcmUrl(url) && max > 0 && max < kReceiveBuffer / 4) {
    log_.push_back(fmt::format(
        "the kernel caps receive buffers at {} KB (net.core.rmem_max): with "
        "hundreds of workers bursts are lost and re-sent; raise it, e.g. "
        "sysctl -w net.core.rmem_max={}",
        max / 1024, kReceiveBuffer));
  }
  Open();
  if (!lcm_) {
    throw std::runtime_error(CannotOpenLcm(url));
  }
}

FarmLink::FarmLink(SignedLcm& borrowed, const std::string& prefix,
                   Handlers handlers)
    : channels_(prefix), handlers_(std::move(handlers)), lcm_(&borrowed) {
  Subscribe();
}

FarmLink::~FarmLink() {
  if (lcm_) {
    for (lcm::Subscription* s : subscriptions_) lcm_->unsubscribe(s);
  }
}

std::vector<std::string> FarmLink::TakeLog() {
  std::vector<std::string> out;
  out.swap(log_);
  return out;
}

void FarmLink::Open() {
  auto lcm = std::make_unique<SignedLcm>(
      url_, auth_, [this](const std::string& line) { log_.push_back(line); });
  if (!lcm->good()) return;
  owned_ = std::move(lcm);
  lcm_ = owned_.get();
  Subscribe();
}

void FarmLink::Close(const std::string& why) {
  if (!owned_) return;  // a borrowed connection is the owner's business
  subscriptions_.clear();
  owned_.reset();
  lcm_ = nullptr;
  next_attempt_ = Now() + backoff_;
  log_.push_back(fmt::format("LCM connection lost ({}); re-connecting", why));
}

void FarmLink::Rejoin() {
  if (!owned_) return;
  subscriptions_.clear();
  owned_.reset();
  lcm_ = nullptr;
  Open();
  if (!lcm_) next_attempt_ = Now() + backoff_;
}

void FarmLink::Subscribe() {
  const auto sub =
      [&](const std::string& channel, bool wanted,
          void (FarmLink::*fn)(const lcm::ReceiveBuffer*, const std::string&)) {
        if (!wanted) return;
        lcm::Subscription* s = lcm_->subscribe(channel, fn, this);
        // LCM's default keeps 30 messages per subscription waiting for
        // handle() and silently drops the rest: a burst of results or
        // heartbeats from hundreds of workers (or of jobs to a process of
        // fake workers) lost most of itself there, though the kernel had
        // delivered it and the process was idle.
        s->setQueueCapacity(kQueueCapacity);
        subscriptions_.push_back(s);
      };
  sub(channels_.run, bool(handlers_.run), &FarmLink::OnRun);
  sub(channels_.chunk, bool(handlers_.chunk), &FarmLink::OnChunk);
  sub(channels_.chunk_request, bool(handlers_.chunk_request),
      &FarmLink::OnChunkRequest);
  sub(channels_.heartbeat, bool(handlers_.heartbeat), &FarmLink::OnHeartbeat);
  if (handlers_.job) {
    std::vector<bool> shard(kJobShards, handlers_.job_workers.empty());
    for (const std::string& id : handlers_.job_workers) {
      shard[static_cast<size_t>(JobShard(id))] = true;
    }
    for (int k = 0; k < kJobShards; ++k) {
      sub(channels_.JobChannel(k), shard[static_cast<size_t>(k)],
          &FarmLink::OnJob);
    }
  }
  sub(channels_.result, bool(handlers_.result), &FarmLink::OnResult);
}

template <class Message>
void FarmLink::Deliver(const lcm::ReceiveBuffer* rbuf,
                       const std::function<void(const Message&)>& handler) {
  try {
    Message msg;
    if (!DecodeMessage(rbuf, &msg)) {
      if (handlers_.malformed) handlers_.malformed();
      return;
    }
    handler(msg);
  } catch (...) {
    // Handlers never throw through LCM; a message that makes one fail is
    // counted like an undecodable one.
    if (handlers_.malformed) handlers_.malformed();
  }
}

void FarmLink::OnRun(const lcm::ReceiveBuffer* b, const std::string&) {
  Deliver(b, handlers_.run);
}
void FarmLink::OnChunk(const lcm::ReceiveBuffer* b, const std::string&) {
  Deliver(b, handlers_.chunk);
}
void FarmLink::OnChunkRequest(const lcm::ReceiveBuffer* b, const std::string&) {
  Deliver(b, handlers_.chunk_request);
}
void FarmLink::OnHeartbeat(const lcm::ReceiveBuffer* b, const std::string&) {
  Deliver(b, handlers_.heartbeat);
}
void FarmLink::OnJob(const lcm::ReceiveBuffer* b, const std::string&) {
  Deliver(b, handlers_.job);
}
void FarmLink::OnResult(const lcm::ReceiveBuffer* b, const std::string&) {
  Deliver(b, handlers_.result);
}

void FarmLink::Handle(int timeout_ms) {
  if (!lcm_) {
    const double now = Now();
    if (now >= next_attempt_) {
      Open();
      if (lcm_) {
        log_.push_back("LCM connection re-opened");
        backoff_ = 0.1;
      } else {
        backoff_ = std::min(5.0, backoff_ * 2);
        next_attempt_ = now + backoff_;
      }
    }
    if (!lcm_) {
      const double wait =
          std::clamp(next_attempt_ - Now(), 0.0, timeout_ms / 1000.0);
      std::this_thread::sleep_for(std::chrono::duration<double>(wait));
      return;
    }
  }
  try {
    // At most kBurst messages per call: a node that receives faster than it
    // handles must still get back to beating, dispatching and answering.
    constexpr int kBurst = 256;
    int wait_ms = timeout_ms;
    for (int n = 0; n < kBurst; ++n) {
      pollfd fds[2] = {{lcm_->getFileno(), POLLIN, 0},
                       {wake_ ? wake_->fd() : -1, POLLIN, 0}};
      const int ready = poll(fds, wake_ ? 2 : 1, wait_ms);
      if (ready < 0 && errno != EINTR) throw std::runtime_error("poll failed");
      if (ready <= 0) break;
      if (wake_ && (fds[1].revents & POLLIN)) {
        wake_->Drain();  // false: another Handle drained it first
        wait_ms = 0;     // take what LCM has too, without waiting
        if (!(fds[0].revents & POLLIN)) break;
      }
      const pollfd& pfd = fds[0];
      if (!(pfd.revents & (POLLIN | POLLERR | POLLHUP | POLLNVAL))) break;
      if (pfd.revents & (POLLERR | POLLHUP | POLLNVAL) &&
          !(pfd.revents & POLLIN)) {
        throw std::runtime_error("connection closed");
      }
      if (lcm_->handle() != 0) throw std::runtime_error("lcm handle() failed");
      wait_ms = 0;
    }
  } catch (const std::exception& e) {
    if (!owned_) throw;
    Close(e.what());
  }
}

void FarmLink::Publish(FarmOutbox& out) {
  if (out.rejoin) {
    Rejoin();
    log_.push_back(lcm_ ? "re-joined the LCM group"
                        : "re-join failed; re-connecting");
  }
  if (!lcm_) return;  // lost; the protocol asks again
  const std::int64_t stamp = WallMicros();
  const auto send = [&](const std::string& channel, auto& list,
                        int copies = 1) {
    for (auto& msg : list) {
      msg.utime = stamp;
      for (int c = 0; c < copies; ++c) lcm_->publish(channel, &msg);
    }
  };
  send(channels_.run, out.runs);
  send(channels_.chunk, out.chunks);
  send(channels_.chunk_request, out.chunk_requests);
  send(channels_.heartbeat, out.heartbeats);
  const int copies = std::clamp(out.copies, 1, 4);
  for (auto& msg : out.jobs) {  // each on its worker's shard
    msg.utime = stamp;
    const std::string channel = channels_.JobChannel(JobShard(msg.worker_id));
    for (int c = 0; c < copies; ++c) lcm_->publish(channel, &msg);
  }
  send(channels_.result, out.results, copies);
}

}  // namespace mrsim
