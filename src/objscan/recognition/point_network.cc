#include "objscan/recognition/point_network.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "objscan/common/error.h"
#include "objscan/common/parallel_for.h"
#include "objscan/common/rng.h"

namespace objscan::recognition {

void PointNetworkOptions::Validate() const {
  config::Require(point_features >= 1 && point_features <= 1024, "recognition.classifier.network.point_features",
                  "must be from 1 to 1024");
  config::Require(pooled_features >= 1 && pooled_features <= 1024, "recognition.classifier.network.pooled_features",
                  "must be from 1 to 1024");
  config::Require(head_features >= 1 && head_features <= 1024, "recognition.classifier.network.head_features",
                  "must be from 1 to 1024");
  config::Require(max_points >= 8, "recognition.classifier.network.max_points", "must be at least 8");
  config::Require(epochs >= 1, "recognition.classifier.network.epochs", "must be at least 1");
  config::Require(batch_size >= 1, "recognition.classifier.network.batch_size", "must be at least 1");
  config::RequirePositive("recognition.classifier.network.learning_rate", learning_rate);
  config::RequireNonNegative("recognition.classifier.network.weight_decay", weight_decay);
  config::RequireInRange("recognition.classifier.network.keep_min_fraction", keep_min_fraction, 0.05, 1.0);
  config::RequireInRange("recognition.classifier.network.yaw_jitter_deg", yaw_jitter_deg, 0.0, 180.0);
  config::RequireInRange("recognition.classifier.network.scale_jitter", scale_jitter, 0.0, 0.5);
  config::Require(threads >= 0, "recognition.classifier.network.threads", "must be >= 0");
}

EncodedPointSet EncodePointSet(const std::vector<Eigen::Vector3f>& points, const std::vector<Eigen::Vector3f>& normals,
                               double floor_z_m, int max_points) {
  EncodedPointSet out;
  std::vector<int> finite;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (points[i].allFinite() && (i >= normals.size() || normals[i].allFinite())) finite.push_back(static_cast<int>(i));
  }
  const std::size_t n = finite.size();
  if (n == 0 || max_points < 1) return out;
  std::vector<int> chosen;
  if (n <= static_cast<std::size_t>(max_points)) {
    chosen = finite;
  } else {
    for (int i = 0; i < max_points; ++i) chosen.push_back(finite[static_cast<std::size_t>(i) * n / max_points]);
  }
  double cx = 0.0, cy = 0.0, min_z = std::numeric_limits<double>::infinity();
  for (int i : chosen) {
    cx += points[static_cast<std::size_t>(i)].x();
    cy += points[static_cast<std::size_t>(i)].y();
    min_z = std::min(min_z, static_cast<double>(points[static_cast<std::size_t>(i)].z()));
  }
  cx /= static_cast<double>(chosen.size());
  cy /= static_cast<double>(chosen.size());
  double sxx = 0.0, sxy = 0.0, syy = 0.0;
  for (int i : chosen) {
    const double dx = points[static_cast<std::size_t>(i)].x() - cx, dy = points[static_cast<std::size_t>(i)].y() - cy;
    sxx += dx * dx;
    sxy += dx * dy;
    syy += dy * dy;
  }
  // The principal horizontal axis at angle theta becomes X.
  const double theta = 0.5 * std::atan2(2.0 * sxy, sxx - syy);
  const double c = std::cos(theta), s = std::sin(theta);
  out.channels.reserve(chosen.size() * kPointChannels);
  for (int i : chosen) {
    const Eigen::Vector3f& p = points[static_cast<std::size_t>(i)];
    const double dx = p.x() - cx, dy = p.y() - cy;
    out.channels.push_back(static_cast<float>(c * dx + s * dy));
    out.channels.push_back(static_cast<float>(-s * dx + c * dy));
    out.channels.push_back(static_cast<float>(p.z() - floor_z_m));
    out.channels.push_back(static_cast<float>(p.z() - min_z));
    if (static_cast<std::size_t>(i) < normals.size()) {
      const Eigen::Vector3f& nrm = normals[static_cast<std::size_t>(i)];
      out.channels.push_back(static_cast<float>(std::abs(c * nrm.x() + s * nrm.y())));
      out.channels.push_back(static_cast<float>(std::abs(-s * nrm.x() + c * nrm.y())));
      out.channels.push_back(std::abs(nrm.z()));
    } else {
      out.channels.insert(out.channels.end(), {0.f, 0.f, 0.f});
    }
  }
  return out;
}

