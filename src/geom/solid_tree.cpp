#include "geom/solid_tree.h"

namespace streyes {

SolidTree::SolidTree(const std::vector<SolidNode>& nodes) {
    nodes_.reserve(nodes.size());
    root_.resize(nodes.size());
    for (size_t i = 0; i < nodes.size(); ++i) {
        nodes_.push_back(Node{nodes[i].op, nodes[i].children});
        int r = int(i);
        while (nodes[size_t(r)].parent >= 0) r = nodes[size_t(r)].parent;
        root_[i] = r;
    }
}

bool SolidTree::inside(int n, const uint8_t* in) const {
    const Node& node = nodes_[size_t(n)];
    switch (node.op) {
        case SolidOp::Primitive:
            return in[n] != 0;
        case SolidOp::Union:
            for (int c : node.children)
                if (inside(c, in)) return true;
            return false;
        case SolidOp::Intersection:
            if (node.children.empty()) return false;
            for (int c : node.children)
                if (!inside(c, in)) return false;
            return true;
        case SolidOp::Difference:
            if (node.children.empty() || !inside(node.children.front(), in)) return false;
            for (size_t k = 1; k < node.children.size(); ++k)
                if (inside(node.children[k], in)) return false;
            return true;
    }
    return false;
}

}  // namespace streyes
