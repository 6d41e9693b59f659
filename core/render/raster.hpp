#pragma once
#include <cstdint>
#include <filesystem>
#include <vector>

#include <Eigen/Core>

namespace skein::render {

/// An 8-bit RGB picture, rows top to bottom.
struct Image {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgb;
  Image(int w, int h) : width(w), height(h), rgb(static_cast<size_t>(w) * h * 3, 255) {}
};

/// A flat-coloured polygon in 3D (convex or mildly non-convex; drawn as a fan from its first corner).
struct Polygon {
  std::vector<Eigen::Vector3d> points;
  Eigen::Vector3f color{0.8f, 0.8f, 0.8f};  ///< linear 0..1
};

/// How to look at the model: orthographic views side by side, one panel per direction, all at one scale.
struct View {
  std::vector<Eigen::Vector3d> directions{{0.35, -0.3, -1.0}, {-1.0, -0.3, 0.8}};  ///< from the eye into the scene: front, back-side
  Eigen::Vector3d up{0, 1, 0};
  int panel = 900;          ///< pixels per panel side
  bool outlines = true;     ///< dark polygon edges where polygons are large enough on screen to show them
};

/// A linear intensity (0 to 1; clamped) as a display byte, gamma 2.2, and a display byte back to linear.
std::uint8_t display_byte(float linear);
float linear_of_byte(unsigned byte);

/// Software rasterizer: z-buffered, head-light Lambert shading, 2x supersampled. No GPU or display needed.
Image draw(const std::vector<Polygon>& polygons, const View& view);

/// Writes a PNG (atomically); throws skein::Error naming the path on failure.
void write_png(const Image& image, const std::filesystem::path& path);
/// Reads a PNG written by write_png (for tests and picture checks); throws skein::Error.
Image read_png(const std::filesystem::path& path);

}  // namespace skein::render
