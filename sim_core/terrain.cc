#include "sim_core/terrain.h"

#include <stb/stb_image.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <optional>
#include <stdexcept>

#include "common/input_limits.h"
#include "sim_core/base64.h"

namespace mrsim {
namespace {

namespace fs = std::filesystem;

constexpr char kBase64Prefix[] = "base64:";

bool HasBase64Prefix(const std::string& s) {
  return s.rfind(kBase64Prefix, 0) == 0;
}

std::string Shorten(const std::string& s) {
  return s.size() <= 60 ? s : s.substr(0, 57) + "...";
}

TerrainImage Decode(const std::vector<unsigned char>& bytes,
                    const std::string& source) {
  if (bytes.empty()) {
    throw std::runtime_error("terrain image " + source + " is empty");
  }
  if (bytes.size() > kMaxInputFileBytes) {
    throw std::runtime_error("terrain image " + source + ": larger than " +
                             std::to_string(kMaxInputFileBytes >> 20) + " MiB");
  }
  // stb_image (PNG 8/16 bit, JPEG, BMP, TGA...), converted to one grey
  // channel: no video stack in the core library.
  const int size = static_cast<int>(bytes.size());
  // The header first: a few bytes can claim 100,000 x 100,000 pixels, and
  // decoding would allocate for them before finding the data missing.
  const std::string most = "at most " + std::to_string(kMaxTerrainSide) +
                           " on a side and " +
                           std::to_string(kMaxTerrainPixels) + " in all";
  int header_cols = 0, header_rows = 0, header_channels = 0;
  // (stb refuses headers beyond 2^30 bytes of pixels itself, before it
  // allocates: see the failure below.)
  if (stbi_info_from_memory(bytes.data(), size, &header_cols, &header_rows,
                            &header_channels) != 0 &&
      (header_cols > kMaxTerrainSide || header_rows > kMaxTerrainSide ||
       static_cast<long long>(header_cols) * header_rows > kMaxTerrainPixels)) {
    throw std::runtime_error("terrain image " + source + ": " +
                             std::to_string(header_cols) + "x" +
                             std::to_string(header_rows) + " pixels; " + most);
  }
  const bool wide = stbi_is_16_bit_from_memory(bytes.data(), size) != 0;
  int cols = 0, rows = 0, channels = 0;
  std::unique_ptr<void, decltype(&stbi_image_free)> pixels(
      wide ? static_cast<void*>(stbi_load_16_from_memory(
                 bytes.data(), size, &cols, &rows, &channels, 1))
           : static_cast<void*>(stbi_load_from_memory(bytes.data(), size, &cols,
                                                      &rows, &channels, 1)),
      &stbi_image_free);
  if (!pixels) {
    if (std::string(stbi_failure_reason()) == "too large") {
      throw std::runtime_error("terrain image " + source +
                               ": its header claims more pixels than can be "
                               "decoded; " +
                               most);
    }
    throw std::runtime_error(
        "terrain image " + source +
        ": not an image (PNG, JPEG, BMP, TGA...): " + stbi_failure_reason());
  }
  if (rows < 2 || cols < 2) {
    throw std::runtime_error("terrain image " + source +
                             ": needs at least 2x2 pixels, got " +
                             std::to_string(cols) + "x" + std::to_string(rows));
  }
  TerrainImage image;
  image.rows = rows;
  image.cols = cols;
  image.source = source;
  const size_t n = static_cast<size_t>(rows) * cols;
  image.grey.resize(n);
  for (size_t i = 0; i < n; ++i) {
    image.grey[i] =
        wide ? static_cast<const unsigned short*>(pixels.get())[i] / 65535.0f
             : static_cast<const unsigned char*>(pixels.get())[i] / 255.0f;
  }
  return image;
}

}  // namespace

bool TerrainImageIsFile(const Scene& scene, const std::string& base_dir,
                        std::string* path) {
  const std::string& s = scene.height_image;
  if (s.empty() || HasBase64Prefix(s) || s.size() > 4096) return false;
  fs::path p(s);
  if (p.is_relative() && !base_dir.empty()) p = fs::path(base_dir) / p;
  std::error_code ec;
  if (!fs::is_regular_file(p, ec)) return false;
  if (path) *path = fs::absolute(p, ec).lexically_normal().string();
  return true;
}

TerrainImage LoadTerrainImage(const Scene& scene, const std::string& base_dir) {
  const std::string& s = scene.height_image;
  if (s.empty()) {
    throw std::runtime_error("scene '" + scene.guid + "' has no height image");
  }
  std::string path;
  if (TerrainImageIsFile(scene, base_dir, &path)) {
    std::optional<std::string> text;
    try {
      text = ReadFileAtMost(path);
    } catch (const InputLimitError& e) {
      throw std::runtime_error("terrain image " + std::string(e.what()));
    }
    if (!text) {
      throw std::runtime_error("terrain image '" + path +
                               "': cannot open the file");
    }
    return Decode(std::vector<unsigned char>(text->begin(), text->end()),
                  "'" + path + "'");
  }
  const bool prefixed = HasBase64Prefix(s);
  std::vector<unsigned char> bytes;
  try {
    bytes = Base64Decode(prefixed ? s.substr(sizeof(kBase64Prefix) - 1) : s);
  } catch (const std::exception& e) {
    if (prefixed) {
      throw std::runtime_error("terrain image (embedded base64): " +
                               std::string(e.what()));
    }
    throw std::runtime_error("terrain image '" + Shorten(s) +
                             "': no such file (relative to '" + base_dir +
                             "') and not base64 image bytes");
  }
  if (!prefixed) {
    // Bare base64 that does not decode to an image is most likely a path
    // that does not exist; say so.
    int cols = 0, rows = 0, channels = 0;
    if (stbi_info_from_memory(bytes.data(), static_cast<int>(bytes.size()),
                              &cols, &rows, &channels) == 0) {
      throw std::runtime_error("terrain image '" + Shorten(s) +
                               "': no such file (relative to '" + base_dir +
                               "') and not base64 image bytes");
    }
  }
  return Decode(bytes, "(embedded base64)");
}

std::vector<float> HeightFieldData(const TerrainImage& image) {
  std::vector<float> data(image.grey.size(), 0.0f);
  if (image.grey.empty()) return data;
  const auto [lo, hi] =
      std::minmax_element(image.grey.begin(), image.grey.end());
  const float min = *lo;
  const float range = *hi - *lo;
  for (int r = 0; r < image.rows; ++r) {
    const int src = (image.rows - 1 - r) * image.cols;
    for (int c = 0; c < image.cols; ++c) {
      data[r * image.cols + c] =
          range > 0 ? (image.grey[src + c] - min) / range : 0.0f;
    }
  }
  return data;
}

double TerrainHeightAt(const Scene& scene, const TerrainImage& image, double x,
                       double y) {
  if (image.rows < 2 || image.cols < 2) return 0.0;
  const double width = image.cols * scene.meters_per_pixel;
  const double depth = image.rows * scene.meters_per_pixel;
  const double u = (x - scene.position.x()) / width * (image.cols - 1);
  const double v = (y - scene.position.y()) / depth * (image.rows - 1);
  if (u < 0 || v < 0 || u > image.cols - 1 || v > image.rows - 1) return 0.0;
  const std::vector<float> data = HeightFieldData(image);
  const int c0 = std::min(static_cast<int>(u), image.cols - 2);
  const int r0 = std::min(static_cast<int>(v), image.rows - 2);
  const double fu = u - c0, fv = v - r0;
  auto at = [&](int r, int c) { return data[r * image.cols + c]; };
  const double h = (1 - fv) * ((1 - fu) * at(r0, c0) + fu * at(r0, c0 + 1)) +
                   fv * ((1 - fu) * at(r0 + 1, c0) + fu * at(r0 + 1, c0 + 1));
  return h * scene.height;
}

}  // namespace mrsim
