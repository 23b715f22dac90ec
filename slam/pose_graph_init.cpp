#include "slam/pose_graph_init.hpp"

#include <Eigen/LU>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <cmath>
#include <deque>
#include <limits>

#include "core/error.hpp"

namespace slambox {
namespace {

void CheckGraph(const PoseGraph& graph) {
  const int n = static_cast<int>(graph.poses.size());
  if (graph.anchor < 0 || graph.anchor >= n)
    throw InputError("", 0, "anchor is not a pose index", "set PoseGraph::anchor to an existing pose");
  for (const PoseGraphEdge& e : graph.edges)
    if (e.from < 0 || e.from >= n || e.to < 0 || e.to >= n)
      throw InputError("", 0, "edge " + std::to_string(e.from) + " -> " + std::to_string(e.to) + " names a missing pose",
                       "connect edges only to poses 0.." + std::to_string(n - 1));
}

// Index of each reached, non-anchor pose among the unknowns; -1 otherwise.
std::vector<int> UnknownIndex(const PoseGraph& graph, const SpanningTree& tree, int* count) {
  std::vector<int> index(graph.poses.size(), -1);
  *count = 0;
  for (int v : tree.order)
    if (v != graph.anchor) index[v] = (*count)++;
  return index;
}

bool Reached(const SpanningTree& tree, const PoseGraph& graph, int v) {
  return v == graph.anchor || tree.parent_edge[v] >= 0;
}

// Linear least squares over 2-vectors x_0..x_{m-1}: sum over edges of r^T W r with
// r = x_j - Q x_i - d; an end with index -1 is held at its given value (the anchor).
// Normal equations: row j  W x_j - W Q x_i = W d;  row i  Q^T W Q x_i - Q^T W x_j = -Q^T W d.
class LinearBlockSystem {
 public:
  explicit LinearBlockSystem(int unknowns) : m_(unknowns), b_(Eigen::VectorXd::Zero(2 * unknowns)) {}

  void AddEdge(int i, int j, const Eigen::Matrix2d& W, const Eigen::Matrix2d& Q, const Eigen::Vector2d& d,
               const Eigen::Vector2d& fixed_i, const Eigen::Vector2d& fixed_j) {
    const Eigen::Matrix2d QtW = Q.transpose() * W;
    if (j >= 0) {
      AddBlock(j, j, W);
      b_.segment<2>(2 * j) += W * d;
      if (i >= 0) AddBlock(j, i, -W * Q); else b_.segment<2>(2 * j) += W * Q * fixed_i;
    }
    if (i >= 0) {
      AddBlock(i, i, QtW * Q);
      b_.segment<2>(2 * i) -= QtW * d;
      if (j >= 0) AddBlock(i, j, -QtW); else b_.segment<2>(2 * i) += QtW * fixed_j;
    }
  }

  /// False when the system is singular or the solution not finite.
  bool Solve(Eigen::VectorXd* x) const {
    Eigen::SparseMatrix<double> A(2 * m_, 2 * m_);
    A.setFromTriplets(triplets_.begin(), triplets_.end());
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(A);
    *x = ldlt.solve(b_);
    return ldlt.info() == Eigen::Success && x->allFinite();
  }

