#include "nn_controller/network_genes.h"

namespace mrsim {

std::string WeightGeneName(long i) { return "w" + std::to_string(i); }

std::vector<std::string> NetworkGeneNames(const MlpShape& shape) {
  std::vector<std::string> names = {kPeriodGene};
  const long n = shape.WeightCount();
  names.reserve(static_cast<size_t>(n) + 1);
  for (long i = 0; i < n; ++i) names.push_back(WeightGeneName(i));
  return names;
}

bool IsNetworkGeneName(const std::string& name) {
  if (name == kPeriodGene) return true;
  return name.size() >= 2 && name.size() <= 10 && name[0] == 'w' &&
         name.find_first_not_of("0123456789", 1) == std::string::npos;
}

}  // namespace mrsim
