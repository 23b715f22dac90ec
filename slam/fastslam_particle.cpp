#include "slam/fastslam_particle.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <tuple>

#include "slam/fastslam_closure.hpp"
#include "slam/landmark_ekf.hpp"
#include "slam/particle_weights.hpp"
#include "slam/range_bearing.hpp"

namespace slambox {

namespace {

constexpr int kNewLandmark = -1;
constexpr int kIgnored = -2;  // clutter in known-id mode

struct Association {
  std::vector<int> key;         // per observation: a landmark key, kNewLandmark or kIgnored
  std::vector<int> candidates;  // landmarks in range before the update (for the counters)
  std::vector<double> log_p0;   // per observation (unknown ids): log p0 at its range
  std::vector<PredictedMeasurement> predicted;  // per candidate, before the update (existence test)
};

// Maximum-likelihood correspondences, mutually exclusive within a scan: pairs are taken
// greedily from the most likely down; an observation whose every likelihood is below p0
// (or whose candidates were all taken) starts a new landmark (Thrun 13.2, lines 7-16).
Association Associate(const FastSlamParticle& p, const std::vector<Eigen::Vector2d>& z,
                      const std::vector<LandmarkObservation>& scan, const ParticleUpdateOptions& o) {
  Association a;
  a.key.assign(scan.size(), kNewLandmark);
  if (o.known_ids) {
    for (size_t j = 0; j < scan.size(); ++j)
      if (scan[j].id < 0) a.key[j] = kIgnored;
      else if (FindLandmark(p.map, scan[j].id)) a.key[j] = scan[j].id;
    return a;
  }
  const double reach = o.range_max_m + o.candidate_margin_m;
  const Eigen::Vector2d t = p.pose.translation();
  a.candidates = LandmarksInBox(p.map, (t.array() - reach).matrix(), (t.array() + reach).matrix());
  a.log_p0.resize(z.size());
  for (size_t j = 0; j < z.size(); ++j) a.log_p0[j] = o.LogP0(z[j].x());
  std::vector<std::tuple<double, int, int>> pairs;  // (-log-likelihood, observation, candidate)
  // The score of z against a landmark: log N(z; h, Q) at the particle's pose (1.0, zero
  // pose covariance), or the predictive likelihood over the proposal prior (2.0,
  // Montemerlo 2003).
  const PoseProposal prior{p.pose, p.pose_covariance};
  a.predicted.reserve(a.candidates.size());
  for (size_t c = 0; c < a.candidates.size(); ++c) {
    const PredictedMeasurement& predicted =
        a.predicted.emplace_back(PredictMeasurement(prior, *FindLandmark(p.map, a.candidates[c]), o.R));
    for (size_t j = 0; j < z.size(); ++j) {
      const double ll = LogLikelihood(predicted, z[j]);
      if (ll >= a.log_p0[j]) pairs.emplace_back(-ll, static_cast<int>(j), static_cast<int>(c));
    }
  }
  std::sort(pairs.begin(), pairs.end());
  std::vector<char> taken(a.candidates.size(), 0);
  std::vector<char> done(z.size(), 0);
  for (const auto& [neg_ll, j, c] : pairs) {
    if (done[j] || taken[c]) continue;
    done[j] = taken[c] = 1;
    a.key[j] = a.candidates[c];
  }
  return a;
}

// One trial of the sequential existence test for a landmark predicted at `predicted` (range
// r): its gate is where N(z; z_hat, L) >= p0, d^2 <= g = 2 (log N(z_hat; z_hat, L) - log p0),
// which holds a real detection with P_G = P[chi2(2) <= g] and mu clutter detections
// (ExpectedFalseInGate).
double ExistenceTrial(const PredictedMeasurement& predicted, bool detected, const ParticleUpdateOptions& o) {
  const double r = predicted.z_hat.x();
  const double g = std::max(0.0, 2.0 * (predicted.log_normalizer - o.LogP0(r)));
  const double p_gate = -std::expm1(-0.5 * g);  // the chi-square CDF with 2 dof
  const double mu =
      ExpectedFalseInGate(predicted.L_inverse.inverse(), std::max(r, 0.0), g, o.clutter_density_per_m2);
  const double p_detect = DetectionProbability(o.detection, r);
  return detected ? DetectedLogRatio(p_detect, p_gate, mu) : MissedLogRatio(p_detect, p_gate, mu);
}

// Thrun 13.2 lines 25-31: a landmark in range that should have been seen but was not
// loses one count (with an estimated detection rate: the detection that was expected at
// its range, P_D(r)); below zero it is discarded. A confirmed landmark last seen more than
// keep_confirmed_unseen_m of travel ago stops at the confirmation count: it stays mapped.
// With the sequential test (ExistenceRule) each candidate seen adds a trial's log ratio
// wherever it was, each one in view and not seen a miss's, and it is discarded at Wald's
// lower bound. With the rate, confirmed
// landmarks in view are listed in `expected` with whether they were seen, to estimate it.
int ApplyExistence(FastSlamParticle& p, const Association& a, const ParticleUpdateOptions& o,
                   std::vector<std::pair<double, bool>>& expected) {
  std::vector<int> matched;
  for (int k : a.key)
    if (k >= 0) matched.push_back(k);
  std::sort(matched.begin(), matched.end());
  const bool sprt = o.existence == ExistenceRule::kSequentialTest;
  int discarded = 0;
  for (size_t c = 0; c < a.candidates.size(); ++c) {
    const int key = a.candidates[c];
    const bool seen = std::binary_search(matched.begin(), matched.end(), key);
    LandmarkGaussian lm = *FindLandmark(p.map, key);
    const Eigen::Vector2d z = PredictObservation(p.pose, lm.mean).z;
    const bool in_view = z.x() <= o.range_max_m - o.visibility_margin_m && std::abs(z.y()) <= o.half_fov_rad;
    // Confirmed landmarks in view measure the rate: confirmed before this scan (its
    // sighting has already added its count; the test's trial comes below).
    if (in_view && o.estimate_detection_rate) {
      LandmarkGaussian before = lm;
      before.counter -= seen ? 1.0 : 0.0;
      if (o.Confirmed(before)) expected.emplace_back(z.x(), seen);
    }
    if (sprt) {
      if (!seen && !in_view) continue;
      lm.log_ratio += ExistenceTrial(a.predicted[c], seen, o);
      if (lm.log_ratio <= o.wald.log_delete) {
        EraseLandmark(p.map, key);
        ++discarded;
      } else {
        SetLandmark(p.map, key, lm);
      }
      continue;
    }
    if (!in_view || seen) continue;
    const bool kept = o.Confirmed(lm) && o.travel_m - lm.seen_travel_m > o.keep_confirmed_unseen_m;
    lm.counter -= o.estimate_detection_rate ? DetectionProbability(o.detection, z.x()) : 1.0;
    if (kept) lm.counter = std::max(lm.counter, o.confirmed_counter);
    if (lm.counter < 0) {
      EraseLandmark(p.map, key);
      ++discarded;
    } else {
      SetLandmark(p.map, key, lm);
    }
  }
  return discarded;
}

}  // namespace

ParticleUpdateSummary UpdateParticle(FastSlamParticle& p, const std::vector<LandmarkObservation>& scan,
                                     const ParticleUpdateOptions& o, std::mt19937_64& rng) {
  std::vector<Eigen::Vector2d> z;
  z.reserve(scan.size());
  for (const auto& obs : scan) z.emplace_back(obs.range_m, obs.bearing_rad);
  const Association a = Associate(p, z, scan, o);
  ParticleUpdateSummary s;
  s.landmark_of.assign(scan.size(), -1);
  s.creates.assign(scan.size(), 0);
  if (std::isfinite(o.closure_old_after_m)) s.closure = CorrectClosure(p, a.key, z, o).has_value();

  if (o.fastslam2) {  // sample the pose from the proposal that includes the observations
    PoseProposal proposal{p.pose, p.pose_covariance};
    for (size_t j = 0; j < z.size(); ++j)
      if (a.key[j] >= 0) s.log_weight_factor += ConditionProposal(proposal, *FindLandmark(p.map, a.key[j]), z[j], o.R);
    p.pose = SE2::FromVector(SampleGaussian(proposal.mean.vector(), proposal.covariance, rng));
    p.pose_covariance.setZero();
  }
  for (size_t j = 0; j < z.size(); ++j) {
    const int key = a.key[j];
    if (key == kIgnored) continue;
    if (key >= 0) {  // EKF update of the matched landmark at the (sampled) pose
      const LandmarkGaussian& lm = *FindLandmark(p.map, key);
      const LandmarkMeasurement m = MeasureLandmark(p.pose, lm, z[j], o.R);
      if (!o.fastslam2) s.log_weight_factor += m.log_likelihood;
      LandmarkGaussian updated = UpdateLandmark(lm, m);
      ++updated.counter;
      updated.seen_travel_m = o.travel_m;
      updated.seen_heading_variance_rad2 = o.heading_variance_rad2;
      SetLandmark(p.map, key, updated);
      s.landmark_of[j] = key;
      ++s.matched;
    } else {  // a new landmark: w_{N+1} = p0 (constant over particles with known ids)
      const int new_key = o.known_ids ? scan[j].id : p.next_key++;
      LandmarkGaussian created = InitializeLandmark(p.pose, z[j], o.R);
      created.log_ratio = o.new_log_ratio;
      created.created_travel_m = created.seen_travel_m = o.travel_m;
      created.seen_heading_variance_rad2 = o.heading_variance_rad2;
      SetLandmark(p.map, new_key, created);
      s.landmark_of[j] = new_key;
      s.creates[j] = 1;
      if (!o.known_ids) s.log_weight_factor += a.log_p0[j];
      ++s.created;
    }
  }
  if (!o.known_ids) s.discarded = ApplyExistence(p, a, o, s.expected);
  return s;
}

}  // namespace slambox
