#include "host/eval/report/raster.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace binpick::eval {
namespace {

// 5 x 7 bitmaps of 0-9, one row a byte, bit 4 = leftmost column.
constexpr std::array<std::array<std::uint8_t, 7>, 10> kDigits{{
    {0x0e, 0x11, 0x13, 0x15, 0x19, 0x11, 0x0e}, {0x04, 0x0c, 0x04, 0x04, 0x04, 0x04, 0x0e},
    {0x0e, 0x11, 0x01, 0x02, 0x04, 0x08, 0x1f}, {0x1f, 0x02, 0x04, 0x02, 0x01, 0x11, 0x0e},
    {0x02, 0x06, 0x0a, 0x12, 0x1f, 0x02, 0x02}, {0x1f, 0x10, 0x1e, 0x01, 0x01, 0x11, 0x0e},
    {0x06, 0x08, 0x10, 0x1e, 0x11, 0x11, 0x0e}, {0x1f, 0x01, 0x02, 0x04, 0x08, 0x08, 0x08},
    {0x0e, 0x11, 0x11, 0x0e, 0x11, 0x11, 0x0e}, {0x0e, 0x11, 0x11, 0x0f, 0x01, 0x02, 0x0c}}};

}  // namespace

Canvas::Canvas(std::uint32_t width, std::uint32_t height, Rgb fill) {
  image_.width = width, image_.height = height;
  image_.pixels.resize(std::size_t(width) * height * 3);
  for (std::size_t i = 0; i < image_.pixels.size(); i += 3)
    std::copy(fill.begin(), fill.end(), image_.pixels.begin() + std::ptrdiff_t(i));
}

Canvas Canvas::from_gray(const GrayImage<std::uint8_t>& gray, double brightness) {
  Canvas c(gray.width, gray.height);
  for (std::size_t i = 0; i < gray.pixels.size(); ++i) {
    const auto v = std::uint8_t(std::clamp(gray.pixels[i] * brightness, 0.0, 255.0));
    c.image_.pixels[3 * i] = c.image_.pixels[3 * i + 1] = c.image_.pixels[3 * i + 2] = v;
  }
  return c;
}

Rgb Canvas::get(int x, int y) const {
  if (x < 0 || y < 0 || x >= int(width()) || y >= int(height())) return {0, 0, 0};
  const std::size_t i = 3 * (std::size_t(y) * width() + std::size_t(x));
  return {image_.pixels[i], image_.pixels[i + 1], image_.pixels[i + 2]};
}

void Canvas::blend(int x, int y, Rgb c, double alpha) {
  if (x < 0 || y < 0 || x >= int(width()) || y >= int(height())) return;
  const std::size_t i = 3 * (std::size_t(y) * width() + std::size_t(x));
  for (int k = 0; k < 3; ++k) {
    auto& p = image_.pixels[i + std::size_t(k)];
    p = std::uint8_t(std::lround(p * (1 - alpha) + c[std::size_t(k)] * alpha));
  }
}

void Canvas::disc(double cx, double cy, double radius, Rgb c, double alpha) {
  const int x0 = int(std::floor(cx - radius)), x1 = int(std::ceil(cx + radius));
  const int y0 = int(std::floor(cy - radius)), y1 = int(std::ceil(cy + radius));
  for (int y = y0; y <= y1; ++y)
    for (int x = x0; x <= x1; ++x)
      if ((x - cx) * (x - cx) + (y - cy) * (y - cy) <= radius * radius) blend(x, y, c, alpha);
}

void Canvas::ring(double cx, double cy, double radius, double thickness, Rgb c) {
  const double outer = radius + thickness / 2, inner = std::max(0.0, radius - thickness / 2);
  const int x0 = int(std::floor(cx - outer)), x1 = int(std::ceil(cx + outer));
  const int y0 = int(std::floor(cy - outer)), y1 = int(std::ceil(cy + outer));
  for (int y = y0; y <= y1; ++y)
    for (int x = x0; x <= x1; ++x) {
      const double d2 = (x - cx) * (x - cx) + (y - cy) * (y - cy);
      if (d2 <= outer * outer && d2 >= inner * inner) blend(x, y, c);
    }
}

