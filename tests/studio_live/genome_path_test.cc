// The panel's genome path, for a studio started outside the repository.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
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

// An installed studio started from the desktop menu (no design, the home
// folder): the panel's default is the bundled genome in the data folder.
TEST(GenomePathFor, WithoutADesignTheInstalledGenomeIsFound) {
  const std::string data = testing::TempDir("genome_path_data");
  std::filesystem::create_directories(data + "/scenarios");
  const std::string genome = data + "/scenarios/forward_gait.genome.xml";
  std::ofstream(genome) << "<x/>";
  setenv("MRSIM_DATA_DIR", data.c_str(), 1);
  EXPECT_EQ(GenomePathFor("scenarios/forward_gait.genome.xml", ""), genome);
  EXPECT_EQ(GenomePathFor("nowhere/else.xml", ""), "nowhere/else.xml");
  unsetenv("MRSIM_DATA_DIR");
}

}  // namespace
}  // namespace mrsim::studio
