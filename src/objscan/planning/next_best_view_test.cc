#include "objscan/planning/next_best_view.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "objscan/common/error.h"
#include "objscan/planning/information_gain.h"
#include "objscan/planning/tdf.h"
#include "objscan/planning/voxel_traversal.h"

namespace objscan::planning {
namespace {

using Points = std::vector<Eigen::Vector3f>;

// Samples the six faces of an axis-aligned box on a grid of `spacing_m`.
Points BoxSurface(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, double spacing_m) {
  Points out;
  for (int axis = 0; axis < 3; ++axis) {
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    const int nu = static_cast<int>(std::ceil((hi[u] - lo[u]) / spacing_m));
    const int nv = static_cast<int>(std::ceil((hi[v] - lo[v]) / spacing_m));
    for (double side : {lo[axis], hi[axis]}) {
      for (int i = 0; i <= nu; ++i) {
        for (int j = 0; j <= nv; ++j) {
          Eigen::Vector3d p;
          p[axis] = side;
          p[u] = std::min(hi[u], lo[u] + i * spacing_m);
          p[v] = std::min(hi[v], lo[v] + j * spacing_m);
          out.push_back(p.cast<float>());
        }
      }
    }
  }
  return out;
}

Points Concat(const Points& a, const Points& b) {
  Points out = a;
  out.insert(out.end(), b.begin(), b.end());
  return out;
}

// A 0.6 m cube on 0.2 m legs-height, observed only on its -X half; model A has an extra block on its
// +X face, model B is the plain cube. The models agree everywhere except on the +X block.
struct DisagreeOnPlusX {
  Points cube = BoxSurface({-0.3, -0.3, 0.2}, {0.3, 0.3, 0.8}, 0.01);
  Points block = BoxSurface({0.3, -0.15, 0.35}, {0.5, 0.15, 0.65}, 0.01);
  Points model_a = Concat(cube, block);
  Points model_b = cube;
  Points gamma;
  DisagreeOnPlusX() {
    for (const Eigen::Vector3f& p : cube) {
      if (p.x() < 0.0f) gamma.push_back(p);
    }
  }
  NextBestViewInput Input() const {
    NextBestViewInput in;
    in.gamma_points_world = &gamma;
    in.models = {ModelHypothesis{1, 0.5, &model_a}, ModelHypothesis{2, 0.5, &model_b}};
    return in;
  }
};

geometry::Pose3 LookAt(const Eigen::Vector3d& eye, const Eigen::Vector3d& target) {
  geometry::Pose3 T;
  EXPECT_TRUE(geometry::CameraPoseLookAt(eye, target, &T));
  return T;
}

TEST(NextBestViewTest, OneVoxelTwoModelsMatchesHandComputation) {
  // gamma and m_2 are the same single voxel; m_1 is one voxel 4 voxels further along +X.
  // At m_1's voxel f = (1, 0): H_x(0) = H_x(1) = 0, so G(m_1) = H = -(0.6 ln 0.6 + 0.4 ln 0.4) and
  // G = p(m_1) H = 0.6 H.
  const Points gamma = {Eigen::Vector3f(0.0125f, 0.0125f, 0.5125f)};
  const Points m1 = {Eigen::Vector3f(0.1125f, 0.0125f, 0.5125f)};
  const Points m2 = gamma;
  NextBestViewOptions options;
  options.blur_sigma_voxels = 0.0;
  NextBestView nbv(options);
  NextBestViewInput in;
  in.gamma_points_world = &gamma;
  in.models = {ModelHypothesis{1, 0.6, &m1}, ModelHypothesis{2, 0.4, &m2}};
  const Eigen::Vector3d voxel(0.1125, 0.0125, 0.5125);
  const std::vector<ViewGain> gains =
      nbv.EvaluateViews(in, {LookAt({1.1125, 0.0125, 0.5125}, voxel),     // +X: sees it
                             LookAt({-1.0, 0.0125, 0.5125}, voxel),       // -X: gamma's voxel is in the way
                             LookAt({0.1125, 0.0125, 2.0}, voxel),        // above: sees it
                             LookAt({1.1125, 0.0125, 0.5125}, {2, 0, 0})});  // looking away
  const double h = -(0.6 * std::log(0.6) + 0.4 * std::log(0.4));
  ASSERT_EQ(gains.size(), 4u);
  EXPECT_NEAR(gains[0].gain, 0.6 * h, 1e-7);
  EXPECT_NEAR(gains[0].gain_per_model[0], h, 1e-7);
  EXPECT_EQ(gains[0].gain_per_model[1], 0.0);
  EXPECT_EQ(gains[0].visible_voxels_per_model[0], 1);
  EXPECT_EQ(gains[1].gain, 0.0);  // occluded voxels do not count
  EXPECT_EQ(gains[1].visible_voxels_per_model[0], 0);
  EXPECT_NEAR(gains[2].gain, 0.6 * h, 1e-7);
  EXPECT_EQ(gains[3].gain, 0.0);  // outside the frustum
}

TEST(NextBestViewTest, SceneOccludersHideVoxels) {
  // Same one-voxel case; a scene surface point between the +X camera and the voxel hides it.
  const Points gamma = {Eigen::Vector3f(0.0125f, 0.0125f, 0.5125f)};
  const Points m1 = {Eigen::Vector3f(0.1125f, 0.0125f, 0.5125f)};
  const Points occluder = {Eigen::Vector3f(0.1875f, 0.0125f, 0.5125f)};
  NextBestViewOptions options;
  options.blur_sigma_voxels = 0.0;
  NextBestView nbv(options);
  NextBestViewInput in;
  in.gamma_points_world = &gamma;
  in.models = {ModelHypothesis{1, 0.6, &m1}, ModelHypothesis{2, 0.4, &gamma}};
  const geometry::Pose3 plus_x = LookAt({1.1125, 0.0125, 0.5125}, {0.1125, 0.0125, 0.5125});
  EXPECT_GT(nbv.EvaluateViews(in, {plus_x})[0].gain, 0.0);
  in.occluder_points_world = &occluder;
  EXPECT_EQ(nbv.EvaluateViews(in, {plus_x})[0].gain, 0.0);
}

TEST(NextBestViewTest, AgreeingModelsGiveZeroGain) {
  const DisagreeOnPlusX s;
  NextBestViewInput in = s.Input();
  const Points cube_copy = s.cube;
  in.models = {ModelHypothesis{1, 0.7, &s.cube}, ModelHypothesis{2, 0.3, &cube_copy}};
  NextBestView nbv{NextBestViewOptions()};
  NextBestViewResult r = nbv.Plan(in, nullptr);
  ASSERT_EQ(r.status, NbvStatus::kOk);
  EXPECT_EQ(r.delta_voxels, 0);
  for (const ViewCandidate& c : r.candidates) EXPECT_EQ(c.gain.gain, 0.0);
  // A single candidate model carries no uncertainty either.
  in.models = {ModelHypothesis{1, 0.7, &s.model_a}};
  r = nbv.Plan(in, nullptr);
  EXPECT_EQ(r.prior_entropy_nats, 0.0);
  for (const ViewCandidate& c : r.candidates) EXPECT_EQ(c.gain.gain, 0.0);
}

TEST(NextBestViewTest, PrefersTheViewRevealingWhereModelsDisagree) {
  const DisagreeOnPlusX s;
  NextBestView nbv{NextBestViewOptions()};
  const NextBestViewResult r = nbv.Plan(s.Input(), nullptr);
  ASSERT_EQ(r.status, NbvStatus::kOk);
  ASSERT_EQ(r.candidates.size(), 16u);
  EXPECT_NEAR(r.model_probabilities[0], 0.5, 1e-12);
  EXPECT_NEAR(r.prior_entropy_nats, std::log(2.0), 1e-12);
  // The gain counts voxels, not pixels, so an oblique view seeing the block's +X face, top and a side can
  // beat the head-on one; the winner must be on the +X side all the same.
  const ViewCandidate& best = r.candidates[r.best_index];
  EXPECT_GT(best.gain.gain, 0.0);
  const Eigen::Vector3d d = best.T_world_camera.translation() - r.target_world;
  EXPECT_LE(std::abs(std::atan2(d.y(), d.x())), geometry::DegToRad(45.0) + 1e-9) << "best candidate " << r.best_index;
  EXPECT_GT(best.gain.visible_voxels_per_model[0], 100);
  // From the -X side the block is behind the cube: (almost) nothing to gain there.
  for (int j = 6; j <= 10; ++j) {
    EXPECT_LT(r.candidates[j].gain.gain, 0.05 * best.gain.gain) << "candidate " << j;
  }
  // The head-on +X view beats the side views at +-90 degrees.
  EXPECT_GT(r.candidates[0].gain.gain, r.candidates[4].gain.gain);
  EXPECT_GT(r.candidates[0].gain.gain, r.candidates[12].gain.gain);

  // With one ring of four candidates (+X, +Y, -X, -Y) the +X one must win.
  NextBestViewOptions four;
  four.candidates.num_candidates = 4;
  four.candidates.ring_elevations_deg = {15.0};
  NextBestView nbv4(four);
  const NextBestViewResult r4 = nbv4.Plan(s.Input(), nullptr);
  ASSERT_EQ(r4.status, NbvStatus::kOk);
  EXPECT_EQ(r4.best_index, 0);
  EXPECT_EQ(r4.candidates[2].gain.gain, 0.0);
}

// Four candidates on one ring at 15 degrees: +X, +Y, -X, -Y of the target.
NextBestViewOptions FourOnOneRing() {
  NextBestViewOptions four;
  four.candidates.num_candidates = 4;
  four.candidates.ring_elevations_deg = {15.0};
  return four;
}

TEST(NextBestViewTest, UnobservedSurfaceCountsTheUnseenVoxelsOfOneModel) {
  // One model, the plain cube, seen only on its -X half: no uncertainty, so no information gain, but
  // the unseen +X half is there to be scanned. Four candidates on one ring: +X, +Y, -X, -Y.
  const DisagreeOnPlusX s;
  NextBestView nbv(FourOnOneRing());
  NextBestViewInput in = s.Input();
  in.models = {ModelHypothesis{2, 0.9, &s.model_b}};
  NextBestViewResult r = nbv.Plan(in, nullptr);
  ASSERT_EQ(r.status, NbvStatus::kOk);
  for (const ViewCandidate& c : r.candidates) EXPECT_EQ(c.gain.gain, 0.0);

  in.gain_measure = ViewGainMeasure::kUnobservedSurface;
  r = nbv.Plan(in, nullptr);
  ASSERT_EQ(r.status, NbvStatus::kOk);
  EXPECT_EQ(r.best_index, 0);
  // The gain is the number of unseen model voxels in view: an integer, the same as the count.
  for (const ViewCandidate& c : r.candidates) {
    EXPECT_EQ(c.gain.gain, static_cast<double>(c.gain.visible_voxels_per_model[0]));
  }
  // +X sees the unseen face (0.6 m x 0.6 m: 576 voxels of 2.5 cm, more with the blur) and the unseen
  // half of the top; the sides see half of their face and that half top; -X only that half top.
  EXPECT_GT(r.candidates[0].gain.gain, 576.0);
  EXPECT_GT(r.candidates[0].gain.gain, r.candidates[1].gain.gain);
  EXPECT_GT(r.candidates[1].gain.gain, r.candidates[2].gain.gain);
  EXPECT_GT(r.candidates[3].gain.gain, r.candidates[2].gain.gain);
  EXPECT_LT(r.candidates[2].gain.gain, 0.3 * r.candidates[0].gain.gain);

  // Once everything is observed nothing is left to gain.
  in.gamma_points_world = &s.cube;
  r = nbv.Plan(in, nullptr);
  for (const ViewCandidate& c : r.candidates) EXPECT_EQ(c.gain.gain, 0.0);
}

class RecordTargets : public ViewValidator {
 public:
  ViewValidity Check(const geometry::Pose3&, const Eigen::Vector3d& target) const override {
    targets.push_back(target);
    return ViewValidity::kValid;
  }
  mutable std::vector<Eigen::Vector3d> targets;
};

TEST(NextBestViewTest, AimPointsAddCandidatesLookingAtThem) {
  // The plain cube seen on its -X half; aiming at the unseen +X half adds a second ring set of
  // candidates, each looking at that half's centre and validated against it.
  const DisagreeOnPlusX s;
  NextBestView nbv(FourOnOneRing());
  NextBestViewInput in = s.Input();
  in.models = {ModelHypothesis{2, 1.0, &s.model_b}};
  in.gain_measure = ViewGainMeasure::kUnobservedSurface;
  Points aim;
  for (const Eigen::Vector3f& p : s.cube) {
    if (p.x() > 0.0f) aim.push_back(p);
  }
  in.aim_points_world = &aim;
  const RecordTargets validator;
  const NextBestViewResult r = nbv.Plan(in, &validator);
  ASSERT_EQ(r.status, NbvStatus::kOk);
  ASSERT_EQ(r.candidates.size(), 8u);
  ASSERT_EQ(validator.targets.size(), 8u);
  geometry::Aabb3 box;
  for (const auto& p : aim) box.Extend(p.cast<double>());
  for (int j = 0; j < 8; ++j) {
    const Eigen::Vector3d target = j < 4 ? r.target_world : box.Center();
    EXPECT_LT((validator.targets[j] - target).norm(), 1e-9) << j;
    const geometry::Pose3& T = r.candidates[j].T_world_camera;
    const Eigen::Vector3d to_target = (target - T.translation()).normalized();
    EXPECT_GT(to_target.dot(T.linear().col(2)), 1.0 - 1e-6) << j;  // the optical axis points at it
  }
  // The aimed +X candidate is nearer the unseen half than the whole-object one and sees it too.
  EXPECT_LT((r.candidates[4].T_world_camera.translation() - box.Center()).norm(),
            (r.candidates[0].T_world_camera.translation() - box.Center()).norm() + 1e-9);
  EXPECT_GT(r.candidates[4].gain.gain, 576.0);
  // Without aim points: the four around the whole object only, with the same gains as before.
  in.aim_points_world = nullptr;
  const NextBestViewResult plain = nbv.Plan(in, nullptr);
  ASSERT_EQ(plain.candidates.size(), 4u);
  for (int j = 0; j < 4; ++j) EXPECT_EQ(plain.candidates[j].gain.gain, r.candidates[j].gain.gain);
  Points bad = aim;
  bad.emplace_back(std::numeric_limits<float>::quiet_NaN(), 0.0f, 0.0f);
  in.aim_points_world = &bad;
  EXPECT_THROW(nbv.Plan(in, nullptr), InputError);
}

TEST(NextBestViewTest, OccludedVoxelsDoNotCount) {
  const DisagreeOnPlusX s;
  NextBestView nbv{NextBestViewOptions()};
  NextBestViewInput in = s.Input();
  const Eigen::Vector3d target(0.1, 0.0, 0.5);
  const geometry::Pose3 plus_x = LookAt({2.0, 0.0, 0.5}, target);
  const geometry::Pose3 minus_x = LookAt({-2.0, 0.0, 0.5}, target);
  std::vector<ViewGain> gains = nbv.EvaluateViews(in, {plus_x, minus_x});
  EXPECT_GT(gains[0].gain, 0.0);
  EXPECT_EQ(gains[1].gain, 0.0);  // the block is behind the cube (the observed -X face and model A itself)
  // A wall of scene surface between the +X camera and the block hides it too.
  const Points wall = BoxSurface({0.62, -0.45, 0.1}, {0.62, 0.45, 0.9}, 0.01);
  in.occluder_points_world = &wall;
  gains = nbv.EvaluateViews(in, {plus_x});
  EXPECT_EQ(gains[0].gain, 0.0);
}

class RejectPlusX : public ViewValidator {
 public:
  explicit RejectPlusX(bool reject_all = false) : reject_all_(reject_all) {}
  ViewValidity Check(const geometry::Pose3& T, const Eigen::Vector3d& target) const override {
    if (reject_all_) return ViewValidity::kUnreachable;
    return T.translation().x() > target.x() + 1e-6 ? ViewValidity::kOccupied : ViewValidity::kValid;
  }

