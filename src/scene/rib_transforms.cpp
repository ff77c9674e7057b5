// Transforms: Identity, Transform, ConcatTransform, Translate, Rotate, Scale, alone or as the keys
// of a motion block (a moving CTM).
#include "scene/rib_requests.h"

namespace streyes {

// Row vectors: the request's matrix applies to points first, so CTM(t) = R(t) * CTM(t).
void RibState::applyTransform(const MotionTransform& request, bool replaces, const SourceLoc& loc) {
    MotionTransform result = replaces ? request : request.then(ctm);
    for (const Matrix4& m : result.keys())
        if (!m.isFinite())
            throw InputError(loc, "the transform overflows: its matrix has values beyond the range of doubles");
    ctm = std::move(result);
}

namespace {

// The request's matrix; *replaces says whether it replaces the CTM (Identity, Transform).
Matrix4 readTransformMatrix(RibArgs& args, bool* replaces) {
    const std::string& name = args.name();
    Matrix4 m;
    *replaces = name == "Identity" || name == "Transform";
    if (name == "Transform" || name == "ConcatTransform") {
        std::vector<double> v = args.numbers(16, "a 4x4 matrix, row by row");
        m = Matrix4::fromRowMajor(v.data());
    } else if (name == "Translate") {
        std::vector<double> v = args.numbers(3, "dx dy dz");
        m = Matrix4::translate({v[0], v[1], v[2]});
    } else if (name == "Rotate") {
        std::vector<double> v = args.numbers(4, "angle dx dy dz");
        if (v[1] == 0 && v[2] == 0 && v[3] == 0) args.fail("the rotation axis (dx dy dz) is zero");
        m = Matrix4::rotate(v[0], {v[1], v[2], v[3]});
    } else if (name == "Scale") {
        std::vector<double> v = args.numbers(3, "sx sy sz");
        m = Matrix4::scale({v[0], v[1], v[2]});
    }
    args.expectEnd();
    Matrix4 inverse;
    if (!m.isFinite() || !invert(m, &inverse) || !inverse.isFinite())
        args.failAt(args.loc().line,
                    "the transform is singular (it flattens space, e.g. a zero scale): streyes needs invertible "
                    "transforms",
                    false);
    return m;
}

void transformRequest(RibParser& reader, RibArgs& args) {
    bool replaces = false;
    Matrix4 m = readTransformMatrix(args, &replaces);
    reader.state().applyTransform(MotionTransform(m), replaces, args.loc());
}

void transformKeys(RibParser& reader, const RibKeys& keys) {
    std::vector<Matrix4> matrices;
    bool replaces = false;
    for (const RibRequest& request : keys.requests) {
        RibArgs args(request, keys.usage);
        matrices.push_back(readTransformMatrix(args, &replaces));
    }
    reader.state().applyTransform(MotionTransform(keys.times, std::move(matrices)), replaces,
                                  keys.requests.front().loc);
}

}  // namespace

void addTransformRequests(RibRequestTable& table) {
    const RibPhase anywhere = RibPhase::Anywhere;
    table.add("Identity", {transformRequest, "Identity", anywhere, transformKeys});
    table.add("Transform", {transformRequest, "Transform [16 numbers]", anywhere, transformKeys});
    table.add("ConcatTransform", {transformRequest, "ConcatTransform [16 numbers]", anywhere, transformKeys});
    table.add("Translate", {transformRequest, "Translate dx dy dz", anywhere, transformKeys});
    table.add("Rotate", {transformRequest, "Rotate angle dx dy dz", anywhere, transformKeys});
    table.add("Scale", {transformRequest, "Scale sx sy sz", anywhere, transformKeys});
}

}  // namespace streyes
