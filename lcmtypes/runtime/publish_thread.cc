#include "lcmtypes/runtime/publish_thread.h"

#include <pthread.h>
#include <sched.h>

#include <algorithm>

namespace mrsim {
namespace {

void Relax() {
#if defined(__x86_64__) || defined(__i386__)
  __builtin_ia32_pause();
#endif
}

}  // namespace

PublishThread::PublishThread(Send send, Wait wait)
    : send_(std::move(send)),
      spinning_(wait == Wait::kSpin),
      sleeper_([this] { RunSleeping(); }) {
  if (wait != Wait::kSpin) return;
  try {
    spinner_ = std::thread([this] { RunSpinning(); });
  } catch (...) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      stop_ = true;
      spinning_.store(false);
    }
    wake_sleeper_.notify_all();
    sleeper_.join();
    throw;
  }
}

PublishThread::PublishThread(lcm::LCM& lcm, Wait wait)
    : PublishThread(
          [&lcm](const std::string& channel, const void* data, unsigned size) {
            // A failed send is LCM's to report (it prints); the simulator
            // could do no more.
            lcm.publish(channel, data, size);
          },
          wait) {}

PublishThread::PublishThread(SignedLcm& lcm, Wait wait)
    : PublishThread([&lcm](const std::string& channel, const void* data,
                           unsigned size) { lcm.publish(channel, data, size); },
                    wait) {}

PublishThread::~PublishThread() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
    spinning_.store(false);  // the sleeping thread sends what is left
  }
  // The sleeper sends what is queued even while a starved spinner has yet
  // to notice.
  wake_sleeper_.notify_all();
  wake_spinner_.notify_all();
  if (spinner_.joinable()) spinner_.join();
  sleeper_.join();
}

int PublishThread::publish(const std::string& channel, const void* data,
                           unsigned size) {
  const uint8_t* bytes = static_cast<const uint8_t*>(data);
  bool wake_sleeper = false;
  bool wake_spinner = false;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    Message m;
    if (!spare_.empty()) {
      m = std::move(spare_.back());
      spare_.pop_back();
    }
    m.channel = channel;
    m.data.assign(bytes, bytes + size);
    m.given = Clock::now();
    queue_.push_back(std::move(m));
    // Counted under the lock: a spinner about to sleep sees it.
    given_.fetch_add(1, std::memory_order_release);
    if (spinning_.load(std::memory_order_relaxed)) {
      // After a quiet spell both sleep: the guard must watch again.
      wake_spinner = spinner_waits_;
      wake_sleeper = spinner_waits_ && sleeper_waits_;
    } else {
      wake_sleeper = sleeper_waits_;
    }
  }
  if (wake_spinner) wake_spinner_.notify_one();
  if (wake_sleeper) wake_sleeper_.notify_one();
  return 0;
}

void PublishThread::Drain() {
  std::unique_lock<std::mutex> lock(mutex_);
  drained_.wait(lock, [this] { return queue_.empty() && !sending_; });
}

bool PublishThread::asleep() const {
  std::lock_guard<std::mutex> lock(mutex_);
  if (!queue_.empty() || sending_) return false;
  return spinning_.load() ? spinner_waits_ && sleeper_waits_ : sleeper_waits_;
}

void PublishThread::SendOne(std::unique_lock<std::mutex>& lock) {
  Message m = std::move(queue_.front());
  queue_.pop_front();
  sending_ = true;
  lock.unlock();
  send_(m.channel, m.data.data(), static_cast<unsigned>(m.data.size()));
  lock.lock();
  sending_ = false;
  last_sent_ = Clock::now();
  if (spare_.size() < 8) spare_.push_back(std::move(m));
  if (queue_.empty()) drained_.notify_all();
}

PublishThread::Clock::duration PublishThread::HeadWaited(
    Clock::time_point now) const {
  // Behind a burst a message waits for the sends before it: only the time
  // since it could have gone counts.
  return now - std::max(queue_.front().given, last_sent_);
}