 private:
  void AddBlock(int r, int c, const Eigen::Matrix2d& M) {
    for (int a = 0; a < 2; ++a)
      for (int d = 0; d < 2; ++d) triplets_.emplace_back(2 * r + a, 2 * c + d, M(a, d));
  }
  int m_;
  Eigen::VectorXd b_;
  std::vector<Eigen::Triplet<double>> triplets_;
};

}  // namespace

SpanningTree BuildSpanningTree(const PoseGraph& graph, bool prefer_odometry) {
  CheckGraph(graph);
  const int n = static_cast<int>(graph.poses.size());
  std::vector<std::vector<int>> incident(n);
  for (size_t k = 0; k < graph.edges.size(); ++k) {
    incident[graph.edges[k].from].push_back(static_cast<int>(k));
    incident[graph.edges[k].to].push_back(static_cast<int>(k));
  }
  // 0-1 BFS: an odometry edge costs 0, a loop closure 1, so the tree follows odometry.
  const int kInf = std::numeric_limits<int>::max();
  std::vector<int> dist(n, kInf);
  std::vector<char> done(n, 0);
  SpanningTree tree;
  tree.parent_edge.assign(n, -1);
  tree.theta_unwrapped.assign(n, 0.0);
  std::deque<int> queue{graph.anchor};
  dist[graph.anchor] = 0;
  while (!queue.empty()) {
    const int u = queue.front();
    queue.pop_front();
    if (done[u]) continue;
    done[u] = 1;
    tree.order.push_back(u);
    for (int k : incident[u]) {
      const PoseGraphEdge& e = graph.edges[k];
      const int v = e.from == u ? e.to : e.from;
      const int w = (e.loop_closure || !prefer_odometry) ? 1 : 0;
      if (done[v] || dist[u] + w >= dist[v]) continue;
      dist[v] = dist[u] + w;
      tree.parent_edge[v] = k;
      if (w == 0) queue.push_front(v); else queue.push_back(v);
    }
  }
  tree.theta_unwrapped[graph.anchor] = graph.poses[graph.anchor].theta;
  for (int v : tree.order) {
    if (v == graph.anchor) continue;
    const PoseGraphEdge& e = graph.edges[tree.parent_edge[v]];
    tree.theta_unwrapped[v] = e.to == v ? tree.theta_unwrapped[e.from] + e.T_from_to.theta
                                        : tree.theta_unwrapped[e.to] - e.T_from_to.theta;
  }
  return tree;
}

std::vector<SE2> SpanningTreeInitialization(const PoseGraph& graph) {
  const SpanningTree tree = BuildSpanningTree(graph);
  std::vector<SE2> poses = graph.poses;
  for (int v : tree.order) {
    if (v == graph.anchor) continue;
    const PoseGraphEdge& e = graph.edges[tree.parent_edge[v]];
    poses[v] = e.to == v ? poses[e.from] * e.T_from_to : poses[e.to] * e.T_from_to.inverse();
  }
  return poses;
}

std::vector<double> LagoOrientations(const PoseGraph& graph, const SpanningTree& tree) {
  int m = 0;
  const std::vector<int> index = UnknownIndex(graph, tree, &m);
  std::vector<double> theta = tree.theta_unwrapped;
  if (m == 0) return theta;
  // Minimize sum_e w_e (theta_j - theta_i - delta_e - 2 pi k_e)^2, with k_e the integer
  // making the measurement agree with the tree (k_e = 0 on tree edges), and w_e the
  // marginal angular information 1 / (Omega^-1)_33.
  std::vector<Eigen::Triplet<double>> triplets;
  Eigen::VectorXd b = Eigen::VectorXd::Zero(m);
  for (const PoseGraphEdge& e : graph.edges) {
    if (!Reached(tree, graph, e.from) || !Reached(tree, graph, e.to)) continue;
    const double gap = tree.theta_unwrapped[e.to] - tree.theta_unwrapped[e.from] - e.T_from_to.theta;
    const double delta = e.T_from_to.theta + 2.0 * M_PI * std::round(gap / (2.0 * M_PI));
    const double w = 1.0 / e.information.inverse()(2, 2);
    const int i = index[e.from], j = index[e.to];
    // Gradient rows: d/dtheta_j: w (theta_j - theta_i - delta); d/dtheta_i: the negative.
    if (j >= 0) {
      triplets.emplace_back(j, j, w);
      b(j) += w * delta;
      if (i >= 0) triplets.emplace_back(j, i, -w); else b(j) += w * theta[e.from];
    }
    if (i >= 0) {
      triplets.emplace_back(i, i, w);
      b(i) -= w * delta;
      if (j >= 0) triplets.emplace_back(i, j, -w); else b(i) += w * theta[e.to];
    }
  }
  Eigen::SparseMatrix<double> A(m, m);
  A.setFromTriplets(triplets.begin(), triplets.end());
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(A);
  const Eigen::VectorXd x = ldlt.solve(b);
  if (ldlt.info() != Eigen::Success || !x.allFinite()) return tree.theta_unwrapped;
  for (size_t v = 0; v < index.size(); ++v)
    if (index[v] >= 0) theta[v] = x(index[v]);
  return theta;
}

std::vector<double> ChordalOrientations(const PoseGraph& graph, const SpanningTree& tree) {
  int m = 0;
  const std::vector<int> index = UnknownIndex(graph, tree, &m);
  std::vector<double> theta = tree.theta_unwrapped;
  if (m == 0) return theta;
  // Each rotation as a unit vector z = (cos theta, sin theta); an edge says
  // z_j = Rot(delta_e) z_i. Minimize sum_e w_e |z_j - Rot(delta_e) z_i|^2 (half the
  // squared chordal distance |R_j - R_i R_e|_F^2) over unconstrained z, z_anchor fixed:
  // linear least squares with no 2 pi ambiguity; theta_i = atan2 of the solution.
  LinearBlockSystem system(m);
  const Eigen::Vector2d z_anchor(std::cos(theta[graph.anchor]), std::sin(theta[graph.anchor]));
  for (const PoseGraphEdge& e : graph.edges) {
    if (!Reached(tree, graph, e.from) || !Reached(tree, graph, e.to)) continue;
    const double w = 1.0 / e.information.inverse()(2, 2);
    system.AddEdge(index[e.from], index[e.to], w * Eigen::Matrix2d::Identity(), RotationMatrix(e.T_from_to.theta),
                   Eigen::Vector2d::Zero(), z_anchor, z_anchor);
  }
  Eigen::VectorXd x;
  if (!system.Solve(&x)) return tree.theta_unwrapped;
  for (size_t v = 0; v < index.size(); ++v)
    if (index[v] >= 0 && x.segment<2>(2 * index[v]).norm() > 0)
      theta[v] = std::atan2(x(2 * index[v] + 1), x(2 * index[v]));
  return theta;
}

namespace {

// Positions by linear least squares given the orientations `theta` (LAGO's second phase).
std::vector<SE2> PositionsGivenOrientations(const PoseGraph& graph, const SpanningTree& tree,
                                            const std::vector<double>& theta) {
  int m = 0;
  const std::vector<int> index = UnknownIndex(graph, tree, &m);
  std::vector<SE2> poses = graph.poses;
  if (m == 0) return poses;
  // Given theta, each edge is linear in positions: e = R_i^T (t_j - t_i) - t_ij, i.e.
  // t_j - t_i - R_i t_ij weighted by W = R_i Omega_tt R_i^T (Omega_tt: the 2x2 block, the
  // positional information conditioned on the angles).
  LinearBlockSystem system(m);
  const Eigen::Vector2d t_anchor = graph.poses[graph.anchor].translation();
  for (const PoseGraphEdge& e : graph.edges) {
    if (!Reached(tree, graph, e.from) || !Reached(tree, graph, e.to)) continue;
    const Eigen::Matrix2d R_i = RotationMatrix(theta[e.from]);
    const Eigen::Matrix2d W = R_i * e.information.topLeftCorner<2, 2>() * R_i.transpose();
    system.AddEdge(index[e.from], index[e.to], W, Eigen::Matrix2d::Identity(), R_i * e.T_from_to.translation(),
                   t_anchor, t_anchor);
  }
  Eigen::VectorXd x;
  if (!system.Solve(&x)) return SpanningTreeInitialization(graph);
  for (size_t v = 0; v < index.size(); ++v)
    if (index[v] >= 0) poses[v] = SE2(x(2 * index[v]), x(2 * index[v] + 1), theta[v]);
  return poses;
}

}  // namespace

std::vector<SE2> LagoInitialization(const PoseGraph& graph) {
  const SpanningTree tree = BuildSpanningTree(graph, false);
  return PositionsGivenOrientations(graph, tree, LagoOrientations(graph, tree));
}

std::vector<SE2> ChordalInitialization(const PoseGraph& graph) {
  const SpanningTree tree = BuildSpanningTree(graph, false);
  return PositionsGivenOrientations(graph, tree, ChordalOrientations(graph, tree));
}

std::vector<Eigen::Vector2d> LandmarksFromObservations(const PoseGraph& graph, const std::vector<SE2>& poses,
                                                       LandmarkPlacement placement) {
  std::vector<Eigen::Vector2d> sum(graph.landmarks.size(), Eigen::Vector2d::Zero());
  std::vector<int> count(graph.landmarks.size(), 0);
  for (const LandmarkEdge& e : graph.landmark_edges) {
    if (e.pose < 0 || e.pose >= static_cast<int>(poses.size()) || e.landmark < 0 ||
        e.landmark >= static_cast<int>(sum.size()))
      continue;  // SolvePoseGraph reports it
    if (placement == LandmarkPlacement::kFirstObservation && count[e.landmark] > 0) continue;
    const SE2& T = poses[e.pose];
    sum[e.landmark] += T.translation() + T.rotation() * e.p_pose_landmark;
    ++count[e.landmark];
  }
  std::vector<Eigen::Vector2d> out = graph.landmarks;
  for (size_t j = 0; j < out.size(); ++j)
    if (count[j] > 0) out[j] = sum[j] / count[j];
  return out;
}

}  // namespace slambox
