#pragma once
// Which side of a surface a match puts the sensor on. A LIDAR sees a wall from one side:
// the side its sensor stood on. A target whose normals point towards the sensors that saw
// them (OrientNormalsTowards) tells which side that was; a match that puts the new scan's
// sensor on the other side of the surfaces its points land on has the scan looking at the
// back of the target's walls. That is what a false loop closure one corridor width over
// looks like (slam/README.md, "Back faces"): the new scan's walls lie on the target's walls,
// with its sensor in the rock beside the corridor the target was seen from. Scoring (the
// correlative score, ICP's fitness) only measures distances, so it cannot see this.
//   a source point s (target frame, its sensor at o) matched to target point q with
//   oriented normal n, |s - q| <= max_distance_m, lies on a back face when
//   n . (o - q) < 0;   fraction = back-face points / matched points.
// A thin surface (an open door, a partition) seen from both sides is a back face too, which
// is why the verification bounds a fraction rather than rejecting any back face.
#include <Eigen/Core>
#include <vector>

#include "core/se2.hpp"

namespace slambox {

struct IcpTarget;

/// Flips each normal of `target` that points away from the sensor that saw its point:
/// afterwards n . (viewpoints[i] - points[i]) >= 0. Point-to-line ICP is unaffected (its
/// residual is squared). viewpoints: sensor position per point, target frame.
void OrientNormalsTowards(IcpTarget* target, const std::vector<Eigen::Vector2d>& viewpoints);

struct BackFaceSetting {
  double max_distance_m = 0.1;  ///< [m] a source point farther than this from the target is no evidence
};

struct BackFaceResult {
  int matched = 0;        ///< source points within max_distance_m of a target point with a normal
  int back_faces = 0;     ///< of those, the ones whose sensor is behind the target's surface
  double fraction = 0.0;  ///< back_faces / matched; 0 when nothing matched
};

/// `scan`: the source scan's points in its sensor frame (sensor at the origin); `target`:
/// normals oriented by OrientNormalsTowards, with a kd-tree; T_target_scan: the match.
BackFaceResult BackFaces(const std::vector<Eigen::Vector2d>& scan, const IcpTarget& target, const SE2& T_target_scan,
                         const BackFaceSetting& setting = {});

}  // namespace slambox