// Where each block of weights lies in the flat parameter vector: W1 (channels x point_features), b1,
// W2 (point_features x pooled), b2, W3 ((pooled + globals) x head), b3, W4 (head x classes), b4.
struct PointNetwork::Layout {
  int c = kPointChannels, h1 = 0, h2 = 0, f = 0, h3 = 0, k = 0;
  std::size_t w1 = 0, b1 = 0, w2 = 0, b2 = 0, w3 = 0, b3 = 0, w4 = 0, b4 = 0, size = 0;
  Layout(int point_features, int pooled, int globals, int head, int classes)
      : h1(point_features), h2(pooled), f(globals), h3(head), k(classes) {
    std::size_t at = 0;
    auto take = [&at](std::size_t n) {
      const std::size_t start = at;
      at += n;
      return start;
    };
    w1 = take(static_cast<std::size_t>(c) * h1);
    b1 = take(static_cast<std::size_t>(h1));
    w2 = take(static_cast<std::size_t>(h1) * h2);
    b2 = take(static_cast<std::size_t>(h2));
    w3 = take(static_cast<std::size_t>(h2 + f) * h3);
    b3 = take(static_cast<std::size_t>(h3));
    w4 = take(static_cast<std::size_t>(h3) * k);
    b4 = take(static_cast<std::size_t>(k));
    size = at;
  }
};

PointNetwork::Layout PointNetwork::layout() const {
  return Layout(point_features_, pooled_features_, num_global_features_, head_features_, num_classes_);
}

PointNetwork PointNetwork::Initialized(int num_classes, int num_global_features, const PointNetworkOptions& options) {
  options.Validate();
  PointNetwork net;
  net.num_classes_ = num_classes;
  net.num_global_features_ = num_global_features;
  net.point_features_ = options.point_features;
  net.pooled_features_ = options.pooled_features;
  net.head_features_ = options.head_features;
  net.max_points_ = options.max_points;
  const Layout l = net.layout();
  net.params_.assign(l.size, 0.f);
  net.global_mean_.assign(static_cast<std::size_t>(num_global_features), 0.f);
  net.global_inverse_std_.assign(static_cast<std::size_t>(num_global_features), 1.f);
  Rng rng(DeriveSeed(options.seed, 0x9e7));
  // He-uniform for the layers that feed a ReLU, Glorot-uniform for the logits.
  auto fill = [&](std::size_t at, std::size_t count, double limit) {
    for (std::size_t i = 0; i < count; ++i) net.params_[at + i] = static_cast<float>(rng.Uniform(-limit, limit));
  };
  fill(l.w1, static_cast<std::size_t>(l.c) * l.h1, std::sqrt(6.0 / l.c));
  fill(l.w2, static_cast<std::size_t>(l.h1) * l.h2, std::sqrt(6.0 / l.h1));
  fill(l.w3, static_cast<std::size_t>(l.h2 + l.f) * l.h3, std::sqrt(6.0 / (l.h2 + l.f)));
  fill(l.w4, static_cast<std::size_t>(l.h3) * l.k, std::sqrt(6.0 / (l.h3 + l.k)));
  return net;
}

namespace {

// Back through a dense layer out = in W (+ b), W row-major (n_in x n_out): adds in^T dout to the
// weights' gradient and writes dout W^T, the gradient of each input, to d_in.
void DenseBackward(const float* in, int n_in, const float* dout, int n_out, const float* w, float* gw, float* d_in) {
  for (int i = 0; i < n_in; ++i) {
    const float* wi = w + static_cast<std::size_t>(i) * n_out;
    float* gwi = gw + static_cast<std::size_t>(i) * n_out;
    float d = 0.f;
    for (int k = 0; k < n_out; ++k) {
      gwi[k] += in[i] * dout[k];
      d += wi[k] * dout[k];
    }
    d_in[i] = d;
  }
}

}  // namespace

