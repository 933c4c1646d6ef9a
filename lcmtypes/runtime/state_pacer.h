// Which of a simulator's states one controller answers, and the answers it
// keeps for states the simulator sends again: the lockstep protocol that
// every controller node (mrsim-gait, mrsim-lua) follows, in one place so
// they cannot drift apart (docs/sim.md, "Clock modes"). The node computes the
// joint targets; the pacer says whether to, re-sends recent answers, skips
// states closer than 1/rate, and notices a reset (sim time going back).
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "mrsim/joint_command_t.hpp"
#include "mrsim/robot_state_t.hpp"

namespace mrsim {

class StatePacer {
 public:
  // Answers kept for states the simulator may send again (pipelined
  // lockstep re-sends the two states it waits for).
  static constexpr size_t kRecentAnswers = 8;

  enum class Verdict {
    kAnswer,  // compute targets and call Answer()
    kRepeat,  // re-send repeat(): the state came again
    kSkip,    // older than the last answer, or closer than 1/rate
  };
  struct Decision {
    Verdict verdict = Verdict::kSkip;
    const joint_command_t* repeat = nullptr;  // with kRepeat
    // Sim time went back (a reset or a loaded checkpoint): the controller
    // starts again from rest before answering.
    bool restarted = false;
  };

  // rate: Hz of sim time (0: every state). Throws std::invalid_argument
  // ("--rate must be >= 0") on a negative or non-finite rate.
  StatePacer(std::string robot, std::string sender, double rate);

  // `may_be_lockstep`: the simulator's clock is lockstep or not yet known.
  // A lockstep simulator sending a skipped state again waits for it, so
  // from then on every state is answered (said once in `note`).
  Decision Decide(const robot_state_t& state, bool may_be_lockstep,
                  std::string* note);
  // The command answering `state` with `targets`; kept for repeats.
  const joint_command_t& Answer(const robot_state_t& state,
                                std::vector<double> targets);
  // The controller went back to rest without a reset of the sim time
  // (e.g. a non-finite target): the next answer has no previous time.
  void Restart() { have_last_ = false; }
  // A restored checkpoint: its timing, and no answer kept is valid now.
  void Restore(bool have_last, double last_time);

  bool have_last() const { return have_last_; }
  double last_time() const { return last_time_; }
  double rate() const { return rate_; }

 private:
  std::string robot_;
  std::string sender_;
  double rate_;  // the option until lockstep shows it must be 0
  int64_t last_skipped_seq_ = -1;
  bool have_last_ = false;
  int64_t last_state_seq_ = -1;
  double last_time_ = 0;
  int64_t command_seq_ = 0;
  std::map<int64_t, joint_command_t> recent_;  // answers by state seq
};

}  // namespace mrsim
