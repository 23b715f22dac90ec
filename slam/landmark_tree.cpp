#include "slam/landmark_tree.hpp"

#include <cassert>
#include <unordered_set>

namespace slambox {

namespace {

using NodePtr = std::shared_ptr<LandmarkTreeNode>;

// Makes `slot` safe to modify: a node shared with another tree (use_count > 1) is
// replaced by a copy (path copying); a uniquely owned one is kept. The caller owns the
// node holding `slot` exclusively, so use_count counts other trees' references only.
LandmarkTreeNode& Own(NodePtr& slot) {
  if (!slot) slot = std::make_shared<LandmarkTreeNode>();
  else if (slot.use_count() > 1) slot = std::make_shared<LandmarkTreeNode>(*slot);
  return *slot;
}

void RecomputeBox(LandmarkTreeNode& n) {
  bool first = true;
  for (const NodePtr& c : n.child) {
    if (!c) continue;
    n.box_min = first ? c->box_min : n.box_min.cwiseMin(c->box_min);
    n.box_max = first ? c->box_max : n.box_max.cwiseMax(c->box_max);
    first = false;
  }
}

// `level` = number of key bits still to descend; level 0 is a leaf.
void SetIn(NodePtr& slot, int level, int key, const LandmarkGaussian& landmark) {
  LandmarkTreeNode& n = Own(slot);
  if (level == 0) {
    n.landmark = landmark;
    n.box_min = n.box_max = landmark.mean;
    return;
  }
  SetIn(n.child[(key >> (level - 1)) & 1], level - 1, key, landmark);
  RecomputeBox(n);
}

void EraseIn(NodePtr& slot, int level, int key) {
  if (level == 0) {
    slot.reset();
    return;
  }
  LandmarkTreeNode& n = Own(slot);
  EraseIn(n.child[(key >> (level - 1)) & 1], level - 1, key);
  if (!n.child[0] && !n.child[1]) slot.reset();
  else RecomputeBox(n);
}

void ForEachIn(const LandmarkTreeNode* n, int level, int key_prefix,
               const std::function<void(int, const LandmarkGaussian&)>& fn) {
  if (!n) return;
  if (level == 0) {
    fn(key_prefix, n->landmark);
    return;
  }
  ForEachIn(n->child[0].get(), level - 1, key_prefix << 1, fn);
  ForEachIn(n->child[1].get(), level - 1, (key_prefix << 1) | 1, fn);
}

void BoxIn(const LandmarkTreeNode* n, int level, int key_prefix, const Eigen::Vector2d& lo,
           const Eigen::Vector2d& hi, std::vector<int>& keys) {
  if (!n || (n->box_max.array() < lo.array()).any() || (n->box_min.array() > hi.array()).any()) return;
  if (level == 0) {
    keys.push_back(key_prefix);
    return;
  }
  BoxIn(n->child[0].get(), level - 1, key_prefix << 1, lo, hi, keys);
  BoxIn(n->child[1].get(), level - 1, (key_prefix << 1) | 1, lo, hi, keys);
}

}  // namespace

const LandmarkGaussian* FindLandmark(const LandmarkTree& tree, int key) {
  if (key < 0 || (key >> tree.height) != 0) return nullptr;
  const LandmarkTreeNode* n = tree.root.get();
  for (int level = tree.height; n && level > 0; --level) n = n->child[(key >> (level - 1)) & 1].get();
  return n ? &n->landmark : nullptr;
}

void SetLandmark(LandmarkTree& tree, int key, const LandmarkGaussian& landmark) {
  assert(key >= 0);
  while ((key >> tree.height) != 0) {  // grow: the old root becomes the new root's left child
    ++tree.height;
    if (tree.root) {
      auto root = std::make_shared<LandmarkTreeNode>();
      root->child[0] = std::move(tree.root);
      RecomputeBox(*root);
      tree.root = std::move(root);
    }
  }
  if (!FindLandmark(tree, key)) ++tree.size;
  SetIn(tree.root, tree.height, key, landmark);
}

void EraseLandmark(LandmarkTree& tree, int key) {
  if (!FindLandmark(tree, key)) return;
  --tree.size;
  EraseIn(tree.root, tree.height, key);
}

void ForEachLandmark(const LandmarkTree& tree, const std::function<void(int, const LandmarkGaussian&)>& fn) {
  ForEachIn(tree.root.get(), tree.height, 0, fn);
}

std::vector<int> LandmarksInBox(const LandmarkTree& tree, const Eigen::Vector2d& lo, const Eigen::Vector2d& hi) {
  std::vector<int> keys;
  BoxIn(tree.root.get(), tree.height, 0, lo, hi, keys);
  return keys;
}

size_t CountDistinctNodes(const std::vector<const LandmarkTree*>& trees) {
  std::unordered_set<const LandmarkTreeNode*> seen;
  std::vector<const LandmarkTreeNode*> stack;
  for (const LandmarkTree* t : trees)
    if (t->root) stack.push_back(t->root.get());
  while (!stack.empty()) {
    const LandmarkTreeNode* n = stack.back();
    stack.pop_back();
    if (!seen.insert(n).second) continue;  // shared subtree already counted
    for (const NodePtr& c : n->child)
      if (c) stack.push_back(c.get());
  }
  return seen.size();
}

}  // namespace slambox
