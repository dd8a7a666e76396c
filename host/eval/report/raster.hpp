// Minimal 2D drawing into an RgbImage for the report's pictures: blended pixels, discs, rings,
// crosses, lines and small digit labels. Everything clips at the image border.
#pragma once

#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "host/formats/bop/png_image.hpp"
#include "host/eval/report/colormap.hpp"

namespace binpick::eval {

class Canvas {
 public:
  Canvas(std::uint32_t width, std::uint32_t height, Rgb fill = {0, 0, 0});
  // A grey picture as RGB, each level multiplied by brightness (dimmed backgrounds).
  static Canvas from_gray(const GrayImage<std::uint8_t>& gray, double brightness = 1.0);

  std::uint32_t width() const { return image_.width; }
  std::uint32_t height() const { return image_.height; }
  const RgbImage& image() const { return image_; }

  Rgb get(int x, int y) const;
  // alpha 1 replaces, 0 leaves the pixel as is.
  void blend(int x, int y, Rgb c, double alpha = 1.0);
  void disc(double cx, double cy, double radius, Rgb c, double alpha = 1.0);
  void ring(double cx, double cy, double radius, double thickness, Rgb c);
  void cross(double cx, double cy, int half, int thickness, Rgb c);
  // A segment of the given thickness (pixels) from (x0, y0) to (x1, y1).
  void line(double x0, double y0, double x1, double y1, double thickness, Rgb c, double alpha = 1.0);
  // The inside of a closed polygon (even-odd rule), vertices in pixels.
  void polygon(const std::vector<Eigen::Vector2d>& vertices, Rgb c, double alpha = 1.0);
  // Digits and spaces in a 5 x 7 pixel font scaled by `scale`, top-left at (x, y), with a dark
  // outline so they read on any background. Other characters draw as spaces.
  void text(int x, int y, std::string_view digits, int scale, Rgb c);

 private:
  RgbImage image_;
};

}  // namespace binpick::eval
