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
#include <cstdint>

#include "objscan/sim/depth_camera.h"

namespace objscan::sim {

class DepthNoiseModel {
 public:
  explicit DepthNoiseModel(const SensorOptions& options);

  // Nguyen's total axial standard deviation at depth z.
  double AxialSigma(double z_m) const;
  // Depth difference of one disparity step at depth z (0 when quantisation is off).
  double QuantisationStep(double z_m) const;
  // Standard deviation of the Gaussian part: sqrt(max(0, sigma_z^2 - q^2 / 12)).
  double GaussianSigma(double z_m) const;
  // Quantises a depth via disparity on the grid of phase `phase` in [0, 1); returns 0 when the
  // rounded disparity is not positive.
  double Quantise(double z_m, double phase) const;
  // Fixed sub-step phase of a pixel in [0, 1) (a hash of its index, no random state).
  static double PixelPhase(std::uint64_t pixel_index);

 private:
  double sigma_base_m_;
  double sigma_quadratic_per_m_;
  double sigma_offset_m_;
  double focal_baseline_px_m_;  // fx * b
  double step_px_;
};

}  // namespace objscan::sim
