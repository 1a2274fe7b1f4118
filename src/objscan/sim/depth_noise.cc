#include "objscan/sim/depth_noise.h"

#include <algorithm>
#include <cmath>

#include "objscan/common/rng.h"

namespace objscan::sim {

DepthNoiseModel::DepthNoiseModel(const SensorOptions& options)
    : sigma_base_m_(options.noise_sigma_base_m),
      sigma_quadratic_per_m_(options.noise_sigma_quadratic_per_m),
      sigma_offset_m_(options.noise_sigma_offset_m),
      focal_baseline_px_m_(options.fx_px * options.baseline_m),
      step_px_(options.disparity_step_px) {}

double DepthNoiseModel::AxialSigma(double z_m) const {
  const double dz = z_m - sigma_offset_m_;
  return sigma_base_m_ + sigma_quadratic_per_m_ * dz * dz;
}

double DepthNoiseModel::QuantisationStep(double z_m) const {
  return step_px_ > 0.0 ? z_m * z_m * step_px_ / focal_baseline_px_m_ : 0.0;
}

double DepthNoiseModel::GaussianSigma(double z_m) const {
  const double sigma = AxialSigma(z_m);
  const double q = QuantisationStep(z_m);
  return std::sqrt(std::max(0.0, sigma * sigma - q * q / 12.0));
}

double DepthNoiseModel::Quantise(double z_m, double phase) const {
  if (step_px_ <= 0.0) return z_m;
  if (z_m <= 0.0) return 0.0;
  const double disparity_px = focal_baseline_px_m_ / z_m;
  const double quantised_px = (std::round(disparity_px / step_px_ - phase) + phase) * step_px_;
  return quantised_px > 0.0 ? focal_baseline_px_m_ / quantised_px : 0.0;
}

double DepthNoiseModel::PixelPhase(std::uint64_t pixel_index) {
  return static_cast<double>(MixSeed(pixel_index ^ 0xD1B54A32D192ED03ull) >> 11) * 0x1.0p-53;
}

}  // namespace objscan::sim
