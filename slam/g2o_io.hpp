#pragma once
// Reading and writing 2D pose graphs: g2o (`VERTEX_SE2 id x y theta`,
// `EDGE_SE2 i j dx dy dtheta I11 I12 I13 I22 I23 I33` with the upper triangle of the
// information matrix, `FIX id...`) and TORO (`VERTEX2`, `EDGE2 i j dx dy dtheta inf_ff
// inf_fs inf_ss inf_rr inf_fr inf_sr`) and iSAM (`ODOMETRY i j dx dy dtheta sxx sxy sxt
// syy syt stt`, the upper-triangular square root R of the information, Omega = R^T R; in a
// file with ODOMETRY lines EDGE2 lines are read the same way). '#' starts a comment line.
#include <string>
#include <vector>

#include "slam/pose_graph.hpp"

namespace slambox {

struct PoseGraphFile {
  PoseGraph graph;              ///< poses indexed 0..n-1 in ascending vertex id
  std::vector<int> vertex_ids;  ///< file id of each pose index (ids need not be contiguous)
  std::vector<int> fixed;       ///< pose indices named by FIX lines; the first is the anchor
  bool has_initial_guess = false;  ///< every pose had a VERTEX line (else poses are identity)
};

/// Reads a g2o or TORO 2D graph. Vertex ids may be sparse; edges-only files create their
/// vertices from the edges. An edge is a loop closure unless it joins consecutive indices.
/// Throws InputError naming the file and line for a malformed line, a non-finite number,
/// an unknown tag, an edge to an unknown vertex or a non-positive-definite information.
PoseGraphFile ReadPoseGraph(const std::string& path);
PoseGraphFile ParsePoseGraph(const std::string& text, const std::string& name);

/// Writes g2o (VERTEX_SE2, FIX of the anchor, EDGE_SE2) with %.17g, so reading the output
/// back yields bit-identical doubles. Atomic: the file is complete or absent.
void WritePoseGraph(const std::string& path, const PoseGraph& graph, const std::vector<int>& vertex_ids = {});
std::string FormatPoseGraph(const PoseGraph& graph, const std::vector<int>& vertex_ids = {});

}  // namespace slambox
