// Closed-form ICP steps against independent numerical minimizers, and angle wrap at ±pi.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>

#include "slam/icp_closed_form.hpp"
#include "slam/icp_target.hpp"

namespace slambox {
namespace {

struct Problem {
  std::vector<Eigen::Vector2d> source, target, normals;
  std::vector<double> weights;
};

Problem MakeProblem(const SE2& T, double noise_m, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-5, 5), w(0.2, 2.0), ang(-M_PI, M_PI);
  std::normal_distribution<double> n(0, noise_m);
  Problem p;
  for (int i = 0; i < 40; ++i) {
    const Eigen::Vector2d s(u(rng), u(rng));
    p.source.push_back(s);
    p.target.push_back(T * s + Eigen::Vector2d(n(rng), n(rng)));
    const double a = ang(rng);
    p.normals.emplace_back(std::cos(a), std::sin(a));
    p.weights.push_back(w(rng));
  }
  return p;
}

double CostP2P(const Problem& p, const SE2& T) {
  double c = 0;
  for (size_t i = 0; i < p.source.size(); ++i) c += p.weights[i] * (T * p.source[i] - p.target[i]).squaredNorm();
  return c;
}
double CostP2L(const Problem& p, const SE2& T) {
  double c = 0;
  for (size_t i = 0; i < p.source.size(); ++i) {
    const double e = p.normals[i].dot(T * p.source[i] - p.target[i]);
    c += p.weights[i] * e * e;
  }
  return c;
}

// Oracle: dense scan over theta with the exact optimal translation for each theta, then
// golden-section refinement. Independent of the SVD.
SE2 BruteForceP2P(const Problem& p) {
  auto best_t = [&](double th) {
    double ws = 0;
    Eigen::Vector2d ms = Eigen::Vector2d::Zero(), mt = Eigen::Vector2d::Zero();
    for (size_t i = 0; i < p.source.size(); ++i) ws += p.weights[i], ms += p.weights[i] * p.source[i],
                                                   mt += p.weights[i] * p.target[i];
    const Eigen::Vector2d t = mt / ws - RotationMatrix(th) * ms / ws;
    return SE2(t.x(), t.y(), th);
  };
  double th0 = 0, c0 = 1e300;
  for (int k = 0; k < 3600; ++k) {
    const double th = -M_PI + k * 2 * M_PI / 3600;
    const double c = CostP2P(p, best_t(th));
    if (c < c0) c0 = c, th0 = th;
  }
  double a = th0 - 0.01, b = th0 + 0.01;
  for (int it = 0; it < 100; ++it) {
    const double m1 = a + (b - a) * 0.382, m2 = a + (b - a) * 0.618;
    if (CostP2P(p, best_t(m1)) < CostP2P(p, best_t(m2))) b = m2;
    else a = m1;
  }
  return best_t(0.5 * (a + b));
}

// Oracle: Gauss-Newton on the point-to-line cost, iterated to convergence from T0.
SE2 GaussNewtonP2L(const Problem& p, SE2 T) {
  for (int it = 0; it < 100; ++it) {
    Eigen::Matrix3d H = Eigen::Matrix3d::Zero();
    Eigen::Vector3d g = Eigen::Vector3d::Zero();
    for (size_t i = 0; i < p.source.size(); ++i) {
      const Eigen::Vector2d rs = T.rotation() * p.source[i];
      const Eigen::Vector2d& n = p.normals[i];
      const Eigen::Vector3d J(n.x(), n.y(), n.dot(Eigen::Vector2d(-rs.y(), rs.x())));
      const double e = n.dot(T * p.source[i] - p.target[i]);
      H += p.weights[i] * J * J.transpose();
      g += p.weights[i] * J * e;
    }
    const Eigen::Vector3d dx = -H.ldlt().solve(g);
    T = SE2(T.x + dx.x(), T.y + dx.y(), T.theta + dx.z());
    if (dx.norm() < 1e-14) break;
  }
  return T;
}

TEST(IcpClosedForm, PointToPointMatchesBruteForce) {
  for (std::uint64_t seed = 0; seed < 5; ++seed) {
    const SE2 T_true(0.3 * seed - 0.5, 1.0 - 0.2 * seed, -2.5 + 1.2 * seed);
    const Problem p = MakeProblem(T_true, 0.05, seed);
    const SE2 T = AlignPointToPoint(p.source, p.target, p.weights);
    const SE2 B = BruteForceP2P(p);
    EXPECT_NEAR(T.x, B.x, 1e-6);
    EXPECT_NEAR(T.y, B.y, 1e-6);
    EXPECT_NEAR(NormalizeAngle(T.theta - B.theta), 0.0, 1e-6);
    EXPECT_LE(CostP2P(p, T), CostP2P(p, B) + 1e-9);
  }
}

TEST(IcpClosedForm, PointToPointExactOnCleanDataAcrossAngleWrap) {
  for (double th : {M_PI - 1e-3, -M_PI + 1e-3, -M_PI, 3.0, -3.0}) {
    const SE2 T_true(1.5, -0.7, th);
    const Problem p = MakeProblem(T_true, 0.0, 7);
    const SE2 T = AlignPointToPoint(p.source, p.target, p.weights);
    EXPECT_NEAR(T.x, T_true.x, 1e-9);
    EXPECT_NEAR(T.y, T_true.y, 1e-9);
    EXPECT_NEAR(NormalizeAngle(T.theta - T_true.theta), 0.0, 1e-9) << th;
  }
}

TEST(IcpClosedForm, PointToPointNeverReturnsAReflection) {
  // Target is the mirror image of the source: the unguarded SVD answer is a reflection.
  Problem p = MakeProblem(SE2(), 0.0, 3);
  for (auto& t : p.target) t.x() = -t.x();
  const SE2 T = AlignPointToPoint(p.source, p.target, p.weights);
  const SE2 B = BruteForceP2P(p);  // best proper rotation
  EXPECT_NEAR(CostP2P(p, T), CostP2P(p, B), 1e-6 * CostP2P(p, B));
}

TEST(IcpClosedForm, PointToLineMatchesGaussNewton) {
  for (std::uint64_t seed = 0; seed < 5; ++seed) {
    const SE2 T_true(0.2 * seed, -0.3, 0.4 - 0.15 * seed);
    const Problem p = MakeProblem(T_true, 0.02, 10 + seed);
    const SE2 start(T_true.x + 0.1, T_true.y - 0.1, T_true.theta + 0.05);
    const SE2 T = AlignPointToLine(p.source, p.target, p.normals, p.weights, start);
    const SE2 G = GaussNewtonP2L(p, T_true);
    EXPECT_NEAR(T.x, G.x, 1e-7);
    EXPECT_NEAR(T.y, G.y, 1e-7);
    EXPECT_NEAR(NormalizeAngle(T.theta - G.theta), 0.0, 1e-8);
    EXPECT_LE(CostP2L(p, T), CostP2L(p, G) * (1 + 1e-9) + 1e-15);
  }
}

TEST(IcpClosedForm, PointToLineIsGlobalAcrossAngleWrap) {
  // The exact step needs no good start: from theta = 0 it finds a rotation near ±pi.
  for (double th : {M_PI - 1e-3, -M_PI + 2e-3, 2.9, -2.9}) {
    const SE2 T_true(-0.4, 0.9, th);
    const Problem p = MakeProblem(T_true, 0.0, 21);
    const SE2 T = AlignPointToLine(p.source, p.target, p.normals, p.weights, SE2());
    EXPECT_NEAR(T.x, T_true.x, 1e-7);
    EXPECT_NEAR(T.y, T_true.y, 1e-7);
    EXPECT_NEAR(NormalizeAngle(T.theta - T_true.theta), 0.0, 1e-8) << th;
  }
}

TEST(IcpClosedForm, PointToLineKeepsUnconstrainedTranslation) {
  // All normals along y: x is unobservable and must stay at the current value.
  Problem p = MakeProblem(SE2(0.5, 0.2, 0.0), 0.0, 5);
  for (auto& n : p.normals) n = Eigen::Vector2d(0, 1);
  const SE2 T = AlignPointToLine(p.source, p.target, p.normals, p.weights, SE2(-1.25, 0.0, 0.0));
  EXPECT_NEAR(T.x, -1.25, 1e-9);
  EXPECT_NEAR(T.y, 0.2, 1e-6);
}

TEST(IcpClosedForm, FitNormalOfALine) {
  std::vector<Eigen::Vector2d> pts;
  for (int i = 0; i < 5; ++i) pts.emplace_back(1.0 + i * 0.1 * std::cos(0.3), 2.0 + i * 0.1 * std::sin(0.3));
  const Eigen::Vector2d n = FitNormal(pts.data(), 5);
  EXPECT_NEAR(std::abs(n.dot(Eigen::Vector2d(-std::sin(0.3), std::cos(0.3)))), 1.0, 1e-12);
  EXPECT_EQ(FitNormal(pts.data(), 1), Eigen::Vector2d::Zero());
}

}  // namespace
}  // namespace slambox
