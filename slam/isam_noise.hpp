#pragma once
// The noise values of iSAM-family graph lines (`ODOMETRY`, `LANDMARK`, and `EDGE2` in a file
// that has either): two conventions share these tags. iSAM's own files (manhattanOlson3500,
// cityTrees10000) give the upper-triangular square root R of the information, Omega = R^T R;
// GTSAM's datasets (victoria_park_gtsam.txt) give the upper triangle of the covariance C,
// Omega = C^-1. The order is the same: xx xy xt yy yt tt (pose edges), xx xy yy (points).
//
// kAuto decides for the whole file from the diagonal values: a standard deviation below
// 1 m or 1 rad is a square-root information entry 1/sigma > 1 (in magnitude: a root's sign
// is free) and a covariance entry sigma^2 in (0, 1), so a file with diagonal values of only
// the first kind reads as iSAM's, one with only the second as covariances (all exactly 1:
// iSAM's; both read the same there); a file with both is refused, naming a line of each.
#include <Eigen/Core>
#include <optional>
#include <string>

#include "core/params.hpp"

namespace slambox {

enum class IsamNoise { kAuto, kSqrtInformation, kCovariance };
/// auto, sqrt-information, covariance (for `optimize --noise`).
const EnumNames<IsamNoise>& IsamNoiseNames();

/// The convention of the file's iSAM-family lines (kSqrtInformation or kCovariance), or
/// nullopt when it has none. `requested` other than kAuto is returned as is when the file has
/// such lines. Lines too short or with non-numbers are skipped here (the reader reports them).
/// `isam_edge2`: EDGE2 lines are iSAM's (the file has ODOMETRY or LANDMARK lines).
/// Throws InputError (with both lines) for a kAuto file that holds both kinds of values.
std::optional<IsamNoise> ResolveIsamNoise(const std::string& text, const std::string& name, IsamNoise requested,
                                          bool isam_edge2);

/// Information over (dx, dy, dtheta) from the six values xx xy xt yy yt tt. nullopt when
/// the matrix they describe (R with a zero on its diagonal, or C) is not positive definite.
std::optional<Eigen::Matrix3d> IsamPoseInformation(const double (&v)[6], IsamNoise noise);
/// Information over (dx, dy) from xx xy yy, likewise.
std::optional<Eigen::Matrix2d> IsamPointInformation(const double (&v)[3], IsamNoise noise);

}  // namespace slambox
