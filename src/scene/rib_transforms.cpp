// Transforms: Identity, Transform, ConcatTransform, Translate, Rotate, Scale, alone or as the keys
// of a motion block (a moving CTM); named ones: CoordinateSystem, ScopedCoordinateSystem and
// CoordSysTransform.
#include <algorithm>

#include "scene/rib_requests.h"

namespace streyes {

void keepCoordinateSystem(RenderSettings& settings, const std::string& name, const MotionTransform& objectToWorld) {
    Param p;
    p.name = "CoordinateSystem:" + name, p.type = ParamType::Matrix;
    const Matrix4& m = objectToWorld.keys().front();
    p.nums.assign(m.m.begin(), m.m.end());
    std::vector<Param>& options = settings.options.params;
    auto same = std::find_if(options.begin(), options.end(), [&](const Param& q) { return q.name == p.name; });
    if (same != options.end()) *same = std::move(p);
    else options.push_back(std::move(p));
}

void RibState::endScopedCoordinateSystems(Block& block) {
    // Latest first, so that a name scoped twice in one block gets back what it meant before both.
    for (auto it = block.scopedSpaces.rbegin(); it != block.scopedSpaces.rend(); ++it) {
        if (it->second) coordinateSystems[it->first] = *it->second;
        else coordinateSystems.erase(it->first);
    }
    block.scopedSpaces.clear();
}

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

// CoordinateSystem "name" / ScopedCoordinateSystem "name": the CTM kept under the name (a scoped
// one until the end of the innermost open block).
void coordinateSystem(RibParser& reader, RibArgs& args) {
    const std::string name = args.string("name");
    args.expectEnd();
    if (name.empty()) args.fail("the coordinate system's name is empty");
    RibState& s = reader.state();
    if (args.name() == "ScopedCoordinateSystem" && !s.blocks.empty()) {
        auto old = s.coordinateSystems.find(name);
        s.blocks.back().scopedSpaces.emplace_back(
            name, old == s.coordinateSystems.end() ? std::nullopt : std::optional<MotionTransform>(old->second));
    }
    s.coordinateSystems[name] = s.ctm;
    if (s.world == RibState::World::Before && !s.fragment) {
        s.cameraSpaces.insert(name);  // camera-relative until WorldBegin
    } else {
        s.cameraSpaces.erase(name);
        if (!s.defining) keepCoordinateSystem(reader.scene().settings, name, s.ctm);
    }
}

// CoordSysTransform "name": the CTM becomes the named system's ("world", "camera" and the names
// CoordinateSystem gave). An unknown name warns once and leaves the CTM as it is.
void coordSysTransform(RibParser& reader, RibArgs& args) {
    const std::string name = args.string("name");
    args.expectEnd();
    RibState& s = reader.state();
    const bool before = s.world == RibState::World::Before && !s.fragment;
    auto known = s.coordinateSystems.find(name);
    if (known != s.coordinateSystems.end()) {
        // Given before WorldBegin and asked for inside the world: already made world-relative then.
        s.applyTransform(known->second, true, args.loc());
        return;
    }
    if (name == "world" && !before) {
        s.applyTransform(MotionTransform(), true, args.loc());
        return;
    }
    if (name == "camera") {
        if (before) {
            s.applyTransform(MotionTransform(), true, args.loc());
        } else {  // camera to world: the camera transform's inverse
            const MotionTransform& w2c = reader.scene().camera.worldToCamera;
            std::vector<Matrix4> keys;
            for (const Matrix4& k : w2c.keys()) {
                Matrix4 inv;
                if (!invert(k, &inv)) args.fail("the camera transform is singular: camera space cannot be placed");
                keys.push_back(inv);
            }
            s.applyTransform(MotionTransform(w2c.times(), std::move(keys)), true, args.loc());
        }
        return;
    }
    reader.log().lenient("CoordSysTransform:" + name, args.loc(),
                         "CoordSysTransform: no coordinate system '" + name +
                             "' (name one with CoordinateSystem first; \"world\" and \"camera\" are known): the transform is unchanged");
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
    table.add("CoordinateSystem", {coordinateSystem, "CoordinateSystem \"name\"", anywhere});
    table.add("ScopedCoordinateSystem", {coordinateSystem, "ScopedCoordinateSystem \"name\"", anywhere});
    table.add("CoordSysTransform", {coordSysTransform, "CoordSysTransform \"name\"", anywhere});
}

}  // namespace streyes