double PointNetwork::Backward(const float* x, int n, const float* global, int label, float weight,
                              float* gradient) const {
  const Layout l = layout();
  const float* p = params_.data();
  // Shared per-point layers; the second is maximised over the points as it is computed.
  std::vector<float> h1(static_cast<std::size_t>(n) * l.h1);
  std::vector<float> a2(static_cast<std::size_t>(l.h2));
  std::vector<float> pooled(static_cast<std::size_t>(l.h2), 0.f);
  std::vector<int> arg(static_cast<std::size_t>(l.h2), -1);  // the point that gave each pooled value
  for (int q = 0; q < n; ++q) {
    float* a = &h1[static_cast<std::size_t>(q) * l.h1];
    std::copy(p + l.b1, p + l.b1 + l.h1, a);
    for (int i = 0; i < l.c; ++i) {
      const float xi = x[static_cast<std::size_t>(q) * l.c + i];
      const float* w = p + l.w1 + static_cast<std::size_t>(i) * l.h1;
      for (int j = 0; j < l.h1; ++j) a[j] += xi * w[j];
    }
    for (int j = 0; j < l.h1; ++j) a[j] = std::max(a[j], 0.f);
    std::copy(p + l.b2, p + l.b2 + l.h2, a2.begin());
    for (int j = 0; j < l.h1; ++j) {
      const float h = a[j];
      if (h == 0.f) continue;
      const float* w = p + l.w2 + static_cast<std::size_t>(j) * l.h2;
      for (int k = 0; k < l.h2; ++k) a2[static_cast<std::size_t>(k)] += h * w[k];
    }
    // max(0, max over points) = the max of the ReLU; a point that does not exceed 0 gives no gradient.
    for (int k = 0; k < l.h2; ++k) {
      if (a2[static_cast<std::size_t>(k)] > pooled[static_cast<std::size_t>(k)]) {
        pooled[static_cast<std::size_t>(k)] = a2[static_cast<std::size_t>(k)];
        arg[static_cast<std::size_t>(k)] = q;
      }
    }
  }
  // Head: [pooled, globals] -> ReLU layer -> logits.
  std::vector<float> u(pooled);
  if (l.f > 0) u.insert(u.end(), global, global + l.f);
  std::vector<float> h3(p + l.b3, p + l.b3 + l.h3);
  for (int i = 0; i < l.h2 + l.f; ++i) {
    const float ui = u[static_cast<std::size_t>(i)];
    if (ui == 0.f) continue;
    const float* w = p + l.w3 + static_cast<std::size_t>(i) * l.h3;
    for (int j = 0; j < l.h3; ++j) h3[static_cast<std::size_t>(j)] += ui * w[j];
  }
  for (float& v : h3) v = std::max(v, 0.f);
  std::vector<double> logits(static_cast<std::size_t>(l.k));
  for (int k = 0; k < l.k; ++k) {
    double z = p[l.b4 + static_cast<std::size_t>(k)];
    for (int j = 0; j < l.h3; ++j) z += static_cast<double>(h3[static_cast<std::size_t>(j)]) * p[l.w4 + static_cast<std::size_t>(j) * l.k + k];
    logits[static_cast<std::size_t>(k)] = z;
  }
  const double top = *std::max_element(logits.begin(), logits.end());
  double total = 0.0;
  for (double& z : logits) total += (z = std::exp(z - top));
  for (double& z : logits) z /= total;  // now probabilities
  if (label < 0) {  // forward only: the probabilities in `gradient`
    for (int k = 0; k < l.k; ++k) gradient[k] = static_cast<float>(logits[static_cast<std::size_t>(k)]);
    return 0.0;
  }
  const double loss = -static_cast<double>(weight) * std::log(std::max(logits[static_cast<std::size_t>(label)], 1e-30));
  float* g = gradient;
  std::vector<float> dlogit(static_cast<std::size_t>(l.k));
  for (int k = 0; k < l.k; ++k) {
    dlogit[static_cast<std::size_t>(k)] =
        weight * static_cast<float>(logits[static_cast<std::size_t>(k)] - (k == label ? 1.0 : 0.0));
    g[l.b4 + static_cast<std::size_t>(k)] += dlogit[static_cast<std::size_t>(k)];
  }
  std::vector<float> da3(static_cast<std::size_t>(l.h3));
  DenseBackward(h3.data(), l.h3, dlogit.data(), l.k, p + l.w4, g + l.w4, da3.data());
  for (int j = 0; j < l.h3; ++j) {
    if (!(h3[static_cast<std::size_t>(j)] > 0.f)) da3[static_cast<std::size_t>(j)] = 0.f;  // the ReLU
    g[l.b3 + static_cast<std::size_t>(j)] += da3[static_cast<std::size_t>(j)];
  }
  std::vector<float> du(u.size());  // the pooled values' gradients first, then the globals' (not used)
  DenseBackward(u.data(), l.h2 + l.f, da3.data(), l.h3, p + l.w3, g + l.w3, du.data());
  // Through the max: only the point that gave a pooled value receives its gradient.
  std::vector<float> dh1(static_cast<std::size_t>(n) * l.h1, 0.f);
  std::vector<char> reached(static_cast<std::size_t>(n), 0);
  for (int k = 0; k < l.h2; ++k) {
    const int q = arg[static_cast<std::size_t>(k)];
    if (q < 0) continue;
    const float d = du[static_cast<std::size_t>(k)];
    g[l.b2 + static_cast<std::size_t>(k)] += d;
    reached[static_cast<std::size_t>(q)] = 1;
    const float* hq = &h1[static_cast<std::size_t>(q) * l.h1];
    float* dq = &dh1[static_cast<std::size_t>(q) * l.h1];
    for (int j = 0; j < l.h1; ++j) {
      if (hq[j] == 0.f) continue;
      g[l.w2 + static_cast<std::size_t>(j) * l.h2 + k] += hq[j] * d;
      dq[j] += p[l.w2 + static_cast<std::size_t>(j) * l.h2 + k] * d;
    }
  }
  for (int q = 0; q < n; ++q) {
    if (!reached[static_cast<std::size_t>(q)]) continue;
    const float* hq = &h1[static_cast<std::size_t>(q) * l.h1];
    const float* dq = &dh1[static_cast<std::size_t>(q) * l.h1];
    for (int j = 0; j < l.h1; ++j) {
      if (hq[j] == 0.f) continue;
      g[l.b1 + static_cast<std::size_t>(j)] += dq[j];
      for (int i = 0; i < l.c; ++i) {
        g[l.w1 + static_cast<std::size_t>(i) * l.h1 + j] += x[static_cast<std::size_t>(q) * l.c + i] * dq[j];
      }
    }
  }
  return loss;
}

