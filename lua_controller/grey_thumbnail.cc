#include "lua_controller/grey_thumbnail.h"

#include <algorithm>
#include <cmath>

namespace mrsim {

GreyThumbnail MakeGreyThumbnail(int width, int height, const uint8_t* rgb) {
  GreyThumbnail out;
  if (width < 1 || height < 1) return out;
  const double scale =
      std::min({1.0, static_cast<double>(GreyThumbnail::kMaxWidth) / width,
                static_cast<double>(GreyThumbnail::kMaxHeight) / height});
  out.width = std::clamp(static_cast<int>(std::lround(width * scale)), 1,
                         std::min(width, GreyThumbnail::kMaxWidth));
  out.height = std::clamp(static_cast<int>(std::lround(height * scale)), 1,
                          std::min(height, GreyThumbnail::kMaxHeight));
  out.grey.resize(static_cast<size_t>(out.width) * out.height);
  for (int ty = 0; ty < out.height; ++ty) {
    // Block edges by integer division: every pixel in exactly one block.
    const int y0 = static_cast<int>(int64_t{ty} * height / out.height);
    const int y1 = static_cast<int>(int64_t{ty + 1} * height / out.height);
    for (int tx = 0; tx < out.width; ++tx) {
      const int x0 = static_cast<int>(int64_t{tx} * width / out.width);
      const int x1 = static_cast<int>(int64_t{tx + 1} * width / out.width);
      int64_t r = 0, g = 0, b = 0;
      for (int y = y0; y < y1; ++y) {
        const uint8_t* p = rgb + (static_cast<size_t>(y) * width + x0) * 3;
        for (int x = x0; x < x1; ++x, p += 3) {
          r += p[0];
          g += p[1];
          b += p[2];
        }
      }
      const double n = static_cast<double>(y1 - y0) * (x1 - x0);
      out.grey[static_cast<size_t>(ty) * out.width + tx] =
          (0.299 * r + 0.587 * g + 0.114 * b) / (255.0 * n);
    }
  }
  return out;
}

}  // namespace mrsim
