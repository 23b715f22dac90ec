#pragma once
// `mrpt-ekf-slam`: MRPT 2.5's CRangeBearingKFSLAM2D (EKF over robot pose + 2D landmarks)
// as a peer of slambox's `ekf-slam`. Odometry between landmark events is composed into
// one CActionRobotMovement2D (Gaussian, Thrun-model covariance); each non-empty landmark
// event is one EKF step. Known ids are passed to MRPT; unknown ones go through MRPT's
// nearest-neighbour Mahalanobis data association.
//
// MRPT's filter starts at (0, 0, 0) with zero covariance and skips the prediction while
// its map is empty, so the module dead-reckons until the first landmark is seen and
// anchors MRPT's frame at that dead-reckoned pose (its covariance is then MRPT's, from
// zero). Between EKF steps the pose is propagated by odometry (P' = G P Gᵀ + V M Vᵀ).
//
// MRPT's EKF keeps every detection its association leaves unpaired as a landmark, clutter
// included, and a step's cost grows faster than n² in the landmarks: on a stream with
// clutter the map and the cost grow without bound (held-out park lm9_4, one clutter
// detection per scan at 10 Hz: 500 landmarks after 22 s of run time, 1000 after 352 s).
// Past `max_landmarks` the module stops with that reason, and the run records it as
// failed, instead of running for hours.
#include <memory>
#include <string>

#include "core/slam_module.hpp"

namespace slambox {

/// Unknown ids: MRPT's assocNN or assocJCBB.
enum class MrptDataAssociation { kNearestNeighbour, kJcbb };

struct MrptEkfSlamConfig {
  MrptDataAssociation data_association = MrptDataAssociation::kNearestNeighbour;  ///< nn | jcbb
  double association_chi2_quantile = 0.99;  ///< individual-compatibility gate (chi² quantile)
  double noise_scale = 1.0;       ///< factor on the stream's sensor and odometry variances
  double min_sigma_xy_m = 1e-4;   ///< floor on the action's position std (zero motion)
  double min_sigma_theta_deg = 0.01;  ///< floor on the action's heading std
  int max_landmarks = 1000;  ///< stop (the run fails with the reason) when MRPT's map holds more (0 = no limit)
};
void BindParams(MrptEkfSlamConfig& c, ParamBinder& b);

class MrptEkfSlam : public SlamModule {
 public:
  explicit MrptEkfSlam(const MrptEkfSlamConfig& config);
  ~MrptEkfSlam() override;
  void Start(const StreamHeader& header) override;
  void OnOdometry(const OdometryEvent& odometry) override;
  void OnLandmarks(const LandmarkEvent& landmarks) override;
  Estimate Finish() override;

  struct State;  ///< MRPT objects (pimpl: MRPT stays out of this header)

 private:
  MrptEkfSlamConfig config_;
  std::unique_ptr<State> state_;
};

ModuleInfo MrptEkfSlamModule();

}  // namespace slambox