std::vector<float> PointNetwork::Standardized(const float* global) const {
  std::vector<float> out(static_cast<std::size_t>(num_global_features_));
  for (int i = 0; i < num_global_features_; ++i) {
    out[static_cast<std::size_t>(i)] =
        (global[i] - global_mean_[static_cast<std::size_t>(i)]) * global_inverse_std_[static_cast<std::size_t>(i)];
  }
  return out;
}

namespace {

// The set with X and/or Y negated (flip 0..3).
std::vector<float> Flipped(const EncodedPointSet& set, int flip) {
  std::vector<float> x = set.channels;
  for (std::size_t q = 0; q < x.size(); q += kPointChannels) {
    if (flip & 1) x[q] = -x[q];
    if (flip & 2) x[q + 1] = -x[q + 1];
  }
  return x;
}

}  // namespace

std::vector<double> PointNetwork::Predict(const EncodedPointSet& set, const float* global_features) const {
  if (!trained() || set.num_points() == 0 || (num_global_features_ > 0 && global_features == nullptr)) return {};
  const std::vector<float> global = Standardized(global_features);
  std::vector<double> mean(static_cast<std::size_t>(num_classes_), 0.0);
  std::vector<float> probabilities(static_cast<std::size_t>(num_classes_));
  for (int flip = 0; flip < 4; ++flip) {
    const std::vector<float> x = Flipped(set, flip);
    Backward(x.data(), set.num_points(), global.data(), -1, 0.f, probabilities.data());
    for (int k = 0; k < num_classes_; ++k) mean[static_cast<std::size_t>(k)] += probabilities[static_cast<std::size_t>(k)] / 4.0;
  }
  return mean;
}