void PublishThread::Rescue(std::unique_lock<std::mutex>& lock) {
  const Clock::time_point now = Clock::now();
  while (!rescues_.empty() && now - rescues_.front() > kRescueWindow) {
    rescues_.pop_front();
  }
  rescues_.push_back(now);
  if (static_cast<int>(rescues_.size()) >= kRescuesToFallBack) {
    spinning_.store(false);
    wake_spinner_.notify_one();  // it leaves after a send in progress
  }
  while (!sending_ && !queue_.empty() && HeadWaited(Clock::now()) > kRescue) {
    SendOne(lock);
  }
}

void PublishThread::RunSleeping() {
  std::unique_lock<std::mutex> lock(mutex_);
  for (;;) {
    if (!spinning_.load()) {
      if (!sending_ && !queue_.empty()) {
        SendOne(lock);
        continue;
      }
      if (!sending_ && stop_) return;  // all sent
      sleeper_waits_ = true;
      wake_sleeper_.wait(
          lock, [this] { return !sending_ && (stop_ || !queue_.empty()); });
      sleeper_waits_ = false;
      continue;
    }
    // The spinner sends; this thread sends what it leaves waiting (it may
    // sit behind a busy thread on another CPU for a while).
    if (!sending_ && !queue_.empty() && HeadWaited(Clock::now()) > kRescue) {
      Rescue(lock);
      continue;
    }
    if (spinner_waits_ && queue_.empty()) {
      sleeper_waits_ = true;
      wake_sleeper_.wait(lock, [this] {
        return !spinning_.load() || !spinner_waits_ || !queue_.empty();
      });
      sleeper_waits_ = false;
    } else {
      // publish does not wake this thread while the spinner spins.
      wake_sleeper_.wait_for(lock, kRescue);
    }
  }
}

// On a virtual machine an interrupt to another CPU, which a wake-up by
// publish costs, takes the publishing thread about 7 us: a tenth of a
// simulator's control period. A spinning sender needs none. At idle
// priority any other thread takes its CPU at once, and the scheduler
// counts the CPU it spins on as idle when it places other threads.
void PublishThread::RunSpinning() {
  sched_param param{};
  if (pthread_setschedparam(pthread_self(), SCHED_IDLE, &param) != 0) {
    // Spinning at normal priority would take CPU from the other threads.
    {
      std::lock_guard<std::mutex> lock(mutex_);
      spinning_.store(false);
    }
    wake_sleeper_.notify_one();
    return;
  }
  std::unique_lock<std::mutex> lock(mutex_);
  int late = 0;
  while (spinning_.load()) {
    if (!queue_.empty()) {
      if (sending_) {
        // The sleeper rescues a message: the next is this thread's.
        lock.unlock();
        Relax();
        lock.lock();
        continue;
      }
      // Messages that keep waiting for this thread mean other threads
      // want every CPU: a thread at normal priority does better then.
      late = HeadWaited(Clock::now()) > kLate ? late + 1 : 0;
      if (late == kLateInARow) {
        spinning_.store(false);
        break;
      }
      SendOne(lock);
      continue;
    }
    const uint64_t seen = given_.load(std::memory_order_relaxed);
    lock.unlock();
    const bool came = SpinFor(seen);
    lock.lock();
    if (!came && queue_.empty() && spinning_.load()) {
      // A quiet spell (paused, or a slow peer): sleep until publish.
      spinner_waits_ = true;
      wake_spinner_.wait(
          lock, [this] { return !spinning_.load() || !queue_.empty(); });
      spinner_waits_ = false;
      late = 0;  // being woken is not being starved
    }
  }
  // The sleeping thread may wait for the send this thread just finished.
  lock.unlock();
  wake_sleeper_.notify_one();
}

bool PublishThread::SpinFor(uint64_t seen) {
  const Clock::time_point until = Clock::now() + kSpinWindow;
  while (given_.load(std::memory_order_acquire) == seen) {
    if (!spinning_.load(std::memory_order_relaxed)) return true;
    if (Clock::now() > until) return false;
    Relax();
  }
  return true;
}

}  // namespace mrsim
