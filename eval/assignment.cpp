#include "eval/assignment.hpp"

#include <cassert>
#include <limits>

namespace slambox {

namespace {
// Rows <= columns. Rows are added one at a time; each addition grows an alternating tree
// of tight edges (reduced cost c_ij - u_i - v_j = 0) by Dijkstra-like steps, updating the
// potentials by the smallest slack, until a free column is reached, then flips the path.
std::vector<int> AssignRowsToColumns(const Eigen::MatrixXd& c) {
  const int n = static_cast<int>(c.rows()), m = static_cast<int>(c.cols());
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<double> u(n + 1, 0.0), v(m + 1, 0.0);
  std::vector<int> row_of_col(m + 1, 0), way(m + 1, 0);  // 1-based; column 0 is the root
  for (int i = 1; i <= n; ++i) {
    row_of_col[0] = i;
    int j0 = 0;
    std::vector<double> min_slack(m + 1, inf);
    std::vector<char> used(m + 1, 0);
    do {
      used[j0] = 1;
      const int i0 = row_of_col[j0];
      double delta = inf;
      int j1 = 0;
      for (int j = 1; j <= m; ++j) {
        if (used[j]) continue;
        const double slack = c(i0 - 1, j - 1) - u[i0] - v[j];
        if (slack < min_slack[j]) {
          min_slack[j] = slack;
          way[j] = j0;
        }
        if (min_slack[j] < delta) {
          delta = min_slack[j];
          j1 = j;
        }
      }
      for (int j = 0; j <= m; ++j) {
        if (used[j]) {
          u[row_of_col[j]] += delta;
          v[j] -= delta;
        } else {
          min_slack[j] -= delta;
        }
      }
      j0 = j1;
    } while (row_of_col[j0] != 0);
    do {  // augment along the alternating path back to the root
      const int j1 = way[j0];
      row_of_col[j0] = row_of_col[j1];
      j0 = j1;
    } while (j0 != 0);
  }
  std::vector<int> col_of_row(n, -1);
  for (int j = 1; j <= m; ++j)
    if (row_of_col[j] != 0) col_of_row[row_of_col[j] - 1] = j - 1;
  return col_of_row;
}
}  // namespace

std::vector<int> SolveAssignment(const Eigen::MatrixXd& cost) {
  assert(cost.allFinite());
  if (cost.rows() == 0 || cost.cols() == 0) return std::vector<int>(cost.rows(), -1);
  if (cost.rows() <= cost.cols()) return AssignRowsToColumns(cost);
  const std::vector<int> row_of_col = AssignRowsToColumns(cost.transpose());
  std::vector<int> col_of_row(cost.rows(), -1);
  for (int j = 0; j < static_cast<int>(row_of_col.size()); ++j) col_of_row[row_of_col[j]] = j;
  return col_of_row;
}

}  // namespace slambox
