#pragma once
// KITTI odometry pose files: one pose per line, the first three rows of the 4x4 SE(3)
// matrix T_world_robot in row-major order (12 numbers, evo's `kitti` format). No
// timestamps: two KITTI files correspond line by line. A 2D pose is written as a rotation
// about z with z = 0 (slambox's frame, not KITTI's camera frame with z forward);
// reading takes x, y and the yaw atan2(r10, r00) and rejects rotations out of the x-y
// plane. %.17g numbers: x and y round-trip bit-exactly, the yaw to within 1 ulp of atan2.
#include <string>
#include <vector>

#include "core/stream.hpp"

namespace slambox {

void WriteKittiPoses(const std::string& path, const std::vector<StampedPose>& poses);  ///< atomic; times dropped

/// Poses with t_s = line index (0, 1, ...). Throws InputError naming the file and line
/// for a line without 12 numbers, a non-finite value, or a pose that is not a rotation
/// about z (|r02|, |r12|, |r20|, |r21|, |r22 - 1|, |tz| > 1e-6).
std::vector<StampedPose> ReadKittiPoses(const std::string& path);

enum class TrajectoryFormat { kTum, kKitti };

/// By the first data line: 8 numbers = TUM, 12 = KITTI. Throws InputError otherwise.
TrajectoryFormat DetectTrajectoryFormat(const std::string& path);

}  // namespace slambox
