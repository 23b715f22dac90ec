#pragma once
// Detections the front end left out that the smoothed map explains (issue 14, `forest`).
// The EKF front end leaves a detection unassigned while it holds an uncertain pairing (at a
// loop closure: forest seed 4 at clutter 0.5 loses ~200 detections in scans 900-1100), and
// the graph drops the detections of tentative landmarks it later deleted. Once the smoother
// has merged its landmarks, each such detection z at keyframe k is tested against the
// landmarks of the final graph:
// 1. a loose gate with the smoother's marginals, S = J_pose P_k J_pose^T + J_m P_m J_m^T + R
//    (the pose-landmark cross-covariance left out: the marginals far from the anchor are
//    wide, their difference is not, so this gate is wider than the true one), d^2 < gate;
// 2. for those, the gate that matters, by dead reckoning from the keyframe k1 nearest to k
//    that observes m (slam/reobservation_split.hpp, DeadReckoned: the odometry between k1
//    and k, two observations' noise) — how the front end would have seen it at k1, so an
//    upper bound on the relative uncertainty, never the absolute one.
// z joins m when m is the only landmark inside gate 2, m is seen from two keyframes or more
// (graphslam drops a split-off segment seen from one), m is not observed at k already, no
// other leftover detection of k chose m, and m's gate expects fewer detections nothing mapped
// explains than the gate's miss probability: mu < fake_probability, mu the larger of
// density pi gate sqrt(det C) (clutter and unmapped landmarks at `fake_density_per_m2`) and
// the leftovers of the whole run that fell inside that gate relative to the sensor, per
// keyframe (an empirical rate: a stream may declare less clutter than it has, or clutter
// that is not uniform over the footprint). No new constant: gate, threshold and density are
// the front end's.
#include <Eigen/Core>
#include <vector>

#include "slam/landmark_graph.hpp"

namespace slambox {

struct LeftoverDetection {
  int keyframe = 0;
  Eigen::Vector2d z = Eigen::Vector2d::Zero();  ///< (range [m], bearing [rad])
};

struct LeftoverSettings {
  double gate_chi2 = 9.21;           ///< [chi2, 2 dof] the front end's acceptance gate
  double fake_probability = 0.01;    ///< [-] the gate's miss probability
  double fake_density_per_m2 = 0.0;  ///< [1/m^2] clutter plus unmapped landmarks
};

/// Per detection, the key of the landmark of `graph` it joins, or -1 (see above). Needs
/// s.covariance_ok (else none joins).
std::vector<int> AssociateLeftovers(const LandmarkGraph& graph, const LandmarkGraphSolution& s,
                                    const std::vector<LeftoverDetection>& detections, const LeftoverSettings& settings);

}  // namespace slambox
