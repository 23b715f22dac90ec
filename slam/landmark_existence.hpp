#pragma once
// A landmark's existence as Wald's sequential probability ratio test (Wald 1945; the
// track confirmation of Blackman & Popoli 1999, "Design and Analysis of Modern Tracking
// Systems", Sec. 6.2). Each scan in which the landmark is predicted in view is one
// Bernoulli trial under two hypotheses:
//   H1 "real": detected with P_D (the rate measured at its range) and then inside its gate
//              with the gate's probability P_G = P[chi2(2) < gate_accept];
//   H0 "phantom" (it was clutter): its gate holds at least one clutter detection with
//              1 - exp(-mu), mu the clutter expected in the gate (ExpectedFalseInGate).
// The log likelihood ratio of the trials is summed; the landmark is confirmed when the sum
// reaches log((1 - beta) / alpha) and deleted when it falls to log(beta / (1 - alpha))
// (Wald's bounds: alpha the probability of confirming a phantom, beta of deleting a real
// landmark). Without clutter a pairing cannot come from a phantom: one re-sighting
// confirms, and misses then take very long to delete it.
#include <Eigen/Core>

#include "core/params.hpp"

namespace slambox {

/// Unknown ids: how a landmark is confirmed and removed. Sequential test: Wald's SPRT of
/// "real, seen with the measured P_D" against "clutter reappearing in its gate" (below);
/// counts: +1 per sighting, -1 (or P_D) per miss in view, as each module documents.
enum class ExistenceRule { kSequentialTest, kCounts };
/// sprt, counts.
const EnumNames<ExistenceRule>& ExistenceRuleNames();

struct WaldThresholds {
  double log_confirm = 0.0;  ///< accept H1 at or above (log units)
  double log_delete = 0.0;   ///< accept H0 at or below
};

/// Wald's approximate bounds for error probabilities alpha (false confirm) and beta
/// (false delete), both in (0, 0.5).
WaldThresholds MakeWaldThresholds(double alpha, double beta);

/// Largest |log likelihood ratio| of one trial: keeps sums finite when a hypothesis makes
/// the outcome impossible (no clutter: mu = 0), far beyond any threshold of a probability.
constexpr double kMaxTrialLogRatio = 50.0;

/// Expected number of points of a field of spatial density `density_per_m2` inside the
/// gate d^2 < gate_chi2 of a planar Gaussian with covariance C: the gate is an ellipse of
/// area pi gate_chi2 sqrt(det C).
double ExpectedInGate(const Eigen::Matrix2d& C, double gate_chi2, double density_per_m2);

/// Expected number of false detections (spatial density `density_per_m2`) inside the gate
/// d^2 < gate_chi2 of a predicted observation at `range_m` with innovation covariance S:
/// the gate is an ellipse of area pi gate_chi2 sqrt(det S) in (range, bearing) and, as
/// dx dy = r dr dbearing, r times that in the plane.
double ExpectedFalseInGate(const Eigen::Matrix2d& S, double range_m, double gate_chi2, double density_per_m2);

/// log P[paired in its gate | real] / P[paired | phantom] = log(P_D P_G / (1 - exp(-mu))).
double DetectedLogRatio(double p_detect, double p_gate, double mu);
/// log P[not paired | real] / P[not paired | phantom] = log((1 - P_D P_G) / exp(-mu)).
double MissedLogRatio(double p_detect, double p_gate, double mu);

/// log prior odds that a detection no landmark explains is a new real landmark: of the
/// `births` detections that started a landmark in `scans` scans, clutter_per_scan per scan
/// are expected to be clutter (the gates of mapped landmarks take a negligible share of
/// the footprint). Laplace's rule keeps the fraction inside (0, 1): a stream of clutter
/// only drives the odds towards 0.
double NewLandmarkPriorLogRatio(double births, double scans, double clutter_per_scan);

/// [1/m^2] The density of landmarks not mapped yet, per scan: of the `births` (detections
/// that started a landmark) in `scans` scans, less the clutter_per_scan expected per scan
/// among them, per scan over the detector's footprint r_max^2 half_fov. `prior_scans`
/// pseudo-scans with one birth each come first (Laplace's rule: the density stays positive
/// before the first birth and decays as the map stops growing; 0 for none).
double UnmappedLandmarkDensity(double births, double scans, double clutter_per_scan, double footprint_m2,
                               double prior_scans);

}  // namespace slambox
