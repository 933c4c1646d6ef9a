#include "sim_core/scenario/terrain.h"

#include <stb/stb_image.h>
#include <zlib.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <optional>
#include <stdexcept>

#include "common/input_limits.h"
#include "sim_core/mesh/base64.h"

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

uint32_t ReadBigEndian32(const unsigned char* p) {
  return (uint32_t{p[0]} << 24) | (uint32_t{p[1]} << 16) |
         (uint32_t{p[2]} << 8) | uint32_t{p[3]};
}

// stb_image trusts a PNG's chunk lengths (it grows its buffer to a chunk's
// claimed length before finding the bytes missing: 70 bytes could make it
// allocate 2 GiB) and lets the image data inflate without bound. So a PNG
// is walked here first: every chunk must fit in the bytes left, and the
// image data must inflate (zlib) to no more than its header's pixels need.
void CheckPng(const std::vector<unsigned char>& bytes,
              const std::string& source) {
  static constexpr std::array<unsigned char, 8> kSignature = {
      0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  if (bytes.size() < kSignature.size() ||
      !std::equal(kSignature.begin(), kSignature.end(), bytes.begin())) {
    return;
  }
  auto fail = [&](const std::string& what) {
    throw std::runtime_error("terrain image " + source +
                             ": not a valid PNG: " + what);
  };
  size_t pos = kSignature.size();
  uint64_t raw_bytes = 0;  // what the header's pixels inflate to, at most
  std::vector<std::pair<size_t, size_t>> data;  // IDAT (offset, length)
  bool end = false;
  while (!end) {
    const size_t left = bytes.size() - pos;
    if (left == 0) break;  // no IEND: stb says what is missing
    // stb reads a cut chunk header as if the missing bytes were zeros, and
    // its length could still claim gigabytes: a chunk is whole or refused.
    if (left < 12) {
      fail("it ends inside the chunk at byte " + std::to_string(pos) + " (" +
           std::to_string(left) + " of at least 12 bytes)");
    }
    const uint64_t length = ReadBigEndian32(&bytes[pos]);
    const std::string type(reinterpret_cast<const char*>(&bytes[pos + 4]), 4);
    if (length > left - 12) {
      fail("chunk '" + type + "' at byte " + std::to_string(pos) + " claims " +
           std::to_string(length) + " bytes; only " +
           std::to_string(bytes.size() - pos - 12) + " are left");
    }
    const unsigned char* body = &bytes[pos + 8];
    if (type == "IHDR" && length >= 13) {
      const uint64_t cols = ReadBigEndian32(body);
      const uint64_t rows = ReadBigEndian32(body + 4);
      const uint64_t depth = body[8];
      static const int kChannels[] = {1, 0, 3, 1, 2, 0, 4};
      const uint64_t channels = body[9] < 7 ? kChannels[body[9]] : 0;
      if (channels == 0) fail("colour type " + std::to_string(body[9]));
      // A filter byte per row; Adam7 interlacing adds at most a filter byte
      // and a partial byte per row of each of its seven passes.
      raw_bytes =
          rows * (1 + (cols * channels * depth + 7) / 8) + 14 * rows + 1024;
    } else if (type == "IDAT") {
      data.emplace_back(pos + 8, static_cast<size_t>(length));
    } else if (type == "IEND") {
      end = true;
    }
    pos += 12 + length;
  }
  if (raw_bytes == 0 || data.empty()) return;  // stb says what is missing
  z_stream z{};
  if (inflateInit(&z) != Z_OK) fail("zlib cannot start");
  std::unique_ptr<z_stream, int (*)(z_stream*)> guard(&z, &inflateEnd);
  std::vector<unsigned char> scratch(1 << 16);
  uint64_t inflated = 0;
  int rc = Z_OK;
  for (const auto& [offset, length] : data) {
    z.next_in = const_cast<unsigned char*>(&bytes[offset]);
    z.avail_in = static_cast<uInt>(length);
    while (z.avail_in > 0 && rc == Z_OK) {
      z.next_out = scratch.data();
      z.avail_out = static_cast<uInt>(scratch.size());
      rc = inflate(&z, Z_NO_FLUSH);
      inflated += scratch.size() - z.avail_out;
      if (inflated > raw_bytes) {
        fail("its image data inflates to more than the " +
             std::to_string(raw_bytes) + " bytes its header's pixels need");
      }
      if (rc == Z_BUF_ERROR) rc = Z_OK;  // more input in the next chunk
      if (rc != Z_OK && rc != Z_STREAM_END) break;
    }
    if (rc != Z_OK) break;
  }
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
  CheckPng(bytes, source);
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
