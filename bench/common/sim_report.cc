#include "bench/common/sim_report.h"

#include <fstream>
#include <sstream>
#include <stdexcept>

namespace mrsim {

double ReadRealTimeFactor(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  const std::string key = "real-time factor ";
  const size_t at = text.str().rfind(key);
  if (at == std::string::npos) {
    throw std::runtime_error(path + ": no real-time factor in: " + text.str());
  }
  return std::stod(text.str().substr(at + key.size()));
}

}  // namespace mrsim
