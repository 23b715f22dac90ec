#pragma once
// Relation files of the Kümmerle et al. 2009 benchmark ("On measuring the accuracy of SLAM
// algorithms"; Freiburg's *.relations): one relation per line,
//   t_i t_j dx dy dz roll pitch dtheta
// the pose of the robot at time t_j in its frame at time t_i [s, m, rad], found by
// manually matched scans. Times are the log's clock; lines need not be sorted.
// For an estimate x(t) the relation's error is e = d_ref^-1 (x_i^-1 x_j) (eq. 2), scored
// by eval/relation_metric.hpp.
#include <string>
#include <vector>

#include "core/se2.hpp"
#include "core/stream.hpp"

namespace slambox {

struct Relation {
  double t_i_s = 0.0, t_j_s = 0.0;  ///< [s] the log's clock
  SE2 T_i_j;                        ///< robot at t_j in the robot frame at t_i
  int line = 0;                     ///< in the file, for messages
};

/// Throws InputError naming the file and line for a malformed line (fewer than 8 numbers,
/// a non-finite value); blank lines and lines starting with '#' are skipped.
std::vector<Relation> ParseRelations(const std::string& text, const std::string& name);
std::vector<Relation> ReadRelations(const std::string& path);

struct RelationMatchOptions {
  /// [s] the log's clock at estimate time 0: a relation time t maps to t - time_origin_s
  /// (a converted stream's header says it; 0 for estimates stamped with the log's clock).
  double time_origin_s = 0.0;
  /// [s] a relation time is matched to the nearest estimate pose within this (ties: the
  /// earlier pose); converted streams round times to 1 ms, so 5 ms never misses a scan.
  double max_time_diff_s = 0.005;
};

struct RelationErrors {
  std::vector<double> translation_m;  ///< |t(e)| per matched relation, in file order
  std::vector<double> rotation_deg;   ///< |angle(e)|
  int unmatched = 0;  ///< relations with t_i or t_j farther than max_time_diff_s from every pose
};

/// `trajectory` must be time-ordered (non-decreasing).
RelationErrors ComputeRelationErrors(const std::vector<Relation>& relations, const std::vector<StampedPose>& trajectory,
                                     const RelationMatchOptions& options = {});

/// Relations whose both times, mapped by `time_origin_s`, fall within [0, duration_s]
/// (up to the tolerance): lets a command reject a relations file of another log early.
int RelationsWithin(const std::vector<Relation>& relations, double duration_s, const RelationMatchOptions& options);

}  // namespace slambox
