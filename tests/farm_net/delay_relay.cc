#include "tests/farm_net/delay_relay.h"

#include <fcntl.h>
#include <linux/if.h>
#include <linux/if_tun.h>
#include <poll.h>
#include <sched.h>
#include <sys/ioctl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstring>
#include <stdexcept>

namespace mrsim::testing {
namespace {

double Now() {
  return std::chrono::duration<double>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

// A TAP device in namespace `ns`, made from a thread of its own: setns()
// moves only the calling thread, and the device is created in the
// namespace of the thread that opens /dev/net/tun.
int OpenTap(const std::string& ns, const std::string& name) {
  int fd = -1;
  std::string error;
  std::thread([&] {
    if (!ns.empty()) {
      const std::string path = "/var/run/netns/" + ns;
      const int ns_fd = open(path.c_str(), O_RDONLY | O_CLOEXEC);
      if (ns_fd < 0 || setns(ns_fd, CLONE_NEWNET) != 0) {
        error = "cannot enter network namespace " + ns + ": " +
                std::strerror(errno);
        if (ns_fd >= 0) close(ns_fd);
        return;
      }
      close(ns_fd);
    }
    fd = open("/dev/net/tun", O_RDWR | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) {
      error = std::string("cannot open /dev/net/tun: ") + std::strerror(errno);
      return;
    }
    ifreq ifr{};
    ifr.ifr_flags = IFF_TAP | IFF_NO_PI;
    std::strncpy(ifr.ifr_name, name.c_str(), IFNAMSIZ - 1);
    if (ioctl(fd, TUNSETIFF, &ifr) != 0) {
      error = "cannot create TAP device " + name + " in namespace " + ns +
              ": " + std::strerror(errno);
      close(fd);
      fd = -1;
    }
  }).join();
  if (fd < 0) throw std::runtime_error("delay relay: " + error);
  return fd;
}

}  // namespace

DelayRelay::DelayRelay(std::uint64_t seed, std::size_t max_queued)
    : max_queued_(max_queued), random_(seed) {
  thread_ = std::thread([this] { Loop(); });
}

DelayRelay::~DelayRelay() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  wake_.Signal();
  thread_.join();
  for (const End& e : ends_) close(e.fd);
}

void DelayRelay::AddLink(const std::string& ns_a, const std::string& name_a,
                         const std::string& ns_b, const std::string& name_b,
                         LinkDelay delay) {
  if (delay.jitter < 0 || delay.delay < delay.jitter) {
    throw std::invalid_argument(
        "delay relay: link " + name_a + "-" + name_b +
        ": needs 0 <= jitter <= delay (a frame cannot leave before it came)");
  }
  const int a = OpenTap(ns_a, name_a);
  int b = -1;
  try {
    b = OpenTap(ns_b, name_b);
  } catch (...) {
    close(a);
    throw;
  }
  {
    std::lock_guard<std::mutex> lock(mutex_);
    const int first = static_cast<int>(ends_.size());
    ends_.push_back(End{a, first + 1, 0, -1, delay});
    ends_.push_back(End{b, first, 0, -1, delay});
  }
  wake_.Signal();  // poll the new ends too
}

RelayCounters DelayRelay::counters() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return counters_;
}

void DelayRelay::Loop() {
  std::vector<pollfd> fds;
  std::vector<int> polled;  // index into ends_ of fds[i + 1]
  for (;;) {
    double wait = -1;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (stop_) return;
      fds.assign(1, pollfd{wake_.fd(), POLLIN, 0});
      polled.clear();
      for (size_t i = 0; i < ends_.size(); ++i) {
        if (ends_[i].dead) continue;
        fds.push_back(pollfd{ends_[i].fd, POLLIN, 0});
        polled.push_back(static_cast<int>(i));
      }
      if (!queue_.empty()) wait = std::max(0.0, queue_.front().due - Now());
    }
    timespec ts{};
    if (wait >= 0) {
      ts.tv_sec = static_cast<time_t>(wait);
      ts.tv_nsec = static_cast<long>((wait - std::floor(wait)) * 1e9);
    }
    if (ppoll(fds.data(), fds.size(), wait >= 0 ? &ts : nullptr, nullptr) < 0 &&
        errno != EINTR) {
      return;  // cannot happen with valid descriptors; frames just stop
    }
    std::lock_guard<std::mutex> lock(mutex_);
    if (stop_) return;
    if (fds[0].revents != 0) wake_.Drain();
    const double now = Now();
    for (size_t i = 1; i < fds.size(); ++i) {
      const int end = polled[i - 1];
      if (fds[i].revents & (POLLERR | POLLHUP | POLLNVAL)) {
        ends_[static_cast<size_t>(end)].dead = true;  // else poll spins
      } else if (fds[i].revents & POLLIN) {
        ReadEnd(end, now);
      }
    }
    SendDue(Now());
  }
}

void DelayRelay::ReadEnd(int index, double now) {
  End& end = ends_[static_cast<size_t>(index)];
  std::uniform_real_distribution<double> jitter(-end.delay.jitter,
                                                end.delay.jitter);
  unsigned char buf[65536];
  for (;;) {
    const ssize_t n = read(end.fd, buf, sizeof buf);
    if (n <= 0) return;  // EAGAIN: drained (or the device went away)
    if (queue_.size() >= max_queued_) {
      ++counters_.overflowed;
      continue;
    }
    Frame f;
    f.due = now + end.delay.delay + jitter(random_);
    f.order = order_++;
    f.from = index;
    f.seq = end.read_seq++;
    f.bytes.assign(buf, buf + n);
    queue_.push_back(std::move(f));
    std::push_heap(queue_.begin(), queue_.end(), Later());
  }
}

void DelayRelay::SendDue(double now) {
  while (!queue_.empty() && queue_.front().due <= now) {
    std::pop_heap(queue_.begin(), queue_.end(), Later());
    Frame f = std::move(queue_.back());
    queue_.pop_back();
    End& from = ends_[static_cast<size_t>(f.from)];
    const End& to = ends_[static_cast<size_t>(from.peer)];
    // A device that is down refuses frames (EIO): as a cable pulled.
    if (write(to.fd, f.bytes.data(), f.bytes.size()) !=
        static_cast<ssize_t>(f.bytes.size())) {
      ++counters_.refused;
      continue;
    }
    ++counters_.frames;
    if (f.seq < from.sent_seq) {
      ++counters_.reordered;
    } else {
      from.sent_seq = f.seq;
    }
  }
}

}  // namespace mrsim::testing
