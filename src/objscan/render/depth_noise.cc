#include "objscan/render/depth_noise.h"

namespace objscan::render {

DepthNoiseModel::DepthNoiseModel(const SensorOptions& options)
    : sigma_base_m_(options.noise_sigma_base_m),
      sigma_quadratic_per_m_(options.noise_sigma_quadratic_per_m),
      sigma_offset_m_(options.noise_sigma_offset_m),
      focal_baseline_px_m_(options.fx_px * options.baseline_m),
      step_px_(options.disparity_step_px),
      inverse_step_(options.disparity_step_px > 0.0 ? 1.0 / options.disparity_step_px : 0.0) {}

double DepthNoiseModel::PixelPhase(std::uint64_t pixel_index) {
  return static_cast<double>(MixSeed(pixel_index ^ 0xD1B54A32D192ED03ull) >> 11) * 0x1.0p-53;
}

}  // namespace objscan::render
