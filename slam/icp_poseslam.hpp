#pragma once
// `icp-poseslam`: keyframe pose graph SLAM with ICP. Each scan is registered to the
// latest keyframe (guess: wheel odometry; where it disagrees with the constant-velocity
// guess, also from that, keeping the better fit); a new keyframe starts after keyframe_distance_m
// or keyframe_angle_deg, joined by an ICP edge (information from the capped ICP Hessian,
// or fixed). Loop-closure candidates (slam/loop_closure.hpp) are verified by ICP and the
// graph is re-solved with Ceres (slam/pose_graph.hpp), a robust kernel on loop edges.
// Output: keyframes optimized, every other pose re-anchored to its keyframe; map points
// and an occupancy grid at the optimized keyframes. Pose covariances: the keyframe's
// marginal from the pose graph (Laplace approximation at the solution) composed with the
// pose's covariance relative to its keyframe (the ICP edge covariance at scans, grown by
// the odometry model between them). Both rest on the capped, Hessian-based ICP
// information, so they are as optimistic as that is (Censi 2007).
#include <functional>
#include <optional>

#include "core/slam_module.hpp"
#include "slam/adaptive_threshold.hpp"
#include "slam/back_face.hpp"
#include "slam/correlative_matcher.hpp"
#include "slam/edge_information.hpp"
#include "slam/icp_params.hpp"
#include "slam/loop_closure.hpp"
#include "slam/loop_region.hpp"
#include "slam/occupancy_grid_builder.hpp"
#include "slam/pose_graph.hpp"
#include "slam/scan_points.hpp"

