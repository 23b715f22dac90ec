#pragma once
// Reading (slam/g2o_io.cpp) and writing (slam/g2o_write.cpp) 2D pose(-landmark) graphs:
//  - g2o: `VERTEX_SE2 id x y theta`, `VERTEX_XY id x y` (a point landmark; poses and points
//    share one id space), `EDGE_SE2 i j dx dy dtheta I11 I12 I13 I22 I23 I33` with the upper
//    triangle of the information matrix, `EDGE_SE2_XY pose_id point_id dx dy I11 I12 I22`
//    (g2o's EdgeSE2PointXY: the point in the pose's frame), `FIX id...`;
//  - TORO: `VERTEX2`, `EDGE2 i j dx dy dtheta inf_ff inf_fs inf_ss inf_rr inf_fr inf_sr`;
//  - iSAM: `ODOMETRY i j dx dy dtheta sxx sxy sxt syy syt stt`, the upper-triangular square
//    root R of the information, Omega = R^T R, and `LANDMARK pose_id landmark_id dx dy sxx
//    sxy syy` (R = [sxx sxy; 0 syy]; landmark ids are their own namespace). In a file with
//    any ODOMETRY or LANDMARK line (anywhere in it) EDGE2 lines are iSAM's, as iSAM's loader
//    reads them. GTSAM's datasets use the same tags with the upper triangle of the
//    covariance instead (slam/isam_noise.hpp: which one a file holds, decided per file).
// '#' starts a comment line.
#include <optional>
#include <string>
#include <vector>

#include "slam/isam_noise.hpp"
#include "slam/pose_graph.hpp"

namespace slambox {

struct PoseGraphFile {
  PoseGraph graph;              ///< poses indexed 0..n-1 in ascending vertex id
  std::vector<int> vertex_ids;  ///< file id of each pose index (ids need not be contiguous)
  std::vector<int> fixed;       ///< pose indices named by FIX lines; the first is the anchor
  /// File id of each landmark index, ascending (g2o: VERTEX_XY ids, shared with poses;
  /// iSAM: LANDMARK ids, their own namespace).
  std::vector<int> landmark_ids;
  /// Every pose and landmark had a VERTEX line (else poses are identity, landmarks zero).
  bool has_initial_guess = false;
  /// How the iSAM-family lines' noise was read (kSqrtInformation or kCovariance); nullopt
  /// when the file has none.
  std::optional<IsamNoise> isam_noise;
};

struct PoseGraphReadOptions {
  IsamNoise isam_noise = IsamNoise::kAuto;  ///< iSAM-family lines: decided from the file, or as given
};

/// Reads a g2o, TORO or iSAM 2D graph. Vertex ids may be sparse; edges-only files create
/// their vertices from the edges. A pose edge is a loop closure unless it joins consecutive
/// pose indices. Throws InputError naming the file and line for a malformed line, a
/// non-finite number, an unknown tag, an edge to an unknown vertex or one of the wrong kind
/// (a pose end that is a point, ...), or a non-positive-definite information.
PoseGraphFile ReadPoseGraph(const std::string& path, const PoseGraphReadOptions& options = {});
PoseGraphFile ParsePoseGraph(const std::string& text, const std::string& name, const PoseGraphReadOptions& options = {});

/// Writes g2o (VERTEX_SE2, VERTEX_XY, FIX of the anchor, EDGE_SE2, EDGE_SE2_XY) with %.17g,
/// so reading the output back yields bit-identical doubles. Atomic: the file is complete or
/// absent. g2o has one id space: when landmark_ids are missing or any collides with a pose
/// id (an iSAM file's own namespace), the landmarks get the smallest ids no pose uses, in
/// landmark order (cityTrees10000: landmark k is written as 10000 + k).
void WritePoseGraph(const std::string& path, const PoseGraph& graph, const std::vector<int>& vertex_ids = {},
                    const std::vector<int>& landmark_ids = {});
std::string FormatPoseGraph(const PoseGraph& graph, const std::vector<int>& vertex_ids = {},
                            const std::vector<int>& landmark_ids = {});

}  // namespace slambox
