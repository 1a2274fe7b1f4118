#include "objscan/recognition/point_network.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

#include "objscan/common/error.h"
#include "objscan/common/rng.h"

namespace objscan::recognition {
namespace {

// Points and normals of three kinds of shape, each with a random size and pose: 0 a horizontal
// board at table height, 1 a vertical board standing on the floor, 2 a ball on the floor.
void Shape(int kind, Rng* rng, std::vector<Eigen::Vector3f>* points, std::vector<Eigen::Vector3f>* normals) {
  points->clear();
  normals->clear();
  const double yaw = rng->Uniform(0.0, 2.0 * M_PI);
  const Eigen::Vector3f offset(static_cast<float>(rng->Uniform(-3, 3)), static_cast<float>(rng->Uniform(-3, 3)), 0.f);
  const Eigen::Matrix3f turn = Eigen::AngleAxisf(static_cast<float>(yaw), Eigen::Vector3f::UnitZ()).toRotationMatrix();
  const int n = rng->UniformInt(30, 90);
  const double size = rng->Uniform(0.6, 1.2);
  for (int i = 0; i < n; ++i) {
    Eigen::Vector3f p, nrm;
    if (kind == 0) {
      p = Eigen::Vector3f(static_cast<float>(rng->Uniform(-size, size)), static_cast<float>(rng->Uniform(-0.4, 0.4)),
                          static_cast<float>(0.75 + rng->Normal(0.0, 0.005)));
      nrm = Eigen::Vector3f::UnitZ();
    } else if (kind == 1) {
      p = Eigen::Vector3f(static_cast<float>(rng->Uniform(-size, size)), static_cast<float>(rng->Normal(0.0, 0.005)),
                          static_cast<float>(rng->Uniform(0.0, 1.0)));
      nrm = Eigen::Vector3f::UnitY();
    } else {
      nrm = Eigen::Vector3f(static_cast<float>(rng->Normal()), static_cast<float>(rng->Normal()),
                            static_cast<float>(std::abs(rng->Normal()))).normalized();
      p = 0.3f * static_cast<float>(size) * nrm + Eigen::Vector3f(0.f, 0.f, 0.3f * static_cast<float>(size));
    }
    points->push_back(turn * p + offset);
    normals->push_back(turn * nrm);
  }
}

PointNetworkOptions SmallOptions() {
  PointNetworkOptions options;
  options.point_features = 16;
  options.pooled_features = 32;
  options.head_features = 16;
  options.max_points = 64;
  options.epochs = 12;
  options.batch_size = 16;
  options.learning_rate = 3e-3;
  options.threads = 1;
  return options;
}

PointNetworkTrainingSet Shapes(int per_kind, std::uint64_t seed, int max_points) {
  Rng rng(seed);
  PointNetworkTrainingSet data;
  data.num_classes = 3;
  data.num_global_features = 1;
  std::vector<Eigen::Vector3f> points, normals;
  for (int i = 0; i < per_kind; ++i) {
    for (int kind = 0; kind < 3; ++kind) {
      Shape(kind, &rng, &points, &normals);
      data.sets.push_back(EncodePointSet(points, normals, 0.0, max_points));
      data.global_features.push_back(static_cast<float>(rng.Uniform(-1, 1)));  // noise
      data.labels.push_back(kind);
      data.weights.push_back(1.f);
    }
  }
  return data;
}

TEST(PointNetworkTest, EncodingIsTheSameWhereverTheSetStandsAndHowItIsTurned) {
  Rng rng(3);
  std::vector<Eigen::Vector3f> points, normals;
  Shape(0, &rng, &points, &normals);
  const EncodedPointSet a = EncodePointSet(points, normals, 0.0, 1000);
  const Eigen::Matrix3f turn = Eigen::AngleAxisf(1.1f, Eigen::Vector3f::UnitZ()).toRotationMatrix();
  for (auto& p : points) p = turn * p + Eigen::Vector3f(5.f, -2.f, 0.f);
  for (auto& n : normals) n = turn * n;
  const EncodedPointSet b = EncodePointSet(points, normals, 0.0, 1000);
  ASSERT_EQ(a.num_points(), b.num_points());
  ASSERT_EQ(a.num_points(), static_cast<int>(points.size()));
  // The principal axis may come out either way round: X and Y agree up to their signs.
  for (std::size_t i = 0; i < a.channels.size(); ++i) {
    EXPECT_NEAR(std::abs(a.channels[i]), std::abs(b.channels[i]), 1e-3) << i;
  }
  // The board lies along X in its own frame, at 0.75 m above the floor and 0 above its bottom.
  float x_extent = 0.f, y_extent = 0.f;
  for (int q = 0; q < a.num_points(); ++q) {
    x_extent = std::max(x_extent, std::abs(a.channels[static_cast<std::size_t>(q) * kPointChannels]));
    y_extent = std::max(y_extent, std::abs(a.channels[static_cast<std::size_t>(q) * kPointChannels + 1]));
    EXPECT_NEAR(a.channels[static_cast<std::size_t>(q) * kPointChannels + 2], 0.75f, 0.05f);
    EXPECT_NEAR(a.channels[static_cast<std::size_t>(q) * kPointChannels + 3], 0.0f, 0.05f);
    EXPECT_NEAR(a.channels[static_cast<std::size_t>(q) * kPointChannels + 6], 1.0f, 1e-5f);  // |nz|
  }
  EXPECT_GT(x_extent, y_extent);
  // Thinning keeps max_points, and a floor 1 m lower raises every height by 1 m.
  EXPECT_EQ(EncodePointSet(points, normals, 0.0, 10).num_points(), 10);
  const EncodedPointSet lower = EncodePointSet(points, normals, -1.0, 1000);
  EXPECT_NEAR(lower.channels[2], b.channels[2] + 1.f, 1e-5f);
  EXPECT_EQ(EncodePointSet({}, {}, 0.0, 10).num_points(), 0);
}

TEST(PointNetworkTest, GradientMatchesFiniteDifferences) {
  PointNetworkOptions options = SmallOptions();
  options.point_features = 5;
  options.pooled_features = 6;
  options.head_features = 4;
  PointNetwork net = PointNetwork::Initialized(3, 2, options);
  Rng rng(11);
  for (float& p : net.parameters()) p += static_cast<float>(rng.Uniform(-0.05, 0.05));  // biases off zero
  EncodedPointSet set;
  for (int i = 0; i < 9 * kPointChannels; ++i) set.channels.push_back(static_cast<float>(rng.Uniform(-1, 1)));
  const float global[2] = {0.3f, -0.7f};
  const int label = 1;
  const std::vector<float> gradient = net.Gradient(set, global, label);
  // Central differences of the cross-entropy of the set as given (no flips).
  int checked = 0, nonzero = 0;
  for (std::size_t i = 0; i < net.parameters().size(); ++i) {
    const float saved = net.parameters()[i];
    const float h = 1e-2f;
    net.parameters()[i] = saved + h;
    const double up = -std::log(net.Probabilities(set, global)[label]);
    net.parameters()[i] = saved - h;
    const double down = -std::log(net.Probabilities(set, global)[label]);
    net.parameters()[i] = saved;
    const double numeric = (up - down) / (2.0 * h);
    EXPECT_NEAR(gradient[i], numeric, 2e-3 + 2e-2 * std::abs(numeric)) << "parameter " << i;
    ++checked;
    if (std::abs(gradient[i]) > 1e-4f) ++nonzero;
  }
  EXPECT_EQ(checked, static_cast<int>(net.parameters().size()));
  EXPECT_GT(nonzero, checked / 4);  // the check is not of an all-zero gradient
}

TEST(PointNetworkTest, LearnsShapesItHasNotSeen) {
  const PointNetworkOptions options = SmallOptions();
  const PointNetworkTrainingSet train = Shapes(40, 1, options.max_points);
  const PointNetwork net = PointNetwork::Train(train, options);
  ASSERT_TRUE(net.trained());
  const PointNetworkTrainingSet test = Shapes(30, 2, options.max_points);
  int right = 0;
  for (int s = 0; s < test.num_samples(); ++s) {
    const std::vector<double> p = net.Predict(test.sets[static_cast<std::size_t>(s)], &test.global_features[static_cast<std::size_t>(s)]);
    ASSERT_EQ(p.size(), 3u);
    EXPECT_NEAR(p[0] + p[1] + p[2], 1.0, 1e-6);
    if (std::max_element(p.begin(), p.end()) - p.begin() == test.labels[static_cast<std::size_t>(s)]) ++right;
  }
  EXPECT_GE(right, test.num_samples() * 9 / 10);
  // Training lowered the loss well below chance (log 3 = 1.10).
  EXPECT_LT(net.Loss(test), 0.4);
  EXPECT_GT(PointNetwork::Initialized(3, 1, options).Loss(test), 0.8);
}

// network_shape_features false: no global features, and Predict takes none (null).
TEST(PointNetworkTest, LearnsFromThePointsAloneWithoutGlobalFeatures) {
  const PointNetworkOptions options = SmallOptions();
  const auto without_globals = [](PointNetworkTrainingSet data) {
    data.num_global_features = 0;
    data.global_features.clear();
    return data;
  };
  const PointNetwork net = PointNetwork::Train(without_globals(Shapes(40, 1, options.max_points)), options);
  ASSERT_TRUE(net.trained());
  const PointNetworkTrainingSet test = without_globals(Shapes(30, 2, options.max_points));
  int right = 0;
  for (int s = 0; s < test.num_samples(); ++s) {
    const std::vector<double> p = net.Predict(test.sets[static_cast<std::size_t>(s)], nullptr);
    ASSERT_EQ(p.size(), 3u);
    EXPECT_NEAR(p[0] + p[1] + p[2], 1.0, 1e-6);
    if (std::max_element(p.begin(), p.end()) - p.begin() == test.labels[static_cast<std::size_t>(s)]) ++right;
  }
  EXPECT_GE(right, test.num_samples() * 9 / 10);
}

TEST(PointNetworkTest, SameWeightsAtAnyThreadCount) {
  PointNetworkOptions options = SmallOptions();
  options.epochs = 2;
  const PointNetworkTrainingSet train = Shapes(12, 5, options.max_points);
  PointNetwork one = PointNetwork::Train(train, options);
  options.threads = 3;
  PointNetwork three = PointNetwork::Train(train, options);
  EXPECT_EQ(one.parameters(), three.parameters());
  options.seed = 2;
  PointNetwork other_seed = PointNetwork::Train(train, options);
  EXPECT_NE(one.parameters(), other_seed.parameters());
}

TEST(PointNetworkTest, WritesAndReadsBackExactlyAndRejectsDamage) {
  PointNetworkOptions options = SmallOptions();
  options.epochs = 1;
  const PointNetworkTrainingSet train = Shapes(6, 7, options.max_points);
  const PointNetwork net = PointNetwork::Train(train, options);
  io::BinaryWriter w;
  net.Write(&w);
  const std::string path = "point_network_test";
  io::BinaryReader r(w.buffer().data(), w.buffer().size(), path, "network");
  const PointNetwork back = PointNetwork::Read(&r);
  EXPECT_TRUE(r.AtEnd());
  EXPECT_EQ(back.max_points(), options.max_points);
  for (int s = 0; s < train.num_samples(); ++s) {
    EXPECT_EQ(net.Predict(train.sets[static_cast<std::size_t>(s)], &train.global_features[static_cast<std::size_t>(s)]),
              back.Predict(train.sets[static_cast<std::size_t>(s)], &train.global_features[static_cast<std::size_t>(s)]));
  }
  io::BinaryReader cut(w.buffer().data(), w.buffer().size() / 2, path, "network");
  EXPECT_THROW(PointNetwork::Read(&cut), InputError);
  std::vector<char> bad = w.buffer();
  bad[0] = 0;  // no classes
  io::BinaryReader zero(bad.data(), bad.size(), path, "network");
  EXPECT_THROW(PointNetwork::Read(&zero), InputError);
}

TEST(PointNetworkTest, RejectsBadTrainingSetsAndOptions) {
  PointNetworkOptions options = SmallOptions();
  EXPECT_THROW(PointNetwork::Train(PointNetworkTrainingSet{}, options), InputError);
  PointNetworkTrainingSet data = Shapes(2, 1, options.max_points);
  data.labels[0] = 7;
  EXPECT_THROW(PointNetwork::Train(data, options), InputError);
  data = Shapes(2, 1, options.max_points);
  data.sets[1].channels.clear();
  EXPECT_THROW(PointNetwork::Train(data, options), InputError);
  options.epochs = 0;
  EXPECT_THROW(options.Validate(), ConfigError);
}

}  // namespace
}  // namespace objscan::recognition
