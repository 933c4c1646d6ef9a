// A camera picture as a Lua script is given it (state.cameras, docs/lua.md):
// grey levels 0..1, at most kMaxWidth x kMaxHeight, each the mean
// brightness of a block of the picture. A script cannot afford to walk
// 160 x 120 x 3 numbers per step inside its instruction budget, and a
// thumbnail is enough to steer toward something bright or dark.
#pragma once

#include <cstdint>
#include <vector>

namespace mrsim {

struct GreyThumbnail {
  static constexpr int kMaxWidth = 32;
  static constexpr int kMaxHeight = 24;

  int width = 0;
  int height = 0;
  std::vector<double> grey;  // height x width, top row first
};

// The thumbnail of a width x height RGB picture (`rgb`: red first, top row
// first, width * height * 3 bytes): scaled down by one factor in both
// directions (no more than needed to fit, never up), so it keeps the
// picture's shape. Grey is 0.299 R + 0.587 G + 0.114 B over 255. The same
// picture always gives the same numbers.
GreyThumbnail MakeGreyThumbnail(int width, int height, const uint8_t* rgb);

}  // namespace mrsim
