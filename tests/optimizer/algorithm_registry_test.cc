// The registry of optimiser algorithms is the one list: every row builds
// its algorithm, names parse and print through it, and docs/optimizer.md
// describes exactly the algorithms it holds, in its order.
#include "optimizer/search/algorithm_registry.h"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "optimizer/search/algorithm.h"
#include "optimizer/episode/episode.h"
#include "tests/common/child_process.h"

namespace mrsim {
namespace {

GenomeSpec TwoGenes() {
  GenomeSpec spec;
  for (const char* name : {"a", "b"}) {
    GeneSpec g;
    g.name = name;
    g.lower = -1;
    g.upper = 1;
    spec.genes.push_back(g);
  }
  return spec;
}

TEST(AlgorithmRegistry, EveryRowBuildsItsAlgorithmAndRoundTripsItsName) {
  for (const AlgorithmInfo& info : Algorithms()) {
    EXPECT_EQ(ParseAlgorithm(info.name), info.kind) << info.name;
    EXPECT_STREQ(ToString(info.kind), info.name);
    EXPECT_EQ(&AlgorithmInfoOf(info.kind), &info);
    // Menus holding an index (the studio's default) find the row by kind.
    EXPECT_EQ(&Algorithms().at(AlgorithmIndex(info.kind)), &info);
    AlgorithmSettings settings;
    settings.algorithm = info.kind;
    settings.population = std::max(4, info.min_population);
    auto algorithm = MakeAlgorithm(TwoGenes(), settings);
    ASSERT_NE(algorithm, nullptr) << info.name;
    EXPECT_EQ(static_cast<int>(algorithm->Ask().size()), settings.population)
        << info.name;
  }
}

TEST(AlgorithmRegistry, UnknownNameIsRefusedNamingFieldAndEveryAlgorithm) {
  try {
    ParseAlgorithm("hillclimb", "--algorithm");
    FAIL() << "hillclimb accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(),
                 "--algorithm: expected ga, sa, pso, cmaes or random, got "
                 "'hillclimb'");
  }
}

TEST(AlgorithmRegistry, PopulationBelowAnAlgorithmsMinimumIsRefused) {
  AlgorithmSettings settings;
  settings.algorithm = AlgorithmKind::kCmaes;
  settings.population = 1;
  try {
    settings.Validate();
    FAIL() << "CMA-ES with one individual accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("CMA-ES"), std::string::npos);
  }
}

// The "## Algorithms" section of docs/optimizer.md lists each algorithm as
// a bullet "- `name`: ...".
std::vector<std::string> DocumentedAlgorithms() {
  std::ifstream in(testing::SourcePath("docs/optimizer.md"));
  EXPECT_TRUE(in) << "docs/optimizer.md";
  std::vector<std::string> names;
  std::string line;
  bool inside = false;
  while (std::getline(in, line)) {
    if (line.rfind("## ", 0) == 0 || line.rfind("### ", 0) == 0) {
      inside = line == "## Algorithms";
      continue;
    }
    if (!inside || line.rfind("- `", 0) != 0) continue;
    const size_t end = line.find('`', 3);
    if (end != std::string::npos) names.push_back(line.substr(3, end - 3));
  }
  return names;
}

TEST(AlgorithmRegistry, DocsListEveryAlgorithmOfTheRegistryInOrder) {
  std::vector<std::string> registry;
  for (const AlgorithmInfo& info : Algorithms()) registry.push_back(info.name);
  EXPECT_EQ(DocumentedAlgorithms(), registry)
      << "docs/optimizer.md's \"## Algorithms\" bullets and "
         "optimizer/search/algorithm_registry.cc disagree";
}

TEST(SettingEnums, ParseAndPrintThroughOneTable) {
  for (const std::string& name : SelectionMethods().Names()) {
    EXPECT_EQ(ToString(ParseSelectionMethod(name)), name);
  }
  for (const std::string& name : DistanceModes().Names()) {
    EXPECT_EQ(ToString(ParseDistanceMode(name)), name);
  }
  EXPECT_EQ(SelectionMethods().Names(),
            (std::vector<std::string>{"tournament", "truncation"}));
  EXPECT_EQ(DistanceModes().Names(),
            (std::vector<std::string>{"forward", "net", "up"}));
}

TEST(SettingEnums, BadWordNamesTheFieldAndListsValidWords) {
  try {
    ParseSelectionMethod("best");
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(),
                 "selection: expected tournament or truncation, got 'best'");
  }
  try {
    ParseDistanceMode("sideways", "--distance");
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(),
                 "--distance: expected forward, net or up, got 'sideways'");
  }
}

TEST(SettingEnums, ValueOutsideTheTableIsRefusedByValidate) {
  AlgorithmSettings a;
  a.selection = static_cast<SelectionMethod>(7);
  EXPECT_THROW(a.Validate(), std::invalid_argument);
  EpisodeSettings e;
  e.fitness.distance_mode = static_cast<DistanceMode>(9);
  EXPECT_THROW(e.Validate(), std::invalid_argument);
}

}  // namespace
}  // namespace mrsim
