// A user-space link with delay and jitter for the farm rig (the kernel here
// has no netem): pairs of TAP devices, each end in a network namespace, and
// one thread that forwards every Ethernet frame from one end to the other
// after delay + uniform(-jitter, +jitter), drawn per frame, so frames
// overtake each other as on a real network (a heartbeat overtaking a
// result). Needs root (/dev/net/tun, setns).
#pragma once

#include <cstddef>
#include <cstdint>
#include <mutex>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "common/wake_fd.h"

namespace mrsim::testing {

// Seconds added to every frame on a link: delay +- jitter (uniform).
struct LinkDelay {
  double delay = 0;
  double jitter = 0;
  bool on() const { return delay > 0 || jitter > 0; }
};

struct RelayCounters {
  long long frames = 0;      // forwarded
  long long overflowed = 0;  // dropped: the queue was full
  long long refused = 0;     // dropped: the far end was down (EIO)
  long long reordered = 0;   // sent after a frame of its direction that
                             // came in later
};

class DelayRelay {
 public:
  // `max_queued` frames may wait at once over all links; more are dropped
  // (as a router's full queue would).
  explicit DelayRelay(std::uint64_t seed, std::size_t max_queued = 8192);
  // Stops and joins the thread, then closes the TAPs (which deletes them).
  ~DelayRelay();
  DelayRelay(const DelayRelay&) = delete;
  DelayRelay& operator=(const DelayRelay&) = delete;

  // Creates TAP `name_a` in network namespace `ns_a` and `name_b` in `ns_b`
  // (names as `ip netns` knows them; "" for this process's own) and
  // forwards frames both ways with `delay`. The devices are down and have
  // no address: configure them with ip. Throws naming the device.
  void AddLink(const std::string& ns_a, const std::string& name_a,
               const std::string& ns_b, const std::string& name_b,
               LinkDelay delay);
  RelayCounters counters() const;

 private:
  struct End {
    int fd = -1;
    int peer = -1;            // index of the end frames go out of
    long long read_seq = 0;   // frames read from this end
    long long sent_seq = -1;  // highest read_seq of the ones sent on
    LinkDelay delay;
    bool dead = false;  // its device went away (its namespace was deleted)
  };
  struct Frame {
    double due = 0;
    long long order = 0;  // FIFO among frames due at once
    int from = 0;         // index into ends_
    long long seq = 0;
    std::vector<unsigned char> bytes;
  };
  struct Later {
    bool operator()(const Frame& a, const Frame& b) const {
      return a.due != b.due ? a.due > b.due : a.order > b.order;
    }
  };

  void Loop();
  void ReadEnd(int index, double now);
  void SendDue(double now);

  const std::size_t max_queued_;
  mutable std::mutex mutex_;  // everything below but the thread and stop_
  std::mt19937_64 random_;
  std::vector<End> ends_;
  std::vector<Frame> queue_;  // a heap, by due time (Later)
  long long order_ = 0;
  RelayCounters counters_;
  WakeFd wake_;
  bool stop_ = false;
  std::thread thread_;
};

}  // namespace mrsim::testing
