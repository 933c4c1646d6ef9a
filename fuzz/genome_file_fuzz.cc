// The genome file reader on any bytes, as mrsim-opt reads a user's file
// and as a farm reads a problem's genome (any gene names): a genome that
// validates, or a GenomeError. fuzz-dict: xml
#include <cstdint>
#include <string>

#include "optimizer/search/genome.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string xml(reinterpret_cast<const char*>(data), size);
  for (const bool any_name : {false, true}) {
    try {
      const mrsim::GenomeSpec spec =
          mrsim::ReadGenomeString(xml, "fuzz.genome.xml", any_name);
      spec.Check(spec.StartGenome());
    } catch (const mrsim::GenomeError&) {
    }
  }
  return 0;
}
