#pragma once
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "render/raster.hpp"
#include "woven/volume.hpp"

namespace skein::woven {

/// How a synthesized woven volume is rendered (Zhao 2012 §7, after Zhao 2011): volumetric path tracing of the
/// microflake medium, extinction ρ σ(ω) scaled by `extinction`, single-scattering albedo per yarn colour,
/// Woodcock (delta) tracking for collisions and ratio tracking for the shadow rays to the light.
struct WovenRenderOptions {
  int width = 640, height = 400;
  int samples = 16;               ///< paths per pixel
  int bounces = 8;                ///< scattering events per path at most
  double extinction = 60;         ///< σ_t per unit fibre density [1/mm] (a yarn is optically thick)
  double exponent = 20;           ///< the microflakes' fibre exponent p
  /// Albedo per colour index (linear): by default the CLI's default warp #2a3a7a and weft #d8cfb0, linearized.
  std::vector<Eigen::Vector3f> colors{{0.0189f, 0.0385f, 0.1975f}, {0.6941f, 0.6320f, 0.4423f}};
  Eigen::Vector2d centre{-1, -1};  ///< the fabric point the camera looks at [mm]; negative: the fabric's centre
  double field = 0;               ///< the image's width on the fabric [mm]; 0: the whole fabric
  double tilt = 35;               ///< the view's angle from straight down [degrees]
  double azimuth = -90;           ///< the viewer's direction in the plane [degrees] (-90: from the front, -y)
  Eigen::Vector3d light{-0.4, -0.5, 1.0};  ///< towards the sun
  double sun = 2.5, sky = 0.35, floor = 0.04;  ///< radiances: the sun, the sky, the backdrop behind the cloth
  std::uint64_t seed = 1;
};

struct WovenRenderReport {
  double seconds = 0;
  long paths = 0, lookups = 0;
};

/// Renders the volume (multi-threaded with TBB, deterministic for a seed); throws skein::Error for bad options.
render::Image render_woven(const WovenVolume& volume, const WovenRenderOptions& options, WovenRenderReport* report = nullptr);

}  // namespace skein::woven