 private:
  bool reject_all_;
};

TEST(NextBestViewTest, InvalidCandidatesAreDropped) {
  const DisagreeOnPlusX s;
  NextBestView nbv{NextBestViewOptions()};
  const RejectPlusX validator;
  const NextBestViewResult r = nbv.Plan(s.Input(), &validator);
  ASSERT_EQ(r.status, NbvStatus::kOk);
  int invalid = 0;
  for (const ViewCandidate& c : r.candidates) {
    if (c.validity != ViewValidity::kValid) {
      ++invalid;
      EXPECT_EQ(c.validity, ViewValidity::kOccupied);
      EXPECT_EQ(c.gain.gain, 0.0);
    }
  }
  EXPECT_EQ(invalid, 7);  // azimuths strictly between -90 and +90 degrees
  const ViewCandidate& best = r.candidates[r.best_index];
  EXPECT_EQ(best.validity, ViewValidity::kValid);
  EXPECT_LE(best.T_world_camera.translation().x(), r.target_world.x() + 1e-9);
  EXPECT_GT(best.gain.gain, 0.0);  // the +-90 degree views still see the block's sides

  const RejectPlusX reject_all(true);
  const NextBestViewResult none = nbv.Plan(s.Input(), &reject_all);
  EXPECT_EQ(none.status, NbvStatus::kNoValidView);
  EXPECT_EQ(none.best_index, -1);
  EXPECT_EQ(none.candidates.size(), 16u);
}

TEST(NextBestViewTest, TiesGoToTheCandidateNearestTheCamera) {
  const DisagreeOnPlusX s;
  NextBestViewInput in = s.Input();
  in.models.clear();  // no candidate models: every gain is 0
  in.has_camera_position = true;
  in.camera_position_world = Eigen::Vector3d(0.1, -3.0, 1.0);  // towards azimuth -90 degrees
  NextBestView nbv{NextBestViewOptions()};
  const NextBestViewResult r = nbv.Plan(in, nullptr);
  ASSERT_EQ(r.status, NbvStatus::kOk);
  EXPECT_EQ(r.best_index, 12);
}

TEST(NextBestViewTest, GainsMatchABruteForceSumOverAllVoxels) {
  // Three candidate models with soft TDFs; recompute G^j voxel by voxel straight from the definitions.
  const DisagreeOnPlusX s;
  Points shifted;
  for (const Eigen::Vector3f& p : s.cube) shifted.push_back(p + Eigen::Vector3f(0.0f, 0.0f, 0.05f));
  NextBestViewInput in = s.Input();
  in.models = {ModelHypothesis{1, 0.5, &s.model_a}, ModelHypothesis{2, 0.3, &s.model_b},
               ModelHypothesis{3, 0.2, &shifted}};
  const NextBestViewOptions options;
  NextBestView nbv(options);
  const NextBestViewResult r = nbv.Plan(in, nullptr);
  ASSERT_EQ(r.status, NbvStatus::kOk);

  const LocalGrid& g = r.grid;
  std::vector<float> scratch, f_gamma;
  BuildTdf(g, s.gamma, options.blur_sigma_voxels, &f_gamma, &scratch);
  std::vector<std::vector<float>> f_model(3);
  std::vector<std::uint16_t> mask(g.NumVoxels(), 0);
  RasterizeMask(g, s.gamma, 1, &mask);
  for (int i = 0; i < 3; ++i) {
    BuildTdf(g, *in.models[i].points_world, options.blur_sigma_voxels, &f_model[i], &scratch);
    RasterizeMask(g, *in.models[i].points_world, static_cast<std::uint16_t>(1 << (i + 1)), &mask);
  }
  const std::vector<double> p = CandidateProbabilities({0.5, 0.3, 0.2});
  const double h = Entropy(p.data(), 3);
  for (int j : {0, 3, 8, 13}) {
    const geometry::Pose3& T = r.candidates[j].T_world_camera;
    double expected = 0.0;
    for (int z = 0; z < g.nz; ++z) {
      for (int y = 0; y < g.ny; ++y) {
        for (int x = 0; x < g.nx; ++x) {
          const std::size_t v = g.Index(x, y, z);
          if (f_gamma[v] > options.tdf_epsilon) continue;
          const float f[3] = {f_model[0][v], f_model[1][v], f_model[2][v]};
          double h0, h1;
          OutcomeEntropies(p.data(), f, 3, h, &h0, &h1);
          const Eigen::Vector3d p_camera = T.inverse() * g.CenterOf(x, y, z);
          if (!in.frustum.Contains(p_camera)) continue;
          for (int i = 0; i < 3; ++i) {
            if (f[i] <= options.tdf_epsilon) continue;
            if (!IsVoxelVisible(g.nx, g.ny, g.nz, mask.data(), static_cast<std::uint16_t>(1 | (1 << (i + 1))),
                                g.ToGrid(T.translation()), x, y, z, options.occlusion_tolerance_voxels)) {
              continue;
            }
            expected += p[i] * (h - ConditionalEntropy(f[i], h0, h1));
          }
        }
      }
    }
    EXPECT_NEAR(r.candidates[j].gain.gain, expected, 1e-6 * std::max(1.0, std::abs(expected))) << "candidate " << j;
  }
  // Same input, same answer, whatever the number of threads.
  NextBestViewOptions one_thread = options;
  one_thread.threads = 1;
  NextBestViewOptions three_threads = options;
  three_threads.threads = 3;
  const NextBestViewResult r1 = NextBestView(one_thread).Plan(in, nullptr);
  const NextBestViewResult r3 = NextBestView(three_threads).Plan(in, nullptr);
  const NextBestViewResult again = nbv.Plan(in, nullptr);
  EXPECT_EQ(r1.best_index, r3.best_index);
  for (std::size_t j = 0; j < r.candidates.size(); ++j) {
    EXPECT_EQ(again.candidates[j].gain.gain, r.candidates[j].gain.gain);
    EXPECT_EQ(r1.candidates[j].gain.gain, r.candidates[j].gain.gain);
    EXPECT_EQ(r3.candidates[j].gain.gain, r.candidates[j].gain.gain);
  }
}

TEST(NextBestViewTest, RejectsBadInput) {
  NextBestView nbv{NextBestViewOptions()};
  const Points empty;
  NextBestViewInput in;
  in.gamma_points_world = &empty;
  EXPECT_THROW(nbv.Plan(in, nullptr), InputError);
  const Points one = {Eigen::Vector3f(0, 0, 0.5f)};
  in.gamma_points_world = &one;
  in.models.assign(16, ModelHypothesis{1, 0.5, &one});
  EXPECT_THROW(nbv.Plan(in, nullptr), InputError);
  in.models.assign(1, ModelHypothesis{1, 0.5, nullptr});
  EXPECT_THROW(nbv.Plan(in, nullptr), InputError);
  const Points nan = {Eigen::Vector3f(NAN, 0, 0)};
  in.models.assign(1, ModelHypothesis{1, 0.5, &nan});
  EXPECT_THROW(nbv.Plan(in, nullptr), InputError);
  NextBestViewOptions bad;
  bad.voxel_size_m = 0.0;
  EXPECT_THROW(NextBestView{bad}, ConfigError);
}

}  // namespace
}  // namespace objscan::planning
