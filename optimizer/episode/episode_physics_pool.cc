#include "optimizer/episode/episode_physics_pool.h"

#include <openssl/evp.h>

#include <algorithm>
#include <stdexcept>
#include <thread>

#include "sim_core/scenario/scenario_xml.h"

namespace mrsim {

std::string ScenarioContentHash(const Scenario& scenario) {
  // Not the text itself as the key: a scenario with embedded assets is
  // megabytes, compared on every episode.
  const std::string content =
      WriteScenarioString(scenario) + '\n' + scenario.base_dir;
  unsigned char digest[EVP_MAX_MD_SIZE];
  unsigned int size = 0;
  if (EVP_Digest(content.data(), content.size(), digest, &size, EVP_sha256(),
                 nullptr) != 1) {
    throw std::runtime_error("SHA-256 of the scenario failed (OpenSSL)");
  }
  static const char kHex[] = "0123456789abcdef";
  std::string hex;
  for (unsigned int i = 0; i < size; ++i) {
    hex += kHex[digest[i] >> 4];
    hex += kHex[digest[i] & 15];
  }
  return hex;
}

EpisodePhysicsPool::EpisodePhysicsPool(std::size_t keep)
    : keep_(keep > 0 ? keep
                     : std::max<std::size_t>(
                           1, std::thread::hardware_concurrency())) {}

std::unique_ptr<Physics> EpisodePhysicsPool::Take(const Scenario& scenario,
                                                  std::string* key) {
  *key = ScenarioContentHash(scenario);
  {
    std::lock_guard<std::mutex> lock(mutex_);
    for (auto it = idle_.begin(); it != idle_.end(); ++it) {
      if (it->first != *key) continue;
      std::unique_ptr<Physics> physics = std::move(it->second);
      idle_.erase(it);
      physics->Reset();
      return physics;
    }
  }
  auto built = std::make_unique<Physics>(scenario);
  ++built_;
  return built;
}

void EpisodePhysicsPool::Give(std::string key,
                              std::unique_ptr<Physics> physics) {
  std::lock_guard<std::mutex> lock(mutex_);
  idle_.emplace_back(std::move(key), std::move(physics));
  while (idle_.size() > keep_) idle_.erase(idle_.begin());
}

void EpisodePhysicsPool::Clear() {
  std::lock_guard<std::mutex> lock(mutex_);
  idle_.clear();
}

PhysicsLease::PhysicsLease(EpisodePhysicsPool* pool, const Scenario& scenario)
    : pool_(pool),
      physics_(pool ? pool->Take(scenario, &key_)
                    : std::make_unique<Physics>(scenario)) {}

PhysicsLease::~PhysicsLease() {
  if (pool_ && physics_) pool_->Give(std::move(key_), std::move(physics_));
}

}  // namespace mrsim
