// Solids' trees (SolidBegin ... SolidEnd, streyes/scene.h SolidNode) as the renderer evaluates
// them, and the walk that classifies one line of sight's surface crossings.
//
// A sample (or an eye ray) keeps every crossing of a solid's boundary nearer than its nearest
// opaque surface that belongs to no solid, each tagged with its leaf (the "primitive" solid it
// bounds) and whether it enters or leaves that leaf (its outside faces the eye or not, RI Spec
// 3.2: the inside of a solid is where its normals point away from). Walking them nearest first
// from outside everything, a crossing sets its leaf inside or outside, and is a surface of the
// result when it changes whether the line is inside its tree's root: it is drawn (composited as
// any surface, see-through or not), and the others are not. This is how Aqsis's hider resolves
// its samples too, there by toggling a leaf at each crossing; setting it by facing instead keeps
// a line that grazes a shared edge twice (two micropolygons, one crossing) right.
#pragma once

#include <cstdint>
#include <vector>

#include "streyes/scene.h"

namespace streyes {

class SolidTree {
  public:
    SolidTree() = default;
    explicit SolidTree(const std::vector<SolidNode>& nodes);
    bool empty() const { return nodes_.empty(); }
    size_t size() const { return nodes_.size(); }
    int rootOf(int node) const { return root_[size_t(node)]; }
    // Whether node n holds the point, with leaves' states in `in` (one byte a node).
    bool inside(int n, const uint8_t* in) const;

  private:
    struct Node {
        SolidOp op;
        std::vector<int> children;
    };
    std::vector<Node> nodes_;
    std::vector<int> root_;
};

// A fragment's tag (SampleFragment::solid): its leaf and whether it enters it; -1 for surfaces that
// bound no solid.
inline int32_t solidTag(int leaf, bool entering) { return int32_t(leaf) * 2 + (entering ? 1 : 0); }
inline int solidLeafOf(int32_t tag) { return int(tag >> 1); }
inline bool solidEnters(int32_t tag) { return (tag & 1) != 0; }

// One line of sight's walk through its crossings, nearest first (reset() before each line). Keeps
// its scratch from line to line: no allocation once it has seen the tree.
class SolidWalk {
  public:
    void reset(const SolidTree& tree) {
        tree_ = &tree;
        if (in_.size() != tree.size()) in_.assign(tree.size(), 0);
        for (int n : touched_) in_[size_t(n)] = 0;
        touched_.clear();
    }
    // A line that does not start outside everything (a shadow ray leaves a surface, maybe inside
    // a solid): leaf's state where it starts, set before the walk's crossings.
    void start(int leaf, bool inside) {
        in_[size_t(leaf)] = uint8_t(inside);
        touched_.push_back(leaf);
    }
    // The crossing of leaf `leaf`, entering it or leaving: whether it is a surface of the result
    // (the line goes in or out of the leaf's root there).
    bool cross(int leaf, bool entering) {
        uint8_t& s = in_[size_t(leaf)];
        if (s == uint8_t(entering)) return false;  // already on that side (a double crossing)
        const int root = tree_->rootOf(leaf);
        const bool before = tree_->inside(root, in_.data());
        s = uint8_t(entering);
        touched_.push_back(leaf);
        return tree_->inside(root, in_.data()) != before;
    }

  private:
    const SolidTree* tree_ = nullptr;
    std::vector<uint8_t> in_;    // per node: a leaf's inside state
    std::vector<int> touched_;   // leaves set since reset
};

}  // namespace streyes
