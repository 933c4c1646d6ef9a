// The physics effects are listed once (PhysicsEffectKinds()): Physics
// builds exactly the ones a scene gives something to do, and
// docs/physics.md lists every one of them as the table does.
#include <gtest/gtest.h>

#include <fstream>
#include <set>
#include <string>
#include <vector>

#include "sim_core/physics/physics.h"
#include "sim_core/physics/physics_effect_kinds.h"
#include "sim_core/scenario/chain_builder.h"
#include "tests/common/child_process.h"

namespace mrsim {
namespace {

using Names = std::vector<std::string>;

Scenario Snake() {
  ChainScenarioOptions o;
  o.chain.modules = 4;
  o.chain.pattern = ChainPattern::kYaw;
  o.friction = 0.6;
  return MakeChainScenario(o);
}

FluidRegion Pond() {
  FluidRegion water;
  water.guid = "pond";
  water.position = Eigen::Vector3d(0, 0, 0.02);
  water.size = Eigen::Vector3d(3, 3, 0.04);
  return water;
}

TEST(PhysicsEffectKinds, ListEachEffectOnceWithAHookAndAFactory) {
  std::set<std::string> names;
  int servo_laws = 0;
  for (const PhysicsEffectKind& kind : PhysicsEffectKinds()) {
    ASSERT_NE(kind.name, nullptr);
    EXPECT_TRUE(names.insert(kind.name).second) << kind.name << " twice";
    EXPECT_NE(std::string(kind.summary), "") << kind.name;
    EXPECT_NE(PhysicsHookNames(kind.hooks), "") << kind.name;
    EXPECT_NE(kind.make, nullptr) << kind.name;
    servo_laws += (kind.hooks & kHookControls) ? 1 : 0;
  }
  for (const char* effect : {"fluids", "directional_friction", "reality_gap"}) {
    EXPECT_EQ(names.count(effect), 1u) << effect;
  }
  // One servo law at a time (PhysicsEffect::Controls).
  EXPECT_LE(servo_laws, 1);
}

TEST(PhysicsEffects, PhysicsBuildsExactlyTheEffectsItsSceneNeeds) {
  EXPECT_EQ(Physics(Snake()).effects(), Names{}) << "a plain snake";

  Scenario wet = Snake();
  wet.fluid_regions.push_back(Pond());
  EXPECT_EQ(Physics(wet).effects(), Names{"fluids"});

  Scenario scales = Snake();
  scales.contact_frictions[0].directional = true;
  EXPECT_EQ(Physics(scales).effects(), Names{"directional_friction"});

  Scenario wheels = Snake();
  wheels.robots[0].modules[2].passive_wheels = true;
  EXPECT_EQ(Physics(wheels).effects(), Names{"directional_friction"});

  Scenario all = wet;
  all.contact_frictions = scales.contact_frictions;
  Physics physics(all);
  EXPECT_EQ(physics.effects(), (Names{"fluids", "directional_friction"}));
  physics.SetRealityGap(RealityGap::Typical());
  EXPECT_EQ(physics.effects(),
            (Names{"fluids", "directional_friction", "reality_gap"}));
  physics.Reset();  // keeps the gap
  EXPECT_EQ(physics.effects(),
            (Names{"fluids", "directional_friction", "reality_gap"}));
  RealityGap episode_only;  // per-episode ranges: nothing to do per step
  episode_only.mass_range = 0.1;
  physics.SetRealityGap(episode_only);
  EXPECT_EQ(physics.effects(), (Names{"fluids", "directional_friction"}));
}

TEST(PhysicsEffects, EveryWorldOfASplitSceneRunsTheSceneEffects) {
  Scenario s = Snake();
  ChainOptions far;
  far.name = "far";
  far.modules = 4;
  far.origin = Eigen::Vector3d(0, 3, 0);
  s.robots.push_back(MakeChain(far));
  s.robots[1].modules[1].passive_wheels = true;
  s.fluid_regions.push_back(Pond());
  Physics physics(s);
  const std::vector<unsigned char> state = physics.SaveState();
  ASSERT_EQ(std::string(state.begin(), state.begin() + 8), "MRSIMSW1")
      << "the two robots run in one world";
  EXPECT_EQ(physics.effects(), (Names{"fluids", "directional_friction"}));
  physics.SetRealityGap(RealityGap::Typical());
  EXPECT_EQ(physics.effects(),
            (Names{"fluids", "directional_friction", "reality_gap"}));
}

// The table of the "## Physics effects" section of docs/physics.md: its
// rows after the header row "| effect | hooks | what |".
std::vector<std::string> DocumentedEffects() {
  std::ifstream in(testing::SourcePath("docs/physics.md"));
  EXPECT_TRUE(in) << "docs/physics.md";
  std::vector<std::string> rows;
  std::string line;
  bool section = false, table = false;
  while (std::getline(in, line)) {
    if (line.rfind("## ", 0) == 0) {
      section = line == "## Physics effects";
      table = false;
      continue;
    }
    if (!section) continue;
    if (line == "| effect | hooks | what |") {
      table = true;
    } else if (table && line.rfind("|---", 0) != 0) {
      if (line.rfind("| ", 0) != 0) break;
      rows.push_back(line);
    }
  }
  return rows;
}

TEST(PhysicsEffectKinds, DocsListEveryEffectOfTheTableInOrder) {
  std::vector<std::string> expected;
  std::string paste;
  for (const PhysicsEffectKind& kind : PhysicsEffectKinds()) {
    expected.push_back("| `" + std::string(kind.name) + "` | " +
                       PhysicsHookNames(kind.hooks) + " | " + kind.summary +
                       " |");
    paste += expected.back() + "\n";
  }
  EXPECT_EQ(DocumentedEffects(), expected)
      << "docs/physics.md's \"## Physics effects\" table and "
         "sim_core/physics/physics_effect_kinds.cc disagree; its rows are:\n"
      << paste;
}

}  // namespace
}  // namespace mrsim
