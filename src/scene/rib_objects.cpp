// Retained objects: ObjectBegin handle ... ObjectEnd defines an object, ObjectInstance handle
// places it. Handles are numbers (RI 3.2's RIB form, `ObjectBegin 1`) or strings (the named form,
// `ObjectBegin "tree"`).
//
// An object holds geometry, in its own space: the transforms inside the block place its
// primitives relative to one another, starting from identity. An instance is the object under the
// transform and attributes in force at ObjectInstance (its own motion too: a MotionBegin block of
// transforms before it), with the attributes set inside the definition over them, as Aqsis and
// the exporters that write them (K-3D) expect: the requests that set them are kept with the
// attribute state they made (RibParser::dispatch) and replayed over each instance's attributes.
// Instances share the object: the scene keeps it once, and an instance is a procedural
// (procedural.h) whose bound is the object's, culled before it is expanded.
#include <algorithm>
#include <limits>
#include <set>

#include "scene/rib_requests.h"

namespace streyes {

namespace {

// A handle as written: a whole number or a string.
std::string readHandle(RibArgs& args) {
    if (args.done()) args.fail("missing the object handle");
    const RibValue& v = args.take();
    if (v.isString()) return "\"" + v.strings[0] + "\"";
    if (v.isNumber() && isWholeInt(v.nums[0])) return formatNumber(v.nums[0]);
    args.fail(v, "the object handle must be a whole number or a string, got " + describeValue(v));
}

// Object-space box of points under every key of a transform.
void extendBy(Bounds3d& box, const std::vector<Vec3d>& points, const MotionTransform& xf) {
    for (const Matrix4& m : xf.keys())
        for (const Vec3d& p : points) box.extend(m.point(p));
}

void extendByBox(Bounds3d& box, const Bounds3d& b, const MotionTransform& xf) {
    if (b.empty()) return;
    std::vector<Vec3d> corners;
    for (int i = 0; i < 8; ++i)
        corners.push_back({(i & 1) ? b.hi.x : b.lo.x, (i & 2) ? b.hi.y : b.lo.y, (i & 4) ? b.hi.z : b.lo.z});
    extendBy(box, corners, xf);
}

// A box around a quadric at one key (whole sweep: the angles only shrink it).
Bounds3d quadricBox(QuadricKind kind, const std::array<double, 7>& a) {
    auto box = [](double r, double z0, double z1) {
        return Bounds3d({-r, -r, std::min(z0, z1)}, {r, r, std::max(z0, z1)});
    };
    switch (kind) {
    case QuadricKind::Sphere: return box(std::fabs(a[0]), std::max(-std::fabs(a[0]), std::min(a[1], a[2])),
                                         std::min(std::fabs(a[0]), std::max(a[1], a[2])));
    case QuadricKind::Cylinder: return box(std::fabs(a[0]), a[1], a[2]);
    case QuadricKind::Cone: return box(std::fabs(a[1]), 0, a[0]);
    case QuadricKind::Disk: return box(std::fabs(a[1]), a[0], a[0]);
    case QuadricKind::Paraboloid: return box(std::fabs(a[0]), a[1], a[2]);
    case QuadricKind::Hyperboloid:  // the radius along a line is convex: largest at an end
        return box(std::max(std::hypot(a[0], a[1]), std::hypot(a[3], a[4])), a[2], a[5]);
    case QuadricKind::Torus: return box(std::fabs(a[0]) + std::fabs(a[1]), -std::fabs(a[1]), std::fabs(a[1]));
    }
    return {};
}

// The object's bound in its own space: every control point (curved surfaces lie in the hull of
// theirs), every quadric's box and every nested procedural's bound, under their transforms.
Bounds3d objectBound(const Scene& s) {
    Bounds3d box;
    for (const BilinearPatchDesc& p : s.patches)
        for (const auto& key : p.P) extendBy(box, {key.begin(), key.end()}, p.objectToWorld);
    for (const PatchMeshDesc& p : s.patchMeshes)
        for (const auto& key : p.P) extendBy(box, key, p.objectToWorld);
    for (const SubdivisionMeshDesc& p : s.subdivisionMeshes)
        for (const auto& key : p.P) extendBy(box, key, p.objectToWorld);
    for (const PolygonMeshDesc& p : s.polygonMeshes)
        for (const auto& key : p.P) extendBy(box, key, p.objectToWorld);
    for (const NuPatchDesc& p : s.nuPatches)
        for (const auto& key : p.P) extendBy(box, key, p.objectToWorld);
    for (const QuadricDesc& q : s.quadrics)
        for (const auto& key : q.params) extendByBox(box, quadricBox(q.kind, key), q.objectToWorld);
    for (const ProceduralDesc& p : s.procedurals) extendByBox(box, p.bound, p.objectToWorld);
    // Ribbons and discs reach half their widest width beyond their points (a cubic curve lies in
    // the hull of its control points).
    auto grown = [&](const std::vector<std::vector<Vec3d>>& keys, const std::vector<double>& width,
                     const MotionTransform& xf) {
        double r = 0;
        for (double w : width) r = std::max(r, 0.5 * w);
        for (const auto& key : keys) {
            Bounds3d b;
            for (const Vec3d& q : key) b.extend(q);
            if (!b.empty()) extendByBox(box, Bounds3d(b.lo - Vec3d(r, r, r), b.hi + Vec3d(r, r, r)), xf);
        }
    };
    for (const CurvesDesc& c : s.curves) grown(c.P, c.width, c.objectToWorld);
    for (const PointsDesc& p : s.points) grown(p.P, p.width, p.objectToWorld);
    return box;
}

void objectBegin(RibParser& reader, RibArgs& args) {
    RibState& s = reader.state();
    const std::string handle = readHandle(args);
    args.expectEnd();
    if (s.defining)
        args.fail("ObjectBegin inside the definition of object " + s.defining->handle + " (line " +
                  std::to_string(s.defining->begin.line) + "): close it with ObjectEnd first");
    s.defining = RibState::ObjectDefinition{handle, args.loc(), std::make_shared<Scene>(), s.ctm, s.attributes,
                                            s.blocks.size(), {}};
    s.defining->object->sourceName = reader.scene().sourceName;
    s.ctm = MotionTransform();  // the object's own space
}

void objectEnd(RibParser& reader, RibArgs& args) {
    RibState& s = reader.state();
    args.expectEnd();
    if (!s.defining) args.fail("ObjectEnd without ObjectBegin");
    if (s.blocks.size() > s.defining->blocks) {
        const RibState::Block& open = s.blocks.back();
        throw InputError(open.begin, std::string(RibState::beginName(open.kind)) + " is never closed: ObjectEnd (line " +
                                         std::to_string(args.loc().line) + ") comes before its " +
                                         RibState::endName(open.kind));
    }
    RibState::ObjectDefinition def = std::move(*s.defining);
    s.defining.reset();
    s.ctm = def.ctm;
    s.attributes = def.attributes;
    if (!def.object->lights.empty())
        throw InputError(def.object->lights.front().loc,
                         "a light inside ObjectBegin " + def.handle + " (line " + std::to_string(def.begin.line) +
                             "): an object holds geometry only; declare the light outside the object");
    if (objectBound(*def.object).empty())
        reader.log().warnOnce("object-empty:" + def.handle, def.begin,
                              "object " + def.handle + " holds no geometry: its instances draw nothing");
    if (s.objects.count(def.handle))
        reader.log().warnOnce("object-redefined:" + def.handle, def.begin,
                              "object " + def.handle + " is defined again: later instances use this definition");
    // Only the states the object's primitives hold matter to its instances.
    std::set<const Attributes*> held;
    auto hold = [&](const auto& prims) {
        for (const auto& p : prims) held.insert(p.attributes.get());
    };
    const Scene& o = *def.object;
    hold(o.patches), hold(o.procedurals), hold(o.patchMeshes), hold(o.subdivisionMeshes), hold(o.quadrics);
    hold(o.polygonMeshes), hold(o.curves), hold(o.points), hold(o.nuPatches);
    RibState::AttributeEdits& edits = s.objectEdits[def.handle];
    edits.clear();
    for (auto& e : def.edits)
        if (held.count(e.first.get())) edits.push_back(std::move(e));
    s.objects[def.handle] = std::move(def.object);
    for (auto it = s.instanceAttributes.begin(); it != s.instanceAttributes.end();)
        it = it->first.first == def.handle ? s.instanceAttributes.erase(it) : std::next(it);
}

// The object's attribute states as this instance takes them: the requests of the definition that
// made each, replayed over the attributes in force now (with the current transform as "shader"
// space for shaders set inside the definition). Made once per attribute state instanced under.
std::vector<std::pair<AttributesPtr, AttributesPtr>> instanceAttributes(RibParser& reader, const std::string& handle) {
    RibState& s = reader.state();
    const RibState::AttributeEdits& edits = s.objectEdits[handle];
    if (edits.empty()) return {};
    auto& cached = s.instanceAttributes[{handle, s.attributes.get()}];
    if (cached.first == s.attributes) return cached.second;
    const std::shared_ptr<Attributes> instanced = s.attributes;
    std::vector<std::pair<AttributesPtr, AttributesPtr>> made;
    for (const auto& [state, requests] : edits) {
        s.attributes = instanced;  // shared: the first change copies it
        for (const RibRequest& r : requests) reader.replay(r);
        made.emplace_back(state, s.attributes);
    }
    s.attributes = instanced;
    cached = {instanced, made};
    return made;
}

void objectInstance(RibParser& reader, RibArgs& args) {
    RibState& s = reader.state();
    const std::string handle = readHandle(args);
    args.expectEnd();
    auto it = s.objects.find(handle);
    if (it == s.objects.end()) {
        const bool open = s.defining && s.defining->handle == handle;
        args.fail("ObjectInstance " + handle + ": " +
                  (open ? std::string("the object is still being defined (an object cannot hold itself)")
                        : "no object " + handle + " is defined: ObjectBegin " + handle + " ... ObjectEnd must come first"));
    }
    const Bounds3d bound = objectBound(*it->second);
    if (bound.empty()) return;  // warned at ObjectEnd
    ProceduralDesc p;
    p.kind = "ObjectInstance";
    p.args = {handle};
    p.bound = bound;
    p.objectToWorld = s.ctm;
    p.attributes = s.attributes;
    p.loc = args.loc();
    p.object = it->second;
    p.objectAttributes = instanceAttributes(reader, handle);
    reader.scene().procedurals.push_back(std::move(p));
}

}  // namespace

void addObjectRequests(RibRequestTable& table) {
    table.add("ObjectBegin", {objectBegin, "ObjectBegin handle", RibPhase::World});
    table.add("ObjectEnd", {objectEnd, "ObjectEnd", RibPhase::World});
    table.add("ObjectInstance", {objectInstance, "ObjectInstance handle", RibPhase::World});
}

}  // namespace streyes
