// Solids (RI Spec 3.2, section 5.9): SolidBegin "primitive" | "union" | "intersection" |
// "difference" ... SolidEnd. Each block is a node of a solid's tree (Scene::solids); the geometry
// of a "primitive" block bounds that leaf (Attributes::solid). A solid block saves and restores the
// attributes and the transform, as AttributeBegin does (Aqsis and PRMan alike).
//
// What the peers accept, streyes accepts with a warning (Aqsis warns and renders): geometry
// directly inside a non-primitive solid (drawn as a plain surface) and a solid inside a "primitive"
// one (made a solid of its own). What cannot be read is an error: an unknown operation, SolidEnd
// without its SolidBegin or closing another block, a SolidBegin outside the world block.
#include "scene/rib_requests.h"

namespace streyes {

namespace {

using BlockKind = RibState::BlockKind;

void solidBegin(RibParser& reader, RibArgs& args) {
    RibState& s = reader.state();
    const std::string operation = args.string("operation");
    args.expectEnd();
    SolidOp op;
    if (operation == "primitive") op = SolidOp::Primitive;
    else if (operation == "union") op = SolidOp::Union;
    else if (operation == "intersection") op = SolidOp::Intersection;
    else if (operation == "difference") op = SolidOp::Difference;
    else
        args.fail("unknown solid operation \"" + operation +
                  "\": SolidBegin takes \"primitive\", \"union\", \"intersection\" or \"difference\"");
    if (s.world != RibState::World::Inside)
        args.fail("SolidBegin belongs between WorldBegin and WorldEnd: a solid is geometry");
    s.blocks.push_back(RibState::Block{BlockKind::Solid, args.loc(), s.attributes, s.ctm, s.openSolid});
    int node = RibState::kNoSolidNode;
    if (s.defining || s.fragment) {
        // The tree is the scene's; an object or a procedural's output is a scene of its own.
        reader.log().lenient("solid:" + std::string(s.defining ? "object" : "procedural"), args.loc(),
                             std::string("SolidBegin inside ") +
                                 (s.defining ? "an ObjectBegin definition" : "a procedural's output") +
                                 " is not supported: its geometry is drawn as plain surfaces");
    } else {
        std::vector<SolidNode>& solids = reader.scene().solids;
        int parent = s.openSolid >= 0 ? s.openSolid : -1;
        if (parent >= 0 && solids[size_t(parent)].op == SolidOp::Primitive) {
            reader.log().lenient("solid:in-primitive", args.loc(),
                                 "a solid inside SolidBegin \"primitive\" (line " +
                                     std::to_string(solids[size_t(parent)].loc.line) +
                                     ") is not allowed (RI Spec 3.2, 5.9): made a solid of its own");
            parent = -1;
        }
        node = int(solids.size());
        solids.push_back(SolidNode{op, parent, {}, args.loc()});
        if (parent >= 0) solids[size_t(parent)].children.push_back(node);
    }
    s.openSolid = node;
    const int leaf = node >= 0 && op == SolidOp::Primitive ? node : -1;
    if (s.attributes->solid != leaf) s.mutableAttributes().solid = leaf;
}

void solidEnd(RibParser& reader, RibArgs& args) {
    RibState& s = reader.state();
    args.expectEnd();
    if (s.blocks.empty() || s.blocks.back().kind == BlockKind::World)
        args.fail("SolidEnd without a matching SolidBegin");
    const RibState::Block& open = s.blocks.back();
    if (open.kind != BlockKind::Solid)
        args.fail(std::string("SolidEnd does not match the ") + RibState::beginName(open.kind) + " at line " +
                  std::to_string(open.begin.line) + ": close that with " + RibState::endName(open.kind) + " first");
    s.attributes = open.attributes;
    s.ctm = open.ctm;
    s.openSolid = open.outerSolid;
    s.endScopedCoordinateSystems(s.blocks.back());
    s.blocks.pop_back();
}

}  // namespace

void addSolidRequests(RibRequestTable& table) {
    table.add("SolidBegin", {solidBegin, "SolidBegin \"primitive\"|\"union\"|\"intersection\"|\"difference\""});
    table.add("SolidEnd", {solidEnd, "SolidEnd"});
}

void RibParser::checkSolidGeometry(const RibRequest& request) {
    if (state_.openSolid < 0) return;
    const SolidNode& node = scene_.solids[size_t(state_.openSolid)];
    if (node.op == SolidOp::Primitive) return;
    static const char* names[] = {"primitive", "union", "intersection", "difference"};
    log_.lenient("solid:geometry", request.loc,
                 request.name + " directly inside SolidBegin \"" + names[int(node.op)] + "\" (line " +
                     std::to_string(node.loc.line) +
                     ") is not part of a solid: geometry belongs in a \"primitive\" solid (RI Spec 3.2, 5.9); drawn "
                     "as a plain surface");
}

}  // namespace streyes
