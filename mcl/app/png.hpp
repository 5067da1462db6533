#pragma once
/// A small RGB canvas for pgmcl's pictures (overlay.png, error.png): pixels, lines, discs,
/// arrows and text, written as PNG through stb_image_write.
/// Pixel coordinates: x to the right, y downwards, (0, 0) the top-left pixel's centre.
/// Drawing outside the canvas is clipped silently.

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace pgmcl::app {

struct Rgb {
  std::uint8_t r = 0, g = 0, b = 0;
  friend bool operator==(const Rgb&, const Rgb&) = default;
};

namespace colors {
inline constexpr Rgb kWhite{255, 255, 255};
inline constexpr Rgb kBlack{0, 0, 0};
inline constexpr Rgb kGrey{205, 205, 205};  ///< map_server's "unknown"
inline constexpr Rgb kLightGrey{230, 230, 230};
inline constexpr Rgb kDarkGrey{90, 90, 90};
inline constexpr Rgb kRed{220, 30, 30};
inline constexpr Rgb kGreen{20, 160, 40};
inline constexpr Rgb kBlue{30, 80, 220};
inline constexpr Rgb kOrange{255, 140, 0};
inline constexpr Rgb kPurple{150, 40, 170};
inline constexpr Rgb kPaleGrey{242, 242, 242};
}  // namespace colors

/// A point in pixel coordinates (fractional).
struct PixelPoint {
  double x = 0.0;
  double y = 0.0;
};

class Canvas {
 public:
  /// Throws std::invalid_argument for non-positive or absurd (> 2^28 pixels) sizes.
  Canvas(int width, int height, Rgb background = colors::kWhite);

  [[nodiscard]] int width() const noexcept { return width_; }
  [[nodiscard]] int height() const noexcept { return height_; }
  /// Row-major RGB bytes, top row first.
  [[nodiscard]] const std::vector<std::uint8_t>& data() const noexcept { return rgb_; }

  [[nodiscard]] bool contains(int x, int y) const noexcept {
    return x >= 0 && y >= 0 && x < width_ && y < height_;
  }
  /// Pixel colour; contains(x, y) must hold.
  [[nodiscard]] Rgb at(int x, int y) const noexcept;
  void set(int x, int y, Rgb c) noexcept;
  /// Inclusive rectangle [x0, x1] x [y0, y1], corners in any order.
  void fill_rect(int x0, int y0, int x1, int y1, Rgb c) noexcept;
  /// Filled disc of the given radius (pixels) around a fractional centre.
  void disc(double cx, double cy, double radius, Rgb c) noexcept;
  /// Straight segment of the given width (pixels, >= 1), round caps.
  void line(PixelPoint a, PixelPoint b, Rgb c, double width = 1.0) noexcept;
  void polyline(std::span<const PixelPoint> points, Rgb c, double width = 1.0) noexcept;
  /// A segment drawn as dashes of `dash` pixels separated by `gap` pixels.
  void dashed_line(PixelPoint a, PixelPoint b, Rgb c, double width = 1.0, double dash = 6.0,
                   double gap = 4.0) noexcept;
  /// Circle outline of the given radius and line width (pixels).
  void ring(double cx, double cy, double radius, Rgb c, double width = 1.0) noexcept;
  /// Outline of the inclusive rectangle [x0, x1] x [y0, y1], `width` pixels thick inwards.
  void frame_rect(int x0, int y0, int x1, int y1, Rgb c, int width = 1) noexcept;
  /// Arrow from `tail` of `length` pixels in image direction `angle` (radians, measured
  /// counter-clockwise as seen on screen, i.e. y up), with a head a third of its length.
  void arrow(PixelPoint tail, double angle, double length, Rgb c, double width = 1.0) noexcept;
  /// Copies `src` with its top-left pixel at (x, y), clipped to this canvas.
  void blit(const Canvas& src, int x, int y) noexcept;
  /// ASCII text with its top-left corner at (x, y), glyphs from stb_easy_font
  /// (about 6 x 7 pixels per character at scale 1), magnified by an integer scale.
  void text(int x, int y, std::string_view s, Rgb c, int scale = 1);
  /// Width and height in pixels text() would use.
  [[nodiscard]] static int text_width(std::string_view s, int scale = 1);
  [[nodiscard]] static int text_height(std::string_view s, int scale = 1);

 private:
  int width_ = 0;
  int height_ = 0;
  std::vector<std::uint8_t> rgb_;
};

/// Writes the canvas as an 8-bit RGB PNG. Throws IoError naming the path on failure.
void write_png(const Canvas& canvas, const std::string& path);

}  // namespace pgmcl::app