namespace slambox {

/// Information of an ICP edge: the capped ICP Hessian, or fixed sigmas.
enum class EdgeInformationSource { kHessian, kFixed };

struct IcpPoseSlamConfig {
  /// Front end, scan to keyframe; redescending weights: movers do not drag ICP.
  IcpConfig icp{.correspondence = IcpCorrespondence::kProjection, .robust_kernel = IcpRobustKernel::kGemanMcClure};
  IcpConfig loop_icp{.correspondence = IcpCorrespondence::kKdTree, .max_iterations = 50,
                     .max_correspondence_m = 0.5};
  bool adaptive_gate = true;            ///< KISS-ICP adaptive gate for the front end
  /// Front-end target: the latest keyframe and this many before it, merged in its frame
  /// (scan-to-submap, kd-tree); 0 = the latest keyframe's scan alone (projection).
  int local_map_keyframes = 3;
  double local_map_voxel_m = 0.05;      ///< [m] voxel size of the merged local map
  /// Wheel odometry on real logs stalls and jumps (mit-csail: 0.8 s of frozen readings,
  /// then 85 deg at once); from such a guess ICP settles in a wrong minimum. When the
  /// odometry guess and the constant-velocity guess (the last scan-to-scan motion again)
  /// differ by more than this, ICP starts from both and the better fit is kept.
  /// ICP against the guess as a prior too: the pose relative to the keyframe (the last
  /// scan's ICP composed with the wheel odometry since) with its covariance (the last scan's
  /// capped ICP covariance grown by the stream's odometry noise model, the motion since the
  /// last scan taken as one increment: the model's variance grows with rot^2 per increment,
  /// so summing it over dense odometry messages would make the prior depend on how often
  /// odometry was sampled); ambiguous directions then follow the odometry. Off without an
  /// odometry noise model.
  bool odometry_prior = false;
  double guess_disagreement_m = 0.2;      ///< [m] ... in translation
  double guess_disagreement_deg = 5.0;    ///< [deg] ... or in heading
  double guess_fit_radius_m = 0.1;        ///< [m] fit = fraction of scan points this close to the local map
  double guess_switch_margin = 0.05;      ///< the constant-velocity result must fit this much better to win
  /// An ICP that stopped at its iteration cap without converging measured nothing it can
  /// vouch for: its Hessian says how sharp the cost is where it stopped, not that it stopped
  /// at the right minimum (fr079 at 168-180 s: the wheels report -16 deg while the robot
  /// turns +10 deg, ICP hits the cap scan after scan and ends 25 deg off). A keyframe reached
  /// that way keeps ICP's pose but its edge gets the odometry's information (the motion
  /// model's covariance since the last keyframe), so a later loop closure can bend the graph
  /// there. Off by default: it is not no-worse overall (slam/README.md, "Sparse odometry":
  /// fr079 without ODOM lines 1.421 -> 0.046 m, but fr079's MRPT rawlog 0.045 -> 1.245 m).
  bool unconverged_icp_edges_from_odometry = false;
  double keyframe_distance_m = 0.5;     ///< [m] new keyframe after this much translation
  double keyframe_angle_deg = 20.0;     ///< [deg] ... or this much rotation
  EdgeInformationSource edge_information = EdgeInformationSource::kHessian;
  double info_cap_sigma_xy_m = 0.005;    ///< [m] Hessian information cap, translation
  double info_cap_sigma_theta_deg = 0.1; ///< [deg] Hessian information cap, heading
  double fixed_sigma_xy_m = 0.02;        ///< [m] fixed information, translation
  double fixed_sigma_theta_deg = 0.5;    ///< [deg] fixed information, heading
  LoopClosureConfig loop;
  int loop_submap_keyframes = 5;         ///< loop target: the candidate keyframe and this many on each side
  /// Loop source: the new keyframe's scan, joined by up to loop_submap_keyframes keyframes
  /// before it (placed by the current estimate) while it has fewer points than this. A sparse scan
  /// (a 91-beam LIDAR in a wide hall sees 20-40 points) scores a wrong pose as high as the
  /// right one by chance; Cartographer's loop-closure voxel filter keeps >= 100 points too.
  int loop_min_source_points = 100;
  ScoreTableConfig loop_table{.resolution_m = 0.05, .sigma_m = 0.05, .levels = 5};  ///< correlative search grid
  double loop_min_score = 0.6;           ///< correlative score (mean of exp(-d^2/2 sigma^2)) a closure needs
  double loop_runner_up_radius_m = 0.5;  ///< [m] ambiguity: best score farther than this from the match ...
  double loop_max_runner_up_ratio = 0.95;  ///< ... must stay below this fraction of the match's score
  double loop_max_match_shift_m = 0.1;   ///< [m] ICP may move the correlative match at most this far
  bool loop_reject_window_edge = true;   ///< a correlative optimum on the search window's edge is no closure
  /// A closure whose new scan sees more than this fraction of its matched points from the back
  /// of the target's surfaces is false (slam/back_face.hpp: one corridor width over).
  double loop_max_back_face_fraction = 0.5;
  BackFaceSetting loop_back_face;        ///< which source points count as matched there
  /// Region loop search (slam/loop_region.hpp): at a keyframe where no candidate's submap
  /// closed a loop, the target is the union of the old keyframes within the new scan's
  /// median range (plus each one's search window) of it, admitted pass by pass where the
  /// passes agree under the estimate (score >= loop_min_score over their overlap); matched in
  /// the window of the nearest of them (the anchor), verified as any closure.
  bool loop_region = false;
  RegionConfig loop_region_passes;       ///< overlap radius and fraction (min_agreement, sigma: from loop_min_score, loop_table)
  int loop_region_min_passes = 2;        ///< the region search runs only when this many passes are admitted
  double loop_region_max_search_radius_m = 0.0;  ///< [m] the region search's radius cap (0 = loop_max_search_radius_m)
  int solve_every_keyframes = 20;        ///< re-solve pending small closures after this many keyframes
  double solve_innovation_m = 0.05;      ///< [m] a closure this far off the estimate is solved at once
  RobustKernel loop_kernel = RobustKernel::kDcs;  ///< on loop edges only
  double loop_kernel_scale = 100.0;        ///< Huber/Cauchy scale on the whitened residual; DCS Phi
  double loop_accept_weight = 0.5;       ///< a loop edge the back-end weights below this counts as rejected
  int solve_max_iterations = 50;
  double source_voxel_m = 0.0;           ///< [m] subsample scans (0 = every valid beam)
  double map_voxel_m = 0.05;             ///< [m] voxel size of Estimate::map_points
  double grid_resolution_m = 0.05;       ///< [m] occupancy grid cell (0 = no grid)
  bool compute_covariance = true;        ///< pose covariances for NEES (one selected inversion at the end)
};
void BindParams(IcpPoseSlamConfig& c, ParamBinder& b);

class IcpPoseSlam : public SlamModule {
 public:
  explicit IcpPoseSlam(const IcpPoseSlamConfig& config);
  void Start(const StreamHeader& header) override;
  void OnOdometry(const OdometryEvent& odometry) override;
  void OnLaserScan(const LaserScanEvent& scan) override;
  Estimate Finish() override;

