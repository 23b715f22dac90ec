#pragma once
// Place recognition from landmark constellations (issue 14). After drift a filter maps a
// revisited place a second time: its new landmarks (`recent`) are old ones (`old`) moved by
// one rigid motion, the robot's drift, up to the estimates' local error. Individual gates
// cannot see it (the drift exceeds them, or several old landmarks lie in each gate); the
// shape can. Every pair of recent landmarks and every pair of old ones of the same length
// (within 2 tol) define a motion, a hypothesis; its support is the recent landmarks it brings
// within tol of an old one (each old one taken once, the nearest first).
//
// How often a wrong motion gathers k supporters: its two seeds coincide by construction; each
// of the other n - 2 recent landmarks lands within tol of some old landmark with
// p = 1 - exp(-rho pi tol^2) (rho the old landmarks' density, MapDensity), independently, so
// P_k = P[Binomial(n - 2, p) >= k - 2]. Over the H hypotheses of one search (union bound) the
// best one's chance is at most H P_k. The best hypothesis (most support, then the smallest
// residual) is accepted when that chance is below `false_match_probability` and no other
// hypothesis that passes pairs one of its landmarks differently (a repeated pattern: two
// places fit, so neither is known). A prior bound on the rotation (the drift's) removes the
// motions beyond it from the hypotheses and from H, and so does a bound on how far the motion
// moves the robot (max_anchor_shift_m). The bound is a union bound under
// independence: a park whose landmarks are not Poisson scattered (rows, clusters) and a
// tolerance near their spacing make a wrong match likelier than it says (held-out park
// lm3_0: 16 of 23 landmarks fitted a motion turning by 134 degrees, at a bound of 0.008).
#include <Eigen/Core>
#include <cmath>
#include <limits>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "core/se2.hpp"

namespace slambox {

struct ConstellationSettings {
  double tolerance_m = 1.0;               ///< [m] a recent landmark supports a motion within this of an old one
  double false_match_probability = 0.01;  ///< accept a match less likely than this to arise by chance
  long earlier_hypotheses = 0;            ///< hypotheses of earlier searches on the same data (counted in the union bound)
  double max_rotation_rad = M_PI;         ///< [rad] motions turning by more are not hypotheses (a prior bound on the drift)
  long max_hypotheses = 0;                ///< search budget: more hypotheses than this (earlier ones included) and none is tried (0 = no limit)
  /// [m] motions that move `anchor_xy` (the robot) by more are not hypotheses either: the
  /// drift's prior bound at the robot (infinity: none).
  double max_anchor_shift_m = std::numeric_limits<double>::infinity();
  Eigen::Vector2d anchor_xy = Eigen::Vector2d::Zero();  ///< [m] where max_anchor_shift_m is measured
};

struct ConstellationMatch {
  SE2 T_old_recent;                       ///< the motion, least squares over the support: old ~ T * recent
  std::vector<std::pair<int, int>> pairs; ///< (old index, recent index) of its support
  double chance = 1.0;                    ///< H P_k: the union bound above
  long hypotheses = 0;                    ///< H (earlier_hypotheses included)
};

/// P[Binomial(n, p) >= k] (1 for k <= 0, 0 for k > n).
double BinomialUpperTail(int n, double p, int k);

/// The accepted match of `recent` onto `old`, or none (fewer than 3 recent landmarks, no
/// hypothesis passes, two different motions pass, or H exceeds the budget); `hypotheses`, if
/// given, receives H (counted before the search).
std::optional<ConstellationMatch> MatchConstellation(std::span<const Eigen::Vector2d> old,
                                                     std::span<const Eigen::Vector2d> recent,
                                                     const ConstellationSettings& settings,
                                                     long* hypotheses = nullptr);

}  // namespace slambox
