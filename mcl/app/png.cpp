#include "png.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>

#include "app_util.hpp"
#include "pgmcl/io/errors.hpp"

// stb's headers are C-style: keep their warnings out of our -Werror build.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wsign-compare"
#pragma GCC diagnostic ignored "-Wold-style-cast"
#include <stb/stb_easy_font.h>
#include <stb/stb_image_write.h>
#pragma GCC diagnostic pop

namespace pgmcl::app {
namespace {

/// stb_easy_font wants a mutable, NUL-terminated, printable-ASCII string.
std::vector<char> easy_font_string(std::string_view s) {
  std::vector<char> buf(s.begin(), s.end());
  for (char& ch : buf) {
    if (ch != '\n' && (ch < 32 || ch > 126)) ch = '?';
  }
  buf.push_back('\0');
  return buf;
}

}  // namespace

Canvas::Canvas(int width, int height, Rgb background) : width_(width), height_(height) {
  if (width <= 0 || height <= 0 ||
      static_cast<long long>(width) * static_cast<long long>(height) > (1LL << 28)) {
    throw std::invalid_argument("Canvas: bad size " + std::to_string(width) + " x " +
                                std::to_string(height));
  }
  rgb_.resize(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 3);
  for (std::size_t i = 0; i < rgb_.size(); i += 3) {
    rgb_[i] = background.r;
    rgb_[i + 1] = background.g;
    rgb_[i + 2] = background.b;
  }
}

Rgb Canvas::at(int x, int y) const noexcept {
  const std::size_t i = (static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) +
                         static_cast<std::size_t>(x)) *
                        3;
  return {rgb_[i], rgb_[i + 1], rgb_[i + 2]};
}

void Canvas::set(int x, int y, Rgb c) noexcept {
  if (!contains(x, y)) return;
  const std::size_t i = (static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) +
                         static_cast<std::size_t>(x)) *
                        3;
  rgb_[i] = c.r;
  rgb_[i + 1] = c.g;
  rgb_[i + 2] = c.b;
}

void Canvas::fill_rect(int x0, int y0, int x1, int y1, Rgb c) noexcept {
  if (x0 > x1) std::swap(x0, x1);
  if (y0 > y1) std::swap(y0, y1);
  x0 = std::max(x0, 0);
  y0 = std::max(y0, 0);
  x1 = std::min(x1, width_ - 1);
  y1 = std::min(y1, height_ - 1);
  for (int y = y0; y <= y1; ++y)
    for (int x = x0; x <= x1; ++x) set(x, y, c);
}

void Canvas::disc(double cx, double cy, double radius, Rgb c) noexcept {
  if (!std::isfinite(cx) || !std::isfinite(cy) || !(radius > 0.0)) return;
  const double r = std::max(radius, 0.5);
  if (cx + r < -1.0 || cy + r < -1.0 || cx - r > width_ || cy - r > height_) return;
  const double lo_x = std::max(std::floor(cx - r), -1.0);
  const double hi_x = std::min(std::ceil(cx + r), static_cast<double>(width_));
  const double lo_y = std::max(std::floor(cy - r), -1.0);
  const double hi_y = std::min(std::ceil(cy + r), static_cast<double>(height_));
  for (int y = static_cast<int>(lo_y); y <= static_cast<int>(hi_y); ++y) {
    for (int x = static_cast<int>(lo_x); x <= static_cast<int>(hi_x); ++x) {
      const double dx = x - cx, dy = y - cy;
      if (dx * dx + dy * dy <= r * r) set(x, y, c);
    }
  }
}

void Canvas::line(PixelPoint a, PixelPoint b, Rgb c, double width) noexcept {
  if (!std::isfinite(a.x) || !std::isfinite(a.y) || !std::isfinite(b.x) || !std::isfinite(b.y))
    return;
  const double len = std::hypot(b.x - a.x, b.y - a.y);
  // Far off-canvas segments (a runaway estimate) are not worth walking pixel by pixel.
  const double reach = 4.0 * (width_ + height_);
  if (len > 64.0 * reach) return;
  const double half = std::max(width, 1.0) / 2.0;
  const int steps = std::max(1, static_cast<int>(std::ceil(len / 0.5)));
  for (int i = 0; i <= steps; ++i) {
    const double t = static_cast<double>(i) / steps;
    const double x = a.x + t * (b.x - a.x), y = a.y + t * (b.y - a.y);
    if (x < -reach || y < -reach || x > reach || y > reach) continue;
    if (half <= 0.5) {
      set(static_cast<int>(std::lround(x)), static_cast<int>(std::lround(y)), c);
    } else {
      disc(x, y, half, c);
    }
  }
}

