#pragma once
// Kinect-style depth noise (the model behind SensorOptions::noise).
//
// Nguyen et al. (2012) measured the total axial standard deviation of Kinect depth,
// sigma_z(z) = base + quadratic * (z - offset)^2, and that total already contains the disparity
// quantisation. We simulate both parts and split the variance between them:
//  - quantisation: depth -> disparity d = fx * b / z, rounded to a grid of disparity_step_px whose
//    sub-step phase is fixed per pixel (as the speckle pattern's sub-pixel phase differs from pixel
//    to pixel). Over pixels the rounding error is uniform, so it adds q(z)^2 / 12 of variance, with
//    q(z) = z^2 * step / (fx * b) the depth step at z (0.029 m at 3 m, larger than sigma_z itself);
//  - a Gaussian with the remaining variance sigma_z^2 - q^2 / 12 (always >= 0 in the 0.5-4 m range
//    for the default parameters), added to z before quantising.
// The depth of a fronto-parallel plane then scatters with standard deviation sigma_z over the image,
// as Nguyen measured, while each pixel still shows the sensor's discrete depth levels.
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "objscan/common/rng.h"
#include "objscan/render/depth_camera.h"
#include "objscan/render/normal_sampler.h"

namespace objscan::render {

class DepthNoiseModel {
 public:
  explicit DepthNoiseModel(const SensorOptions& options);

  // Nguyen's total axial standard deviation at depth z.
  double AxialSigma(double z_m) const {
    const double dz = z_m - sigma_offset_m_;
    return sigma_base_m_ + sigma_quadratic_per_m_ * dz * dz;
  }
  // Depth difference of one disparity step at depth z (0 when quantisation is off).
  double QuantisationStep(double z_m) const { return z_m * z_m * step_px_ / focal_baseline_px_m_; }
  // Standard deviation of the Gaussian part: sqrt(max(0, sigma_z^2 - q^2 / 12)).
  double GaussianSigma(double z_m) const {
    const double sigma = AxialSigma(z_m);
    const double q = QuantisationStep(z_m);
    return std::sqrt(std::max(0.0, sigma * sigma - q * q / 12.0));
  }
  // Quantises a depth via disparity on the grid of phase `phase` in [0, 1); returns 0 when the depth
  // is not positive.
  double Quantise(double z_m, double phase) const {
    if (!(z_m > 0.0)) return 0.0;
    if (step_px_ <= 0.0) return z_m;
    // Disparity in steps is positive, so truncating x + 0.5 rounds (without a libm call per pixel).
    const double steps = focal_baseline_px_m_ / z_m * inverse_step_ - phase;
    const double rounded = static_cast<double>(static_cast<std::int64_t>(steps + 0.5)) + phase;
    return rounded > 0.0 ? focal_baseline_px_m_ / (rounded * step_px_) : 0.0;
  }
  // A measurement of true depth z at a pixel of grid phase `phase`: Gaussian part, then quantisation
  // (0 when the result is not a positive depth).
  double Measure(double z_m, double phase, Rng& rng) const {
    return Quantise(z_m + GaussianSigma(z_m) * normal_(rng), phase);
  }
  // Fixed sub-step phase of a pixel in [0, 1) (a hash of its index, no random state).
  static double PixelPhase(std::uint64_t pixel_index);

 private:
  double sigma_base_m_;
  double sigma_quadratic_per_m_;
  double sigma_offset_m_;
  double focal_baseline_px_m_;  // fx * b
  double step_px_;
  double inverse_step_;  // 1 / step_px_ (0 when quantisation is off)
  NormalSampler normal_;
};

}  // namespace objscan::render
