// EM steps against closed-form least-squares fits (STYLE.md: check math against an independent
// computation).

#include "relplane/segmenter/em.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <random>

namespace relplane::segmenter {
namespace {

// The closed-form plane of a point set: centroid and smallest eigenvector of the scatter.
void ClosedFormFit(const std::vector<Eigen::Vector3d>& pts, Eigen::Vector3d* n, double* d) {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const auto& p : pts) mean += p;
  mean /= pts.size();
  Eigen::Matrix3d s = Eigen::Matrix3d::Zero();
  for (const auto& p : pts) s += (p - mean) * (p - mean).transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(s);
  *n = eig.eigenvectors().col(0);
  *d = -n->dot(mean);
}

double AngleDeg(const Eigen::Vector3d& a, const Eigen::Vector3f& b) {
  return std::acos(std::min(1.0, std::fabs(a.dot(b.cast<double>().normalized())))) * 180 / M_PI;
}

// Points on the plane through `origin` spanned by u, v with Gaussian noise along the normal.
std::vector<Eigen::Vector3d> Patch(Eigen::Vector3d origin, Eigen::Vector3d u, Eigen::Vector3d v,
                                   int count, double sigma, std::mt19937* rng) {
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  std::normal_distribution<double> noise(0.0, sigma);
  const Eigen::Vector3d n = u.cross(v).normalized();
  std::vector<Eigen::Vector3d> pts;
  for (int i = 0; i < count; ++i) {
    pts.push_back(origin + uni(*rng) * u + uni(*rng) * v + noise(*rng) * n);
  }
  return pts;
}

Cloud ToCloud(const std::vector<std::vector<Eigen::Vector3d>>& sets) {
  Cloud c;
  for (const auto& set : sets) {
    for (const auto& p : set) c.Add(p.cast<float>());
  }
  return c;
}

EmPlane Perturbed(Eigen::Vector3d n, double d, double tilt_rad, double shift) {
  const Eigen::Vector3d axis = n.unitOrthogonal();
  const Eigen::Vector3d tilted = Eigen::AngleAxisd(tilt_rad, axis) * n;
  EmPlane p;
  p.normal = tilted.cast<float>();
  p.d = static_cast<float>(d + shift);
  p.sigma = 0.02f;
  return p;
}

TEST(EStep, ResponsibilitiesSumToOneAndFavourTheNearPlane) {
  Cloud c;
  c.Add(1.0f, 0.0f, 0.0f);  // on plane x = 1
  c.Add(0.0f, 2.0f, 0.0f);  // on plane y = 2
  c.Add(5.0f, 5.0f, 5.0f);  // far from both: an outlier
  EmPlane a, b;
  a.normal = Eigen::Vector3f::UnitX();
  a.d = -1.0f;
  b.normal = Eigen::Vector3f::UnitY();
  b.d = -2.0f;
  Responsibilities r;
  EStep(c, {a, b}, Options{}, &r);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(r.At(0, i) + r.At(1, i) + r.Outlier(i), 1.0f, 1e-5);
  // On a plane: its Gaussian peak against the constant outlier density (the other plane is
  // beyond the cut-off).
  const float peak = 1.0f / (std::sqrt(2.0f * static_cast<float>(M_PI)) * a.sigma);
  const float on_plane = peak / (peak + Options{}.noise.outlier_density);
  EXPECT_NEAR(r.At(0, 0), on_plane, 1e-5);
  EXPECT_NEAR(r.At(1, 1), on_plane, 1e-5);
  EXPECT_GT(r.Outlier(2), 0.99f);
}

TEST(EStep, RangeNoiseWidensFarPoints) {
  Cloud c;
  c.Add(1.0f, 0.0f, 0.03f);  // 3 cm off the plane z = 0, 1 m away
  c.Add(4.0f, 0.0f, 0.03f);  // 3 cm off, 4 m away
  EmPlane floor;
  floor.sigma = 0.005f;
  Options o;
  o.noise.range_noise = 0.003f;  // 4.8 cm at 4 m
  Responsibilities r;
  EStep(c, {floor}, o, &r);
  EXPECT_GT(r.Outlier(0), 0.9f);  // 6 sigma at 1 m
  EXPECT_GT(r.At(0, 1), 0.8f);    // 0.6 sigma at 4 m
  EStep(c, {floor}, Options{}, &r);
  EXPECT_GT(r.Outlier(1), 0.9f);  // without range noise both are outliers
}

// RunEm stops refitting a converged plane and keeps its density row: evaluating only the planes
// that moved must give the responsibilities of evaluating them all.
TEST(EStep, ReevaluatingOnlyTheMovedPlanesGivesTheFullResult) {
  std::mt19937 rng(11);
  const auto floor = Patch({0.5, -2, -1}, {4, 0, 0}, {0, 4, 0}, 300, 0.01, &rng);
  const auto wall = Patch({4.5, -2, -1}, {0, 4, 0}, {0, 0, 2.5}, 300, 0.01, &rng);
  const Cloud c = ToCloud({floor, wall});
  Options o;
  o.noise.range_noise = 0.003f;
  std::vector<EmPlane> planes = {Perturbed({0, 0, 1}, 1.0, 0.02, 0.01),
                                 Perturbed({1, 0, 0}, -4.5, 0.02, 0.01)};
  Responsibilities partial, full;
  EStep(c, planes, o, &partial);
  planes[1] = Perturbed({1, 0, 0}, -4.5, -0.01, 0.0);  // only the wall moves
  const std::vector<uint8_t> moved = {0, 1};
  EStep(c, planes, o, &partial, &moved);
  EStep(c, planes, o, &full);
  ASSERT_EQ(partial.r.size(), full.r.size());
  for (size_t i = 0; i < full.r.size(); ++i) ASSERT_EQ(partial.r[i], full.r[i]) << i;
  // And an M-step that refits only the wall leaves the floor as it was, support updated.
  std::vector<EmPlane> refitted = planes;
  MStep(c, full, o, &refitted, &moved);
  EXPECT_EQ(refitted[0].normal, planes[0].normal);
  EXPECT_EQ(refitted[0].d, planes[0].d);
  EXPECT_GT(refitted[0].support, 250.0f);
  EXPECT_NE(refitted[1].d, planes[1].d);
}

TEST(RunEm, ConvergesToTheClosedFormFitOfOnePlaneAmongOutliers) {
  std::mt19937 rng(3);
  const auto plane = Patch({2, -1, -0.5}, {0, 2, 0.3}, {0.2, 0, 1.5}, 800, 0.005, &rng);
  std::vector<Eigen::Vector3d> clutter;
  std::uniform_real_distribution<double> uni(-3.0, 3.0);
  for (int i = 0; i < 100; ++i) {
    Eigen::Vector3d p(uni(rng) + 6, uni(rng), uni(rng));  // well behind the plane
    clutter.push_back(p);
  }
  Eigen::Vector3d n;
  double d;
  ClosedFormFit(plane, &n, &d);
  std::vector<EmPlane> planes = {Perturbed(n, d, 0.05, 0.02)};
  Responsibilities r;
  RunEm(ToCloud({plane, clutter}), Options{}, 50, &planes, &r);
  EXPECT_LT(AngleDeg(n, planes[0].normal), 0.05);
  EXPECT_NEAR(std::fabs(planes[0].d), std::fabs(d), 1e-3);
  EXPECT_NEAR(planes[0].sigma, 0.005, 0.001);  // learns the noise
  // Support is the sum of responsibilities: ~2-3% of each inlier goes to the outlier class.
  EXPECT_GT(planes[0].support, 0.95f * 800);
  EXPECT_LT(planes[0].support, 800.0f);
}

TEST(RunEm, SeparatesTwoCrossingPlanesIntoTheirOwnFits) {
  std::mt19937 rng(5);
  const auto floor = Patch({0.5, -2, -1}, {4, 0, 0}, {0, 4, 0}, 1500, 0.01, &rng);
  const auto wall = Patch({4.5, -2, -1}, {0, 4, 0}, {0, 0, 2.5}, 1500, 0.01, &rng);
  Eigen::Vector3d nf, nw;
  double df, dw;
  ClosedFormFit(floor, &nf, &df);
  ClosedFormFit(wall, &nw, &dw);
  std::vector<EmPlane> planes = {Perturbed(nf, df, 0.08, 0.05), Perturbed(nw, dw, -0.08, 0.05)};
  Responsibilities r;
  RunEm(ToCloud({floor, wall}), Options{}, 50, &planes, &r);
  // Only the corner strip is shared, so each plane stays within a small angle of its own fit.
  EXPECT_LT(AngleDeg(nf, planes[0].normal), 0.2);
  EXPECT_LT(AngleDeg(nw, planes[1].normal), 0.2);
  EXPECT_NEAR(std::fabs(planes[0].d), std::fabs(df), 0.005);
  EXPECT_NEAR(std::fabs(planes[1].d), std::fabs(dw), 0.005);
}

TEST(MStep, IsTheWeightedLeastSquaresFit) {
  std::mt19937 rng(9);
  const auto pts = Patch({1, 0, 0}, {0, 1, 0}, {0, 0, 1}, 200, 0.02, &rng);
  Cloud c = ToCloud({pts});
  // Hand-made weights: the closed-form fit of the points weighted 1 and 0 must come out.
  Responsibilities r;
  r.num_points = static_cast<int>(pts.size());
  r.num_planes = 1;
  r.r.assign(2 * pts.size(), 0.0f);
  r.range_variance.assign(pts.size(), 0.0f);
  std::vector<Eigen::Vector3d> chosen;
  for (size_t i = 0; i < pts.size(); ++i) {
    if (i % 3 == 0) continue;
    r.r[i] = 1.0f;
    chosen.push_back(pts[i]);
  }
  Eigen::Vector3d n;
  double d;
  ClosedFormFit(chosen, &n, &d);
  std::vector<EmPlane> planes(1);
  planes[0].normal = Eigen::Vector3f::UnitX();
  MStep(c, r, Options{}, &planes);
  EXPECT_LT(AngleDeg(n, planes[0].normal), 1e-3);
  EXPECT_NEAR(std::fabs(planes[0].d), std::fabs(d), 1e-5);
  EXPECT_FLOAT_EQ(planes[0].support, static_cast<float>(chosen.size()));
}

}  // namespace
}  // namespace relplane::segmenter
