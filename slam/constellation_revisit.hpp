#pragma once
// A revisit found by its constellation, for any filter that maps landmarks in one frame
// (ekf-slam: slam/ekf_slam_constellation.cpp; fastslam: slam/fastslam_constellation.cpp).
// After drift a filter maps a revisited place a second time: the confirmed landmarks it
// created within the last 2, 4 or 8 range_max of travel (`recent`) are matched as one rigid
// shape (slam/constellation_match.hpp) onto the confirmed landmarks last seen before that
// window (`old`). The windows widen until one decides: a footprint swept once holds few
// landmarks (`forest`: about 5), too few to rise above the chance of the motions tried.
//
// Two priors make the search a test rather than a guess. (1) The filter's heading has
// drifted from the old landmarks' frame since it last saw them by no more than dead
// reckoning's would have: the motion model's heading variance summed over the steps since
// the earliest of them was seen bounds the rotation to its gate, and that heading error over
// the travel since then, d, bounds how far the match may move the robot: variance
// sigma_theta^2 d^2 (the whole drift as one heading error at the start, an overestimate of a
// random walk's d^2 / 3), within the same gate probability with 2 dof; a lattice of landmarks
// (an orchard, a warehouse's reflectors) otherwise fits the newly explored part of itself onto
// the old one shifted by whole rows (tests/slam/fastslam_module_test.cpp's 4 m grid: fastslam2
// 0.1 m -> 9.6 m on 5 of 10 seeds). (2) Old landmarks that the
// match puts in view of the window's scans should have been mapped again there: if they
// were missed with a probability below the false-match one (the product of 1 - P_D over
// every such scan), the match is refused (LogMissedUnderRevisit).
//
// The match is the drift accrued since the old landmarks were seen. What the filter mapped in
// between carries part of it: each such landmark takes the share of the motion that dead
// reckoning's heading variance had accrued by its last sighting (RevisitShares, PartOfMotion),
// and the missed-landmarks rule expects it where that share leaves it.
#include <Eigen/Core>
#include <functional>
#include <optional>
#include <span>
#include <vector>

#include "core/se2.hpp"
#include "slam/constellation_match.hpp"

namespace slambox {

/// One confirmed landmark as the search sees it.
struct RevisitLandmark {
  Eigen::Vector2d xy = Eigen::Vector2d::Zero();  ///< [m] mean in the map frame
  double created_travel_m = 0;                   ///< [m] the robot's travel when it was created
  double seen_travel_m = 0;                      ///< [m] the robot's travel when it was last seen
  double seen_heading_variance_rad2 = 0;         ///< [rad^2] dead reckoning's heading variance summed until then
};

struct RevisitSettings {
  double travel_m = 0;               ///< [m] the robot's travel so far
  double heading_variance_rad2 = 0;  ///< [rad^2] the motion model's heading variance summed over every step so far
  Eigen::Vector2d robot_xy = Eigen::Vector2d::Zero();  ///< [m] the robot's position in the map frame now
  double range_max_m = 15;           ///< [m] the detector's range: the windows are multiples of it
  double tolerance_m = 1;            ///< [m] ConstellationSettings::tolerance_m (RevisitTolerance)
  double gate_probability = 0.99;    ///< the heading gate's probability; 1 - it is the false-match probability
  long max_hypotheses = 0;           ///< ConstellationSettings::max_hypotheses, over all windows together
};

struct Revisit {
  ConstellationMatch match;     ///< pairs index `old` and `recent` below
  std::vector<int> old, recent; ///< indices into the landmarks searched
  double window_m = 0;          ///< [m] the window of travel that decided
};

/// [m] a recent landmark supports a motion within this of an old one: two estimates of one
/// landmark differ by about two detections' noise, so the gate's radius (d^2 = gate_chi2) for
/// the difference of two detections at range_max, along the worse of range and bearing.
double RevisitTolerance(const Eigen::Matrix2d& R, double range_max_m, double gate_chi2);

/// The widest window of travel [m] the search reads (scan poses older than this are unused).
double RevisitWidestWindow(double range_max_m);

/// True when some landmark created within the widest window is not in `searched` (the recent
/// landmarks of the last search, replaced by this call's): a match needs it as a supporter.
bool RevisitWorthSearching(std::span<const RevisitLandmark> confirmed, std::span<const int> keys,
                           const RevisitSettings& settings, std::vector<int>& searched);

/// The first window whose match passes (1) and MatchConstellation's own rules, or none.
std::optional<Revisit> FindRevisit(std::span<const RevisitLandmark> confirmed, const RevisitSettings& settings);

/// The share in [0, 1] of the revisit's motion that each of `revisit.old` takes (0 for the
/// paired ones). The motion is the drift accrued since the paired old landmarks were seen; an
/// old landmark mapped during that drift (seen later than they were) carries the part accrued
/// until its own sighting. Dead reckoning's heading variance measures how far along: the
/// share is (v - v_paired) / (v_now - v_paired), v its `seen_heading_variance_rad2`, v_paired
/// the paired ones' largest, v_now `settings.heading_variance_rad2`; clipped to [0, 1]. This
/// is how pose-graph relaxation spreads a loop's rotational error (in proportion to the
/// covariance along the path): without it the map drawn during the drift stays where the
/// drift put it and the rest of the lap follows it again.
std::vector<double> RevisitShares(const Revisit& revisit, std::span<const RevisitLandmark> confirmed,
                                  const RevisitSettings& settings);

/// One landmark's share: (v - v_paired) / (v_now - v_paired) clipped to [0, 1] (0 if v_now <= v_paired).
double RevisitShare(double v_rad2, double paired_rad2, double now_rad2);

/// `share` of motion T along its screw (Exp(share Log T)): the identity at 0, T at 1.
SE2 PartOfMotion(const SE2& T, double share);

/// log P[the old landmarks the match puts in view were all missed]: for each old landmark the
/// match did not pair and that no window landmark (`window_xy`: every landmark not old,
/// tentative ones too) lies within tolerance of, sum log(1 - P_D(z)) over the window's scan
/// poses (`scan_poses`) that would see it at z. `detection_in_view(z)` is P_D at the predicted
/// (range, bearing) z, 0 outside the field of view. An old landmark that the correction moves
/// by its share of T (`shares`, per `revisit.old`, RevisitShares; empty: none moves) is
/// expected where that leaves it: one mapped during the drift (after a lap the old map holds
/// the drifted copy of the place where the lap ended) moves with the window, not with the
/// old map.
double LogMissedUnderRevisit(const Revisit& revisit, std::span<const RevisitLandmark> confirmed,
                             std::span<const Eigen::Vector2d> window_xy, std::span<const SE2> scan_poses,
                             double tolerance_m, std::span<const double> shares,
                             const std::function<double(const Eigen::Vector2d&)>& detection_in_view);

}  // namespace slambox