 private:
  struct Keyframe {
    double t_s = 0.0;
    ScanPoints points;
    LaserScanEvent geometry;  ///< beam layout (for the loop-closure target)
    double path_m = 0.0;      ///< path length travelled up to this keyframe
  };
  struct LoopTarget {  ///< a submap around keyframe `keyframe`, in its frame
    int keyframe = -1;
    ScoreTable table;
    IcpTarget cloud;
  };
  struct Record {  ///< a trajectory pose relative to a keyframe (-1: absolute, before the first)
    double t_s = 0.0;
    int keyframe = -1;
    SE2 T_kf_robot;
    Eigen::Matrix3d covariance;  ///< of T_kf_robot (absolute before the first keyframe)
  };
  void RecordPose(double t_s);
  /// edge_icp: the ICP result joining it to the previous keyframe, or null (odometry edge).
  void AddKeyframe(const LaserScanEvent& scan, ScanPoints points, const IcpResult* edge_icp);
  void CloseLoops(double t_s);
  /// Correlative match of `source` (LoopSource(), newest keyframe's frame) against `table`
  /// (frame of keyframe `from`) in the window, ICP refinement against cloud() and
  /// verification; on success a loop edge from -> newest is added and its innovation
  /// returned. (slam/icp_poseslam_loop.cpp)
  bool TryLoop(int from, const std::vector<Eigen::Vector2d>& source, const ScoreTable& table,
               const std::function<const IcpTarget&()>& cloud, double radius_m, double angle_rad,
               double* innovation_m);
  /// The region search (slam/loop_region.hpp) at the newest keyframe. (slam/icp_poseslam_loop.cpp)
  bool CloseLoopInRegion(const std::vector<Eigen::Vector2d>& source, const std::vector<Eigen::Matrix3d>& relative_cov,
                         const std::vector<double>& path, double* innovation_m);
  /// The newest keyframe's points, with earlier keyframes' while below loop_min_source_points.
  std::vector<Eigen::Vector2d> LoopSource() const;
  /// A loop target's points: keyframes `ids` in the frame T_w_frame, those `keep` accepts (all
  /// when empty), voxel-thinned, each with the position of the keyframe that saw it.
  struct LoopSubmap {
    std::vector<Eigen::Vector2d> points, viewpoints;
  };
  LoopSubmap LoopSubmapPoints(const std::vector<int>& ids, const SE2& T_w_frame,
                              const std::function<bool(const Eigen::Vector2d&)>& keep) const;
  /// The submap as an ICP target, normals towards their viewpoints (slam/back_face.hpp).
  static IcpTarget LoopCloud(LoopSubmap submap);
  /// The submap of keyframe +- loop_submap_keyframes, cached. (slam/icp_poseslam_loop.cpp)
  const LoopTarget& LoopTargetFor(int keyframe);
  PoseGraphSolveResult Solve(bool marginals = false);
  InformationCaps Caps() const;

  IcpPoseSlamConfig config_;
  IcpConfig icp_, loop_icp_, local_map_icp_;
  PoseGraphSolveOptions solve_options_;
  AdaptiveThreshold gate_;
  std::array<double, 4> alpha_{};
  SE2 start_pose_;
  SE2 T_kf_robot_;                 ///< current pose relative to the latest keyframe
  SE2 T_kf_last_scan_;             ///< the previous scan's pose relative to the latest keyframe
  SE2 T_last_scan_motion_;         ///< the motion between the two previous scans (their frame)
  int guesses_switched_ = 0;       ///< scans where the constant-velocity guess fitted better
  Eigen::Matrix3d odometry_cov_ = Eigen::Matrix3d::Zero();  ///< of T_kf_robot_ by the motion model
  Eigen::Matrix3d relative_cov_ = Eigen::Matrix3d::Zero();  ///< of T_kf_robot_: ICP at scans, odometry after
  Eigen::Matrix3d last_scan_cov_ = Eigen::Matrix3d::Zero();  ///< of T_kf_last_scan_ (odometry prior)
  double path_m_ = 0.0;
  IcpTarget keyframe_target_;
  std::vector<Keyframe> keyframes_;
  PoseGraph graph_;
  std::vector<int> loop_record_of_edge_;  ///< per graph edge: index into loop_closures, or -1
  std::vector<Record> records_;
  Estimate estimate_;
  int proposed_ = 0;
  std::vector<LoopTarget> loop_targets_;  ///< recently used submaps (a few; oldest replaced)
  int keyframes_since_solve_ = 0;
  bool pending_closures_ = false;
};

ModuleInfo IcpPoseSlamModule();

}  // namespace slambox
