// Simulations built for episodes, kept for the next episode of the same
// scenario. Building a Physics (MJCF compile and three zeroed mjData
// arenas) costs about as much as a 4 s episode; an idle one of the same
// scenario is reset instead, which gives bit for bit the same episode
// (tested) at a fraction of the cost. One pool serves all the threads of
// an evaluator: a thread's first episode takes the simulation another
// thread built. Whoever runs episodes owns the pool and passes it to
// RunEpisode (mrsim-opt's local evaluator, a farm worker); there is no
// process-wide one. Thread-safe.
#pragma once

#include <atomic>
#include <cstddef>
#include <memory>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include "sim_core/physics/physics.h"
#include "sim_core/scenario/scenario.h"

namespace mrsim {

// SHA-256 (hex) of the scenario's content: its canonical XML text and the
// folder its relative paths resolve from. Equal for scenarios that build
// the same simulation; the pool's key.
std::string ScenarioContentHash(const Scenario& scenario);

class EpisodePhysicsPool {
 public:
  // keep: idle simulations kept (the most recent); 0: one per hardware
  // thread, as many as the machine runs episodes at once.
  explicit EpisodePhysicsPool(std::size_t keep = 0);
  EpisodePhysicsPool(const EpisodePhysicsPool&) = delete;
  EpisodePhysicsPool& operator=(const EpisodePhysicsPool&) = delete;

  // A simulation of `scenario` at its start state: an idle one of the same
  // content hash, reset, or a new one. Throws what building throws.
  std::unique_ptr<Physics> Take(const Scenario& scenario, std::string* key);
  // Hands back a simulation taken with `key`.
  void Give(std::string key, std::unique_ptr<Physics> physics);
  // Frees the idle ones: the next episode builds afresh.
  void Clear();
  // Simulations built so far.
  long long built() const { return built_; }

 private:
  std::size_t keep_;
  std::mutex mutex_;
  std::vector<std::pair<std::string, std::unique_ptr<Physics>>> idle_;
  std::atomic<long long> built_{0};
};

// A simulation for one episode, given back to its pool when it ends
// (without a pool: built for this episode alone).
class PhysicsLease {
 public:
  PhysicsLease(EpisodePhysicsPool* pool, const Scenario& scenario);
  ~PhysicsLease();
  PhysicsLease(const PhysicsLease&) = delete;
  PhysicsLease& operator=(const PhysicsLease&) = delete;
  Physics& operator*() { return *physics_; }

 private:
  EpisodePhysicsPool* pool_;
  std::string key_;
  std::unique_ptr<Physics> physics_;
};

}  // namespace mrsim
