#include "woven/woven_render.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <numbers>
#include <random>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "common/error.hpp"
#include "woven/microflake.hpp"

namespace skein::woven {

namespace {

/// Where a ray meets the volume's box: [t0, t1], empty when t1 <= t0.
std::pair<double, double> box_hit(const Eigen::Vector3d& o, const Eigen::Vector3d& d, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  double t0 = 0, t1 = 1e30;
  for (int k = 0; k < 3; ++k) {
    if (std::abs(d[k]) < 1e-15) {
      if (o[k] < lo[k] || o[k] > hi[k]) return {1, 0};
      continue;
    }
    double a = (lo[k] - o[k]) / d[k], b = (hi[k] - o[k]) / d[k];
    if (a > b) std::swap(a, b);
    t0 = std::max(t0, a), t1 = std::min(t1, b);
  }
  return {t0, t1};
}

struct Tracer {
  const WovenVolume& volume;
  const WovenRenderOptions& o;
  FiberMicroflake flakes;
  Eigen::Vector3d lo, hi, sun;
  double majorant;

  double extinction(const WovenVolume::Sample& s, const Eigen::Vector3d& d) const {
    return s.density <= 0 ? 0.0 : o.extinction * s.density * flakes.sigma(d, s.direction.cast<double>().normalized());
  }

  /// Ratio tracking: the transmittance from p along d to the box's edge.
  double transmittance(const Eigen::Vector3d& p, const Eigen::Vector3d& d, std::mt19937_64& random, long& lookups) const {
    const auto [t0, t1] = box_hit(p, d, lo, hi);
    std::uniform_real_distribution<double> unit(0, 1);
    double t = std::max(0.0, t0), T = 1;
    while (T > 1e-3) {
      t -= std::log(1 - unit(random)) / majorant;
      if (t >= t1) break;
      ++lookups;
      T *= 1 - extinction(volume.at(p + t * d), d) / majorant;
    }
    return T;
  }

  Eigen::Vector3d radiance(Eigen::Vector3d p, Eigen::Vector3d d, std::mt19937_64& random, long& lookups) const {
    std::uniform_real_distribution<double> unit(0, 1);
    Eigen::Vector3d throughput = Eigen::Vector3d::Ones(), sum = Eigen::Vector3d::Zero();
    for (int bounce = 0;; ) {
      const auto [t0, t1] = box_hit(p, d, lo, hi);
      double t = std::max(0.0, t0);
      bool scattered = false;
      if (t1 > t0)
        while (true) {
          t -= std::log(1 - unit(random)) / majorant;
          if (t >= t1) break;
          const Eigen::Vector3d q = p + t * d;
          ++lookups;
          const auto s = volume.at(q);
          if (unit(random) * majorant >= extinction(s, d)) continue;  // a null collision
          // A real collision: the sun by next-event estimation, then a new direction from the phase function.
          const Eigen::Vector3d f = s.direction.cast<double>().normalized();
          const Eigen::Vector3d albedo = o.colors[std::clamp<int>(s.color, 0, static_cast<int>(o.colors.size()) - 1)].cast<double>();
          const double lit = flakes.phase(-d, sun, f) * transmittance(q, sun, random, lookups);
          sum += throughput.cwiseProduct(albedo) * (o.sun * lit);
          throughput = throughput.cwiseProduct(albedo);
          d = flakes.sample(-d, f, random);
          p = q;
          scattered = true;
          break;
        }
      if (!scattered) return sum + throughput * (d.z() > 0 ? o.sky : o.floor);
      if (++bounce > o.bounces) return sum;
    }
  }
};

}  // namespace

render::Image render_woven(const WovenVolume& volume, const WovenRenderOptions& o, WovenRenderReport* report) {
  if (o.width < 8 || o.height < 8 || o.width > 8192 || o.height > 8192) throw Error("", "render", "the picture must be 8 to 8192 pixels each way");
  if (o.samples < 1 || o.samples > 65536 || o.bounces < 1 || o.bounces > 256) throw Error("", "render", "needs 1 to 65536 samples and 1 to 256 bounces");
  if (!(o.extinction > 0) || o.colors.empty() || !(o.tilt >= 0 && o.tilt < 89)) throw Error("", "render", "needs a positive extinction, colours and a tilt of 0 to 89 degrees");
  const auto start = std::chrono::steady_clock::now();
  const Eigen::Vector3d size = volume.size();
  Tracer tracer{volume, o, FiberMicroflake(o.exponent), {0, 0, volume.z_low}, {size.x(), size.y(), volume.z_high}, o.light.normalized(), 0};
  tracer.majorant = o.extinction * tracer.flakes.sigma_max();
  const double tilt = o.tilt * std::numbers::pi / 180, azimuth = o.azimuth * std::numbers::pi / 180;
  const Eigen::Vector3d towards_eye(std::sin(tilt) * std::cos(azimuth), std::sin(tilt) * std::sin(azimuth), std::cos(tilt));
  Eigen::Vector3d up = Eigen::Vector3d::UnitY() - Eigen::Vector3d::UnitY().dot(towards_eye) * towards_eye;
  if (up.norm() < 1e-6) up = Eigen::Vector3d::UnitX();
  up.normalize();
  const Eigen::Vector3d right = up.cross(towards_eye);
  const Eigen::Vector2d centre = o.centre.x() >= 0 ? o.centre : Eigen::Vector2d(0.5 * size.x(), 0.5 * size.y());
  const double field = o.field > 0 ? o.field : std::max(size.x(), size.y() * o.width / o.height);
  const double pixel = field / o.width;
  const Eigen::Vector3d target(centre.x(), centre.y(), 0.5 * (volume.z_low + volume.z_high));
  const double away = 10 * (size.norm() + 1);
  std::vector<Eigen::Vector3f> light(static_cast<size_t>(o.width) * o.height);
  std::atomic<long> lookups = 0;
  tbb::parallel_for(tbb::blocked_range<int>(0, o.height), [&](const tbb::blocked_range<int>& rows) {
    long mine = 0;
    for (int y = rows.begin(); y < rows.end(); ++y) {
      std::mt19937_64 random(o.seed * 0x9E3779B97F4A7C15ull + static_cast<std::uint64_t>(y));
      std::uniform_real_distribution<double> unit(0, 1);
      for (int x = 0; x < o.width; ++x) {
        Eigen::Vector3d sum = Eigen::Vector3d::Zero();
        for (int s = 0; s < o.samples; ++s) {
          const double u = (x + unit(random) - 0.5 * o.width) * pixel, v = (0.5 * o.height - y - unit(random)) * pixel;
          sum += tracer.radiance(target + u * right + v * up + away * towards_eye, -towards_eye, random, mine);
        }
        light[static_cast<size_t>(y) * o.width + x] = (sum / o.samples).cast<float>();
      }
    }
    lookups += mine;
  });
  render::Image image(o.width, o.height);
  for (size_t k = 0; k < light.size(); ++k)
    for (int c = 0; c < 3; ++c) image.rgb[3 * k + c] = render::display_byte(light[k][c]);
  if (report) {
    report->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    report->paths = static_cast<long>(o.width) * o.height * o.samples;
    report->lookups = lookups;
  }
  return image;
}

}  // namespace skein::woven