std::vector<double> PointNetwork::Probabilities(const EncodedPointSet& set, const float* global_features) const {
  const std::vector<float> global = Standardized(global_features);
  std::vector<float> p(static_cast<std::size_t>(num_classes_));
  Backward(set.channels.data(), set.num_points(), global.data(), -1, 0.f, p.data());
  return std::vector<double>(p.begin(), p.end());
}

std::vector<float> PointNetwork::Gradient(const EncodedPointSet& set, const float* global_features, int label) const {
  const std::vector<float> global = Standardized(global_features);
  std::vector<float> g(params_.size(), 0.f);
  Backward(set.channels.data(), set.num_points(), global.data(), label, 1.f, g.data());
  return g;
}

double PointNetwork::Loss(const PointNetworkTrainingSet& data) const {
  double loss = 0.0, weight = 0.0;
  for (int s = 0; s < data.num_samples(); ++s) {
    const float* global = data.num_global_features > 0
                              ? &data.global_features[static_cast<std::size_t>(s) * data.num_global_features]
                              : nullptr;
    const std::vector<double> p = Predict(data.sets[static_cast<std::size_t>(s)], global);
    if (p.empty()) continue;
    const double w = data.weights[static_cast<std::size_t>(s)];
    loss -= w * std::log(std::max(p[static_cast<std::size_t>(data.labels[static_cast<std::size_t>(s)])], 1e-30));
    weight += w;
  }
  return weight > 0.0 ? loss / weight : 0.0;
}

