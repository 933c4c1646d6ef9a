// Network files: one neural-network controller (MlpNetwork) as XML, what
// mrsim-opt --controller mlp:H saves as best_network.xml and mrsim-nn runs
// (docs/nn.md). Numbers are written in their shortest exact form, so a
// network read back has the same weights bit for bit.
//
//   <network name="optimised" joints="11" hidden="8" clock="1" imu="0"
//            sensors="0" range="1.5708" period="2.5">
//     <weights count="299">0.12 -0.5 ... (whitespace separated)</weights>
//   </network>
#pragma once

#include <stdexcept>
#include <string>

#include "nn_controller/mlp_network.h"

namespace mrsim {

// A bad network file. what() names the file, the line and the field, and
// what was expected.
class NetworkFileError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct NetworkFile {
  std::string name = "network";
  MlpNetwork network;
};

// Reads and validates a network: every attribute but name is required; the
// shape's bounds (MlpShape) are checked before the weights are allocated.
// Throws NetworkFileError.
NetworkFile ReadNetworkFile(const std::string& path);
// As ReadNetworkFile; `source` names the text in error messages.
NetworkFile ReadNetworkString(const std::string& xml,
                              const std::string& source);

std::string WriteNetworkString(const MlpNetwork& network,
                               const std::string& name = "network");
// Through a temporary file and a rename. Throws NetworkFileError.
void WriteNetworkFile(const MlpNetwork& network, const std::string& path,
                      const std::string& name = "network");

}  // namespace mrsim
