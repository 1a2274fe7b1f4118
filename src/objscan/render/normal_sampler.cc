#include "objscan/render/normal_sampler.h"

#include <cmath>

namespace objscan::render {
namespace {

// Right edge of the base layer and the common area of every layer for 128 layers.
constexpr double kTailStart = 3.442619855899;
constexpr double kLayerArea = 9.91256303526217e-3;

double Density(double x) { return std::exp(-0.5 * x * x); }

}  // namespace

NormalSampler::NormalSampler() {
  x_[0] = kLayerArea / Density(kTailStart);
  x_[1] = kTailStart;
  for (int i = 1; i < kLayers - 1; ++i) {
    x_[i + 1] = std::sqrt(-2.0 * std::log(Density(x_[i]) + kLayerArea / x_[i]));
  }
  x_[kLayers] = 0.0;
  for (int i = 0; i <= kLayers; ++i) f_[i] = Density(x_[i]);
}

double NormalSampler::operator()(Rng& rng) const {
  for (;;) {
    const std::uint64_t bits = rng();
    const int layer = static_cast<int>(bits & (kLayers - 1));
    const double sign = (bits & kLayers) ? -1.0 : 1.0;
    const double u = static_cast<double>(bits >> 11) * 0x1.0p-53;
    const double x = u * x_[layer];
    // Inside the part of the layer that lies wholly under the curve: the common, fast case.
    if (x < x_[layer + 1]) return sign * x;
    if (layer == 0) {
      // Beyond the base layer's rectangle: the tail x > kTailStart (Marsaglia's exponential method).
      for (;;) {
        double u1 = rng.Uniform01(), u2 = rng.Uniform01();
        while (u1 <= 0.0) u1 = rng.Uniform01();
        while (u2 <= 0.0) u2 = rng.Uniform01();
        const double a = -std::log(u1) / kTailStart;
        const double b = -std::log(u2);
        if (2.0 * b > a * a) return sign * (kTailStart + a);
      }
    }
    // The wedge between the layer's inner rectangle and the curve.
    const double y = f_[layer] + rng.Uniform01() * (f_[layer + 1] - f_[layer]);
    if (y < Density(x)) return sign * x;
  }
}

}  // namespace objscan::render
