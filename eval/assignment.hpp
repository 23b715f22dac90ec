#pragma once
// Optimal assignment (Hungarian method, Kuhn 1955 / Munkres 1957) in the O(n^2 m)
// shortest-augmenting-path form with row and column potentials.
#include <Eigen/Core>
#include <vector>

namespace slambox {

/// Minimum-cost assignment for an n x m cost matrix: every row is assigned to a distinct
/// column when n <= m, every column to a distinct row otherwise. Returns, per row, its
/// column or -1 (only when n > m). Costs must be finite.
std::vector<int> SolveAssignment(const Eigen::MatrixXd& cost);

}  // namespace slambox
