// Template part of test_scenes.h.
#pragma once

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <stdexcept>

namespace mrsim::testing {

template <typename F>
std::string WriteGreyPng(const std::string& path, int rows, int cols, F pixel) {
  cv::Mat image(rows, cols, CV_8U);
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) image.at<unsigned char>(r, c) = pixel(r, c);
  }
  if (!cv::imwrite(path, image)) {
    throw std::runtime_error("cannot write " + path);
  }
  return path;
}

}  // namespace mrsim::testing