PointNetwork PointNetwork::Train(const PointNetworkTrainingSet& data, const PointNetworkOptions& options) {
  options.Validate();
  const int n = data.num_samples();
  const int f = data.num_global_features;
  if (n == 0) throw InputError("point network: no training samples");
  if (data.num_classes < 1 || f < 0 || data.sets.size() != static_cast<std::size_t>(n) ||
      data.weights.size() != static_cast<std::size_t>(n) ||
      data.global_features.size() != static_cast<std::size_t>(n) * static_cast<std::size_t>(f)) {
    throw InputError("point network: inconsistent training set sizes");
  }
  for (int s = 0; s < n; ++s) {
    const int label = data.labels[static_cast<std::size_t>(s)];
    if (label < 0 || label >= data.num_classes) throw InputError("point network: a label out of range");
    if (data.sets[static_cast<std::size_t>(s)].num_points() == 0) throw InputError("point network: an empty point set");
    if (!(data.weights[static_cast<std::size_t>(s)] > 0.f)) throw InputError("point network: a weight that is not positive");
  }
  PointNetwork net = Initialized(data.num_classes, f, options);
  // The head's global features standardised over the training set.
  std::vector<float> global(data.global_features.size());
  for (int j = 0; j < f; ++j) {
    double mean = 0.0, square = 0.0;
    for (int s = 0; s < n; ++s) {
      const double v = data.global_features[static_cast<std::size_t>(s) * f + j];
      mean += v;
      square += v * v;
    }
    mean /= n;
    const double variance = std::max(0.0, square / n - mean * mean);
    net.global_mean_[static_cast<std::size_t>(j)] = static_cast<float>(mean);
    net.global_inverse_std_[static_cast<std::size_t>(j)] = variance > 1e-12 ? static_cast<float>(1.0 / std::sqrt(variance)) : 0.f;
  }
  for (int s = 0; f > 0 && s < n; ++s) {
    const std::vector<float> row = net.Standardized(&data.global_features[static_cast<std::size_t>(s) * f]);
    std::copy(row.begin(), row.end(), global.begin() + static_cast<std::ptrdiff_t>(s) * f);
  }
  const std::size_t size = net.params_.size();
  std::vector<float> m(size, 0.f), v(size, 0.f), step_gradient(size);
  const int batch = std::min(options.batch_size, n);
  const int batches_per_epoch = (n + batch - 1) / batch;
  const long total_steps = static_cast<long>(batches_per_epoch) * options.epochs;
  // A batch's samples are summed in a fixed number of chunks, each in sample order, and the chunks
  // in chunk order: the same float sums whichever thread ran a chunk.
  constexpr int kChunks = 8;
  std::vector<std::vector<float>> chunk_gradient(kChunks, std::vector<float>(size));
  const double beta1 = 0.9, beta2 = 0.999, epsilon = 1e-8;
  const double yaw_jitter = options.yaw_jitter_deg * M_PI / 180.0;
  std::vector<int> order(static_cast<std::size_t>(n));
  long step = 0;
  for (int epoch = 0; epoch < options.epochs; ++epoch) {
    std::iota(order.begin(), order.end(), 0);
    Rng shuffle(DeriveSeed(options.seed, 2 * static_cast<std::uint64_t>(epoch) + 1));
    for (int i = n - 1; i > 0; --i) std::swap(order[static_cast<std::size_t>(i)], order[static_cast<std::size_t>(shuffle.UniformInt(0, i))]);
    const std::uint64_t epoch_seed = DeriveSeed(options.seed, 2 * static_cast<std::uint64_t>(epoch) + 2);
    for (int b = 0; b < batches_per_epoch; ++b) {
      const int first = b * batch, count = std::min(batch, n - first);
      const int chunks = std::min(kChunks, count);
      ParallelForBlocks(chunks, options.threads, [&](int chunk) {
        std::vector<float>& gc = chunk_gradient[static_cast<std::size_t>(chunk)];
        std::fill(gc.begin(), gc.end(), 0.f);
        std::vector<float> x;
        for (int t = chunk; t < count; t += chunks) {
          const int s = order[static_cast<std::size_t>(first + t)];
          const EncodedPointSet& set = data.sets[static_cast<std::size_t>(s)];
          Rng rng(DeriveSeed(epoch_seed, static_cast<std::uint64_t>(s)));
          // Augmented: a random share of the points, turned a little, scaled a little, flipped.
          const int points = set.num_points();
          std::vector<int> keep(static_cast<std::size_t>(points));
          std::iota(keep.begin(), keep.end(), 0);
          const int kept = std::max(1, static_cast<int>(std::ceil(points * rng.Uniform(options.keep_min_fraction, 1.0))));
          for (int i = 0; i < kept && i < points - 1; ++i) {
            std::swap(keep[static_cast<std::size_t>(i)], keep[static_cast<std::size_t>(rng.UniformInt(i, points - 1))]);
          }
          keep.resize(static_cast<std::size_t>(kept));
          std::sort(keep.begin(), keep.end());
          const double yaw = rng.Uniform(-yaw_jitter, yaw_jitter);
          const float c = static_cast<float>(std::cos(yaw)), sn = static_cast<float>(std::sin(yaw));
          const float scale = static_cast<float>(rng.Uniform(1.0 - options.scale_jitter, 1.0 + options.scale_jitter));
          const float sx = rng.Bernoulli(0.5) ? -1.f : 1.f, sy = rng.Bernoulli(0.5) ? -1.f : 1.f;
          x.assign(static_cast<std::size_t>(kept) * kPointChannels, 0.f);
          for (int i = 0; i < kept; ++i) {
            const float* src = &set.channels[static_cast<std::size_t>(keep[static_cast<std::size_t>(i)]) * kPointChannels];
            float* dst = &x[static_cast<std::size_t>(i) * kPointChannels];
            const float px = sx * src[0], py = sy * src[1];
            dst[0] = scale * (c * px - sn * py);
            dst[1] = scale * (sn * px + c * py);
            dst[2] = scale * src[2];
            dst[3] = scale * src[3];
            // The normals' absolute components are kept as they are: the turn is small.
            dst[4] = src[4];
            dst[5] = src[5];
            dst[6] = src[6];
          }
          net.Backward(x.data(), kept, f > 0 ? &global[static_cast<std::size_t>(s) * f] : nullptr,
                       data.labels[static_cast<std::size_t>(s)], data.weights[static_cast<std::size_t>(s)], gc.data());
        }
      });
      std::fill(step_gradient.begin(), step_gradient.end(), 0.f);
      for (int chunk = 0; chunk < chunks; ++chunk) {
        const std::vector<float>& gc = chunk_gradient[static_cast<std::size_t>(chunk)];
        for (std::size_t i = 0; i < size; ++i) step_gradient[i] += gc[i];
      }
      ++step;
      const double rate = options.learning_rate * 0.5 * (1.0 + std::cos(M_PI * static_cast<double>(step - 1) / total_steps));
      const double correction1 = 1.0 - std::pow(beta1, static_cast<double>(step));
      const double correction2 = 1.0 - std::pow(beta2, static_cast<double>(step));
      const float inverse_count = 1.f / static_cast<float>(count);
      for (std::size_t i = 0; i < size; ++i) {
        const float gi = step_gradient[i] * inverse_count;
        m[i] = static_cast<float>(beta1 * m[i] + (1.0 - beta1) * gi);
        v[i] = static_cast<float>(beta2 * v[i] + (1.0 - beta2) * gi * gi);
        const double update = (m[i] / correction1) / (std::sqrt(v[i] / correction2) + epsilon);
        net.params_[i] = static_cast<float>(net.params_[i] * (1.0 - rate * options.weight_decay) - rate * update);
      }
    }
  }
  return net;
}

