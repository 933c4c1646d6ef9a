// The terrain's height image decoded to grey values, shared by the MJCF
// builder, the physics and the scenario validator.
#pragma once

#include <string>
#include <vector>

#include "sim_core/scenario/scenario.h"

namespace mrsim {

// The largest height image the terrain takes (docs/scenario.md, "Limits"),
// checked on the image's header before it is decoded: 4096 x 4096 samples
// is a 40 m square at 1 cm per pixel, and MuJoCo's height field of it
// already holds 64 MB.
inline constexpr int kMaxTerrainSide = 16384;
inline constexpr long long kMaxTerrainPixels = 4096LL * 4096;

// A grey-scale image, row-major, row 0 = top row of the image (the +y edge
// of the terrain), values in [0, 1] (pixel / max pixel value of the depth).
struct TerrainImage {
  int rows = 0;
  int cols = 0;
  std::vector<float> grey;
  std::string source;  // the file path, or "<base64 image>" for embedded bytes
};

// Decodes Scene::height_image: "base64:<bytes>", a path (absolute or
// relative to base_dir), or bare base64 bytes. Throws std::runtime_error
// naming the image when it cannot be read or decoded. Empty height_image is
// an error too (callers check Scene::height_image first).
TerrainImage LoadTerrainImage(const Scene& scene, const std::string& base_dir);

// True when height_image names a file (relative to base_dir or absolute)
// rather than embedded bytes; `path` receives the resolved path.
bool TerrainImageIsFile(const Scene& scene, const std::string& base_dir,
                        std::string* path);

// Elevation of each sample as MuJoCo's height field stores it: rows
// flipped so row 0 is the -y edge, normalised so the darkest pixel is 0 and
// the brightest 1 (all 0 for a uniform image). This is exactly what MuJoCo
// does with a PNG given by file=, so exported and in-memory models agree.
std::vector<float> HeightFieldData(const TerrainImage& image);

// Height of the terrain surface above Scene::position.z at world (x, y),
// bilinear like MuJoCo's height field; 0 outside the image.
double TerrainHeightAt(const Scene& scene, const TerrainImage& image, double x,
                       double y);

}  // namespace mrsim