void Canvas::polyline(std::span<const PixelPoint> points, Rgb c, double width) noexcept {
  for (std::size_t i = 1; i < points.size(); ++i) line(points[i - 1], points[i], c, width);
  if (points.size() == 1) line(points[0], points[0], c, width);
}

void Canvas::arrow(PixelPoint tail, double angle, double length, Rgb c, double width) noexcept {
  // Screen y points down, so a counter-clockwise angle has a negative y component.
  const PixelPoint tip{tail.x + length * std::cos(angle), tail.y - length * std::sin(angle)};
  line(tail, tip, c, width);
  const double head = length / 3.0, spread = 2.6;  // ~150 degrees back from the shaft
  for (const double s : {spread, -spread}) {
    const PixelPoint p{tip.x + head * std::cos(angle + s), tip.y - head * std::sin(angle + s)};
    line(tip, p, c, width);
  }
}

void Canvas::blit(const Canvas& src, int x, int y) noexcept {
  for (int sy = 0; sy < src.height(); ++sy)
    for (int sx = 0; sx < src.width(); ++sx) set(x + sx, y + sy, src.at(sx, sy));
}

void Canvas::text(int x, int y, std::string_view s, Rgb c, int scale) {
  if (s.empty()) return;
  scale = std::max(scale, 1);
  std::vector<char> str = easy_font_string(s);
  std::vector<char> vbuf(str.size() * 300 + 1024);
  const int quads = stb_easy_font_print(0.0f, 0.0f, str.data(), nullptr, vbuf.data(),
                                        static_cast<int>(vbuf.size()));
  // Each quad is four vertices of {float x, y, z; uint8 rgba[4]}: an axis-aligned box.
  for (int q = 0; q < quads; ++q) {
    float xs[4], ys[4];
    for (int v = 0; v < 4; ++v) {
      const char* p = vbuf.data() + (static_cast<std::size_t>(q) * 4 + v) * 16;
      std::memcpy(&xs[v], p, sizeof(float));
      std::memcpy(&ys[v], p + 4, sizeof(float));
    }
    const int qx0 = static_cast<int>(std::lround(*std::min_element(xs, xs + 4)));
    const int qx1 = static_cast<int>(std::lround(*std::max_element(xs, xs + 4)));
    const int qy0 = static_cast<int>(std::lround(*std::min_element(ys, ys + 4)));
    const int qy1 = static_cast<int>(std::lround(*std::max_element(ys, ys + 4)));
    if (qx1 <= qx0 || qy1 <= qy0) continue;
    fill_rect(x + qx0 * scale, y + qy0 * scale, x + qx1 * scale - 1, y + qy1 * scale - 1, c);
  }
}

int Canvas::text_width(std::string_view s, int scale) {
  std::vector<char> str = easy_font_string(s);
  return stb_easy_font_width(str.data()) * std::max(scale, 1);
}

int Canvas::text_height(std::string_view s, int scale) {
  std::vector<char> str = easy_font_string(s);
  return stb_easy_font_height(str.data()) * std::max(scale, 1);
}

void write_png(const Canvas& canvas, const std::string& path) {
  // Encoded in memory, then written and checked here: stbi_write_png ignores fwrite's and
  // fclose's results, so a full disk would go unnoticed.
  std::string bytes;
  const auto append = [](void* ctx, void* data, int size) {
    static_cast<std::string*>(ctx)->append(static_cast<const char*>(data),
                                           static_cast<std::size_t>(size));
  };
  const int ok = stbi_write_png_to_func(append, &bytes, canvas.width(), canvas.height(), 3,
                                        canvas.data().data(), canvas.width() * 3);
  if (ok == 0) throw io::IoError(path + ": cannot encode PNG");
  write_text_file(path, bytes);
}

}  // namespace pgmcl::app
