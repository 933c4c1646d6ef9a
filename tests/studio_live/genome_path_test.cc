// The panel's genome path, for a studio started outside the repository.
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "studio/live/optimise_session.h"
#include "tests/common/child_process.h"

namespace mrsim::studio {
namespace {

TEST(GenomePathFor, ARelativePathNotFoundHereIsFoundBesideTheDesign) {
  const std::string dir = testing::TempDir("genome_path_for");
  const std::string design = dir + "/case_study.xml";
  const std::string genome = dir + "/forward_gait.genome.xml";
  std::ofstream(design) << "<x/>";
  std::ofstream(genome) << "<x/>";
  // The panel's default, typed relative to the repository.
  EXPECT_EQ(GenomePathFor("scenarios/forward_gait.genome.xml", design), genome);
  EXPECT_EQ(GenomePathFor("forward_gait.genome.xml", design), genome);
  // Absolute, missing everywhere, or no design yet: as typed, so the error
  // names what the user wrote.
  EXPECT_EQ(GenomePathFor(genome, design), genome);
  EXPECT_EQ(GenomePathFor("nowhere/else.xml", design), "nowhere/else.xml");
  EXPECT_EQ(GenomePathFor("scenarios/forward_gait.genome.xml", ""),
            "scenarios/forward_gait.genome.xml");
}

}  // namespace
}  // namespace mrsim::studio
