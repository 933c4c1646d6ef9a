// A Problem as one self-contained text payload: what the master sends to
// the workers (in chunks) and what the local evaluator decodes too, so a
// local run and a farm run evaluate exactly the same bytes.
#pragma once

#include <stdexcept>
#include <string>

#include "optimizer/episode/episode.h"

namespace mrsim {

class ProblemError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Replaces a terrain image path by its bytes ("base64:...") and every mesh
// frame's file by its bytes (sim_core/mesh/embedded_mesh.h), so the scenario
// names no file. Throws ProblemError naming the frame for an unreadable
// mesh.
void EmbedAssets(Scenario& scenario);

// The payload (assets must be embedded).
std::string EncodeProblem(const Problem& problem);

// Throws ProblemError naming `source` on a malformed payload, a scenario
// that names a file (image path or mesh path), or invalid contents. Reads no
// file.
Problem DecodeProblem(const std::string& payload, const std::string& source);

}  // namespace mrsim