void Canvas::cross(double cx, double cy, int half, int thickness, Rgb c) {
  const int x = int(std::lround(cx)), y = int(std::lround(cy));
  for (int d = -half; d <= half; ++d)
    for (int t = -(thickness / 2); t <= thickness / 2; ++t) blend(x + d, y + t, c), blend(x + t, y + d, c);
}

void Canvas::line(double x0, double y0, double x1, double y1, double thickness, Rgb c, double alpha) {
  // Every pixel whose centre lies within half the thickness of the segment, once.
  const double r = std::max(0.5, thickness / 2);
  const int xa = int(std::floor(std::min(x0, x1) - r)), xb = int(std::ceil(std::max(x0, x1) + r));
  const int ya = int(std::floor(std::min(y0, y1) - r)), yb = int(std::ceil(std::max(y0, y1) + r));
  const double dx = x1 - x0, dy = y1 - y0, length2 = dx * dx + dy * dy;
  for (int y = std::max(0, ya); y <= std::min(int(height()) - 1, yb); ++y)
    for (int x = std::max(0, xa); x <= std::min(int(width()) - 1, xb); ++x) {
      const double s = length2 > 0 ? std::clamp(((x - x0) * dx + (y - y0) * dy) / length2, 0.0, 1.0) : 0.0;
      const double ex = x - (x0 + s * dx), ey = y - (y0 + s * dy);
      if (ex * ex + ey * ey <= r * r) blend(x, y, c, alpha);
    }
}

void Canvas::polygon(const std::vector<Eigen::Vector2d>& v, Rgb c, double alpha) {
  if (v.size() < 3) return;
  double y0 = v[0].y(), y1 = y0;
  for (const auto& p : v) y0 = std::min(y0, p.y()), y1 = std::max(y1, p.y());
  // Scanlines through the pixel centres: the crossings of each edge, filled between pairs.
  for (int y = std::max(0, int(std::floor(y0))); y <= std::min(int(height()) - 1, int(std::ceil(y1))); ++y) {
    std::vector<double> xs;
    for (std::size_t i = 0; i < v.size(); ++i) {
      const Eigen::Vector2d& a = v[i];
      const Eigen::Vector2d& b = v[(i + 1) % v.size()];
      if ((a.y() <= y) != (b.y() <= y)) xs.push_back(a.x() + (y - a.y()) * (b.x() - a.x()) / (b.y() - a.y()));
    }
    std::sort(xs.begin(), xs.end());
    for (std::size_t k = 0; k + 1 < xs.size(); k += 2)
      for (int x = std::max(0, int(std::ceil(xs[k]))); x <= std::min(int(width()) - 1, int(std::floor(xs[k + 1]))); ++x)
        blend(x, y, c, alpha);
  }
}

void Canvas::text(int x, int y, std::string_view digits, int scale, Rgb c) {
  // Outline first (every lit cell grown by one scaled pixel in black), then the glyphs.
  for (int pass = 0; pass < 2; ++pass)
    for (std::size_t n = 0; n < digits.size(); ++n) {
      if (digits[n] < '0' || digits[n] > '9') continue;
      const auto& glyph = kDigits[std::size_t(digits[n] - '0')];
      const int gx = x + int(n) * 6 * scale;
      for (int row = 0; row < 7; ++row)
        for (int col = 0; col < 5; ++col) {
          if (!(glyph[std::size_t(row)] & (0x10 >> col))) continue;
          const int px = gx + col * scale, py = y + row * scale, grow = pass == 0 ? scale / 2 + 1 : 0;
          for (int yy = py - grow; yy < py + scale + grow; ++yy)
            for (int xx = px - grow; xx < px + scale + grow; ++xx)
              blend(xx, yy, pass == 0 ? Rgb{0, 0, 0} : c);
        }
    }
}

}  // namespace binpick::eval
