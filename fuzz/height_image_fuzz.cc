// The terrain's height image decoder on any bytes (a scenario's embedded
// height_Image): a decoded image within the limits, or an error naming it.
#include <cstdint>
#include <cstdlib>
#include <stdexcept>
#include <vector>

#include "sim_core/mesh/base64.h"
#include "sim_core/scenario/terrain.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  mrsim::Scene scene;
  scene.height_image =
      "base64:" +
      mrsim::Base64Encode(std::vector<unsigned char>(data, data + size));
  try {
    const mrsim::TerrainImage image = mrsim::LoadTerrainImage(scene, "");
    if (static_cast<long long>(image.rows) * image.cols >
            mrsim::kMaxTerrainPixels ||
        image.grey.size() != static_cast<size_t>(image.rows) * image.cols) {
      std::abort();
    }
    mrsim::HeightFieldData(image);
  } catch (const std::runtime_error&) {
  }
  return 0;
}