void PointNetwork::Write(io::BinaryWriter* out) const {
  out->Pod(static_cast<std::int32_t>(num_classes_));
  out->Pod(static_cast<std::int32_t>(num_global_features_));
  out->Pod(static_cast<std::int32_t>(point_features_));
  out->Pod(static_cast<std::int32_t>(pooled_features_));
  out->Pod(static_cast<std::int32_t>(head_features_));
  out->Pod(static_cast<std::int32_t>(max_points_));
  out->Vector(params_);
  out->Vector(global_mean_);
  out->Vector(global_inverse_std_);
}

PointNetwork PointNetwork::Read(io::BinaryReader* in) {
  PointNetwork net;
  net.num_classes_ = in->Pod<std::int32_t>("network classes");
  net.num_global_features_ = in->Pod<std::int32_t>("network global features");
  net.point_features_ = in->Pod<std::int32_t>("network widths");
  net.pooled_features_ = in->Pod<std::int32_t>("network widths");
  net.head_features_ = in->Pod<std::int32_t>("network widths");
  net.max_points_ = in->Pod<std::int32_t>("network points");
  auto in_range = [](int v) { return v >= 1 && v <= 4096; };
  if (!in_range(net.num_classes_) || net.num_global_features_ < 0 || net.num_global_features_ > 4096 ||
      !in_range(net.point_features_) || !in_range(net.pooled_features_) || !in_range(net.head_features_) ||
      net.max_points_ < 1) {
    in->Fail("network sizes out of range");
  }
  net.params_ = in->Vector<float>("network weights");
  net.global_mean_ = in->Vector<float>("network feature means");
  net.global_inverse_std_ = in->Vector<float>("network feature scales");
  if (net.params_.size() != net.layout().size ||
      net.global_mean_.size() != static_cast<std::size_t>(net.num_global_features_) ||
      net.global_inverse_std_.size() != static_cast<std::size_t>(net.num_global_features_)) {
    in->Fail("network weights of the wrong size");
  }
  return net;
}

}  // namespace objscan::recognition
