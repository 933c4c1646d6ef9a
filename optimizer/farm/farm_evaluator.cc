#include "optimizer/farm/farm_evaluator.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "common/printable.h"
#include "common/wall_time.h"

namespace mrsim {

FarmLink::Handlers FarmEvaluator::MakeHandlers() {
  FarmLink::Handlers h;
  h.heartbeat = [this](const opt_heartbeat_t& m) {
    core_.OnHeartbeat(m, FarmLink::Now());
  };
  h.result = [this](const opt_result_t& m) {
    core_.OnResult(m, FarmLink::Now());
  };
  h.chunk_request = [this](const opt_chunk_request_t& m) {
    core_.OnChunkRequest(m, FarmLink::Now());
  };
  h.malformed = [this] { core_.CountMalformed(); };
  return h;
}

FarmEvaluator::FarmEvaluator(const std::string& lcm_url, std::string payload,
                             std::string run_id, FarmSettings settings)
    : settings_(settings),
      core_(std::move(payload), std::move(run_id), WallMicros(),
            std::move(settings)) {
  link_ = std::make_unique<FarmLink>(lcm_url, settings_.prefix, MakeHandlers(),
                                     settings_.auth);
  worker_hint_ =
      fmt::format("; start one with: mrsim-worker --lcm-url '{}'{}", lcm_url,
                  settings_.prefix == FarmSettings().prefix
                      ? ""
                      : " --prefix " + settings_.prefix);
  Step(0);
}

FarmEvaluator::FarmEvaluator(SignedLcm& lcm, std::string payload,
                             std::string run_id, FarmSettings settings)
    : settings_(settings),
      core_(std::move(payload), std::move(run_id), WallMicros(),
            std::move(settings)) {
  link_ = std::make_unique<FarmLink>(lcm, settings_.prefix, MakeHandlers());
  Step(0);
}

FarmEvaluator::~FarmEvaluator() = default;

void FarmEvaluator::Step(int timeout_ms) {
  link_->Handle(timeout_ms);
  FarmOutbox out = core_.Tick(FarmLink::Now());
  link_->Publish(out);
  for (const std::string& line : link_->TakeLog()) {
    if (settings_.log) settings_.log(Printable(line));  // names from peers
  }
}

std::vector<EvalResult> FarmEvaluator::Evaluate(
    const std::vector<Genome>& batch) {
  if (!in_flight_.empty()) {
    throw std::logic_error("FarmEvaluator: Evaluate with batches in flight");
  }
  Submit(batch);
  return Collect();
}

void FarmEvaluator::Submit(std::vector<Genome> batch) {
  in_flight_.push_back(core_.OpenBatch(batch));
  // The jobs go out now, not after the first wait for a message.
  FarmOutbox first = core_.Tick(FarmLink::Now());
  link_->Publish(first);
}

std::vector<EvalResult> FarmEvaluator::Collect() {
  if (in_flight_.empty()) {
    throw std::logic_error("FarmEvaluator: Collect with nothing submitted");
  }
  const std::int64_t id = in_flight_.front();
  double last_wait_log = FarmLink::Now();
  while (!core_.batch_done(id)) {
    const double wait = core_.next_deadline() - FarmLink::Now();
    Step(std::clamp(static_cast<int>(std::ceil(wait * 1000)), 0, 50));
    if (settings_.stop && settings_.stop()) {
      throw EvaluationInterrupted("farm evaluation interrupted");
    }
    if (!core_.failure().empty()) {
      throw std::runtime_error("farm: " + core_.failure());
    }
    const double now = FarmLink::Now();
    if (now - last_wait_log > 5.0 && core_.workers_ready() == 0) {
      if (settings_.log) {
        settings_.log(
            fmt::format("waiting for workers on {}_* ({} heard, none ready){}",
                        settings_.prefix, core_.workers_alive(), worker_hint_));
      }
      last_wait_log = now;
    }
  }
  std::vector<EvalResult> results = core_.results(id);
  core_.CloseBatch(id, FarmLink::Now());
  in_flight_.pop_front();
  return results;
}

}  // namespace mrsim
