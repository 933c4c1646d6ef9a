// The master's side of the farm: a BatchEvaluator that hands a generation
// out as jobs to mrsim-worker processes over LCM and collects the results.
// The logic is FarmMasterCore's; this adapter owns the connection
// (FarmLink) and the clock. Results are a function of the genome only, so
// faults never change them.
#pragma once

#include <cstdint>
#include <deque>
#include <lcm/lcm-cpp.hpp>
#include <memory>
#include <string>
#include <vector>

#include "lcmtypes/runtime/signed_lcm.h"
#include "optimizer/search/batch_evaluator.h"
#include "optimizer/farm/farm_link.h"
#include "optimizer/farm/farm_master_core.h"

namespace mrsim {

class FarmEvaluator : public BatchEvaluator {
 public:
  // Opens its own connection to `lcm_url` (re-connected when it fails,
  // e.g. a tcpq hub restart). `payload` is EncodeProblem's output;
  // `run_id` tells this master's messages apart from any other's.
  FarmEvaluator(const std::string& lcm_url, std::string payload,
                std::string run_id, FarmSettings settings);
  // Uses a connection the caller owns (not re-connected).
  FarmEvaluator(SignedLcm& lcm, std::string payload, std::string run_id,
                FarmSettings settings);
  ~FarmEvaluator() override;
  FarmEvaluator(const FarmEvaluator&) = delete;
  FarmEvaluator& operator=(const FarmEvaluator&) = delete;

  std::vector<EvalResult> Evaluate(const std::vector<Genome>& batch) override;
  void Submit(std::vector<Genome> batch) override;
  std::vector<EvalResult> Collect() override;
  int workers_alive() const override { return core_.workers_alive(); }
  // Workers holding this run's payload.
  int workers_ready() const { return core_.workers_ready(); }

  const std::string& scenario_hash() const { return core_.scenario_hash(); }
  const FarmCounters& counters() const { return core_.counters(); }
  double episode_seconds() const { return core_.episode_seconds(); }

 private:
  FarmLink::Handlers MakeHandlers();
  void Step(int timeout_ms);

  FarmSettings settings_;
  FarmMasterCore core_;
  std::deque<std::int64_t> in_flight_;  // submitted batch ids, oldest first
  std::unique_ptr<FarmLink> link_;
  // How to start a worker for this farm, for the "waiting" line ("" when
  // the LCM instance came from the caller).
  std::string worker_hint_;
};

}  // namespace mrsim
