#include "lcmtypes/runtime/state_pacer.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

namespace mrsim {
namespace {

robot_state_t StateAt(int64_t seq, double sim_time) {
  robot_state_t s{};
  s.seq = seq;
  s.sim_time = sim_time;
  s.utime = static_cast<int64_t>(sim_time * 1e6);
  s.robot = "snake";
  return s;
}

TEST(StatePacer, AnswersAtTheRateAndSkipsStatesInBetween) {
  StatePacer pacer("snake", "gait", 50.0);  // every 20 ms of sim time
  std::string note;
  int answered = 0;
  for (int k = 0; k < 10; ++k) {
    const robot_state_t s = StateAt(k, 0.01 * k);
    const StatePacer::Decision d = pacer.Decide(s, false, &note);
    if (d.verdict == StatePacer::Verdict::kAnswer) {
      ++answered;
      pacer.Answer(s, {0.1});
    }
  }
  EXPECT_EQ(answered, 5);
  EXPECT_TRUE(note.empty());
}

TEST(StatePacer, ResendsTheSameAnswerForAStateSentAgain) {
  StatePacer pacer("snake", "gait", 0.0);
  const robot_state_t s = StateAt(7, 0.07);
  ASSERT_EQ(pacer.Decide(s, true, nullptr).verdict,
            StatePacer::Verdict::kAnswer);
  const joint_command_t first = pacer.Answer(s, {0.5, -0.5});
  EXPECT_EQ(first.state_seq, 7);
  EXPECT_EQ(first.robot, "snake");
  EXPECT_EQ(first.sender, "gait");
  const StatePacer::Decision again = pacer.Decide(s, true, nullptr);
  ASSERT_EQ(again.verdict, StatePacer::Verdict::kRepeat);
  EXPECT_EQ(again.repeat->seq, first.seq);
  EXPECT_EQ(again.repeat->target, first.target);
}

TEST(StatePacer, LockstepResendOfASkippedStateMakesItAnswerEveryState) {
  StatePacer pacer("snake", "gait", 50.0);
  pacer.Answer(StateAt(0, 0.0), {0});
  const robot_state_t s = StateAt(1, 0.01);
  ASSERT_EQ(pacer.Decide(s, true, nullptr).verdict, StatePacer::Verdict::kSkip);
  std::string note;
  EXPECT_EQ(pacer.Decide(s, true, &note).verdict, StatePacer::Verdict::kAnswer);
  EXPECT_NE(note.find("answering every state"), std::string::npos) << note;
  EXPECT_EQ(pacer.rate(), 0.0);
}

TEST(StatePacer, ARealTimeSimulatorResendingAStateDoesNotLiftTheRate) {
  StatePacer pacer("snake", "gait", 50.0);
  pacer.Answer(StateAt(0, 0.0), {0});
  const robot_state_t s = StateAt(1, 0.01);
  pacer.Decide(s, false, nullptr);
  EXPECT_EQ(pacer.Decide(s, false, nullptr).verdict,
            StatePacer::Verdict::kSkip);
  EXPECT_EQ(pacer.rate(), 50.0);
}

TEST(StatePacer, SimTimeGoingBackRestartsAndOlderSeqsAreSkipped) {
  StatePacer pacer("snake", "gait", 0.0);
  pacer.Answer(StateAt(5, 1.0), {0});
  EXPECT_EQ(pacer.Decide(StateAt(4, 0.9), true, nullptr).verdict,
            StatePacer::Verdict::kSkip);
  const StatePacer::Decision reset =
      pacer.Decide(StateAt(6, 0.0), true, nullptr);
  EXPECT_TRUE(reset.restarted);
  EXPECT_EQ(reset.verdict, StatePacer::Verdict::kAnswer);
  EXPECT_FALSE(pacer.have_last());
}

TEST(StatePacer, KeepsOnlyTheRecentAnswers) {
  StatePacer pacer("snake", "gait", 0.0);
  for (int k = 0; k < 20; ++k) pacer.Answer(StateAt(k, 0.01 * k), {0});
  EXPECT_EQ(pacer.Decide(StateAt(19, 0.19), true, nullptr).verdict,
            StatePacer::Verdict::kRepeat);
  EXPECT_EQ(
      pacer.Decide(StateAt(19 - StatePacer::kRecentAnswers, 0.1), true, nullptr)
          .verdict,
      StatePacer::Verdict::kSkip);
}

TEST(StatePacer, RefusesANegativeOrNonFiniteRate) {
  EXPECT_THROW(StatePacer("snake", "gait", -1.0), std::invalid_argument);
  EXPECT_THROW(StatePacer("snake", "gait", 1.0 / 0.0), std::invalid_argument);
}

}  // namespace
}  // namespace mrsim
