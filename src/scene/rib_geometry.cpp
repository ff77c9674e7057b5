#include "scene/rib_geometry.h"

namespace streyes {

// ---- Primitive variables ----------------------------------------------------------------------------
size_t ClassCounts::of(ParamClass c) const {
    switch (c) {
    case ParamClass::Constant: return 1;
    case ParamClass::Uniform: return uniform;
    case ParamClass::Varying: return varying;
    case ParamClass::Vertex: return vertex;
    case ParamClass::FaceVarying: return faceVarying;
    }
    return 1;
}

namespace {
size_t valueCount(const Param& p) { return p.type == ParamType::String ? p.strings.size() : p.nums.size(); }
}  // namespace

void checkCount(const RibArgs& args, const Param& p, size_t items) {
    size_t expected = items * size_t(p.componentsPerItem());
    if (valueCount(p) == expected) return;
    std::string unit = p.type == ParamType::String ? "value" : "number";
    std::string item = std::string(paramClassName(p.cls)) + " " + paramTypeName(p.type);
    if (p.arraySize != 1) item += "[" + std::to_string(p.arraySize) + "]";
    std::string detail = plural(items, item);
    if (p.componentsPerItem() > 1) detail += " of " + plural(size_t(p.componentsPerItem()), unit) + " each";
    args.failAt(p.loc.line,
                "parameter '" + p.name + "' has " + plural(valueCount(p), unit) + ", expected " +
                    std::to_string(expected) + " (" + detail + ")",
                false);
}

// The positions: "P" (x y z) or "Pw" (x y z w) per vertex, declared as such.
const Param& positionParam(const RibArgs& args, const ParamList& params) {
    if (const Param* pz = params.find("Pz"))
        args.failAt(pz->loc.line, "\"Pz\" is not supported: give \"P\" with x y z for every vertex", false);
    const Param* P = params.find("P");
    const Param* Pw = params.find("Pw");
    if (P && Pw) args.failAt(Pw->loc.line, "give either \"P\" or \"Pw\", not both", false);
    if (!P && !Pw) args.fail("missing \"P\": give x y z for every vertex (or \"Pw\" with x y z w)");
    const Param& pos = P ? *P : *Pw;
    if (pos.type != (P ? ParamType::Point : ParamType::HPoint) || pos.arraySize != 1)
        args.failAt(pos.loc.line, "\"" + pos.name + "\" must be declared as " + (P ? "point" : "hpoint"), false);
    return pos;
}

std::vector<Vec3d> pointsOf(const RibArgs& args, const Param& pos) {
    const size_t per = size_t(pos.componentsPerItem());
    std::vector<Vec3d> points(pos.nums.size() / per);
    for (size_t i = 0; i < points.size(); ++i) {
        const double* v = &pos.nums[i * per];
        if (per == 4 && v[3] == 0)
            args.failAt(pos.loc.line, "\"Pw\" vertex " + std::to_string(i) + " has w = 0", false);
        points[i] = per == 4 ? Vec3d(v[0] / v[3], v[1] / v[3], v[2] / v[3]) : Vec3d(v[0], v[1], v[2]);
    }
    return points;
}

// "Cs", if given: a color with as many values as its class has items here.
ColorPrimvar readColors(const RibArgs& args, const ParamList& params, const ClassCounts& counts) {
    ColorPrimvar c;
    const Param* cs = params.find("Cs");
    if (!cs) return c;
    if (cs->type != ParamType::Color || cs->arraySize != 1)
        args.failAt(cs->loc.line, "\"Cs\" must be declared as a color", false);
    checkCount(args, *cs, counts.of(cs->cls));
    c.cls = cs->cls;
    for (size_t i = 0; i + 2 < cs->nums.size(); i += 3)
        c.values.emplace_back(float(cs->nums[i]), float(cs->nums[i + 1]), float(cs->nums[i + 2]));
    return c;
}

ParamList otherParams(const RibArgs& args, const ParamList& params, const ClassCounts& counts, Log& log,
                      bool perVertex, bool mesh) {
    ParamList out;
    for (const Param& p : params.params) {
        if (p.name == "P" || p.name == "Pw" || p.name == "Cs") continue;
        checkCount(args, p, counts.of(p.cls));
        const bool st = p.name == "st" && p.type == ParamType::Float && p.arraySize == 2;
        const bool typed = st || (p.arraySize == 1 && (p.type == ParamType::Float || p.type == ParamType::Color ||
                                                       p.type == ParamType::Point || p.type == ParamType::Vector ||
                                                       p.type == ParamType::Normal || p.type == ParamType::String));
        const bool whole = p.cls == ParamClass::Constant || (p.cls == ParamClass::Uniform && counts.uniform == 1);
        // Per-vertex classes whose values are the face's corners (not a bicubic patch's 16 vertex values).
        const bool corners = perVertex && p.type != ParamType::String &&
                             (p.cls == ParamClass::Varying || p.cls == ParamClass::Vertex || p.cls == ParamClass::FaceVarying) &&
                             counts.of(p.cls) == counts.varying;
        const bool faces = mesh && p.type != ParamType::String && p.cls != ParamClass::Constant;
        if (typed && (whole || corners || faces)) {
            Param q = p;
            if (whole) q.cls = ParamClass::Constant;
            if (q.type == ParamType::String && q.strings.size() > 1) q.strings.resize(1);
            out.params.push_back(std::move(q));
            continue;
        }
        log.warnOnce("geometry-param:" + p.name, p.loc,
                     "parameter '" + p.name + "' on " + args.name() +
                         " is not bound to shaders yet (primitive variables are: float, color, point, vector, normal and string ones "
                         "constant over the primitive, and uniform, varying, vertex or facevarying floats and colours "
                         "on polygons, polygon meshes, patches, patch meshes, subdivision meshes and quadrics): ignored");
    }
    return out;
}

bool emptyPrimitive(RibParser& reader, const RibArgs& args, size_t items, const char* what) {
    if (items > 0) return false;
    reader.log().lenient("empty:" + args.name(), args.loc(), args.name() + " has no " + what + ": nothing is drawn");
    return true;
}

// A bracketed array of whole numbers, each at least `min`.
std::vector<int> intArray(RibArgs& args, const std::string& what, int min) {
    if (args.done()) args.fail("missing " + what + " (an array of whole numbers)");
    const RibValue& v = args.take();
    if (v.kind != RibValue::Kind::Array || !v.isNumericArray())
        args.fail(v, what + " must be an array of whole numbers, got " + describeValue(v));
    std::vector<int> out;
    for (double x : v.nums) {
        if (!isWholeInt(x) || x < min)
            args.fail(v, what + " must hold whole numbers of at least " + std::to_string(min) + ", got " +
                             formatNumber(x));
        out.push_back(int(x));
    }
    return out;
}

const RibValue& takeArray(RibArgs& args, const std::string& what, bool strings) {
    if (args.done()) args.fail("missing " + what);
    const RibValue& v = args.take();
    if (v.kind != RibValue::Kind::Array || (strings ? !v.isStringArray() : !v.isNumericArray()))
        args.fail(v, what + " must be an array of " + (strings ? "strings" : "numbers") + ", got " + describeValue(v));
    return v;
}

std::string indexCount(size_t n) { return std::to_string(n) + (n == 1 ? " index" : " indices"); }

size_t sum(const std::vector<int>& v) {
    size_t s = 0;
    for (int x : v) s += size_t(x);
    return s;
}

// ---- A single face --------------------------------------------------------------------------------
bool readFaceKey(RibParser& reader, RibArgs& args, bool polygon, FaceKey* key) {
    ParamList params = reader.readParams(args);
    const Param& pos = positionParam(args, params);
    const size_t perVertex = size_t(pos.componentsPerItem());
    size_t vertices = 4;
    if (polygon) {
        if (pos.nums.size() % perVertex != 0)
            args.failAt(pos.loc.line,
                        "parameter '" + pos.name + "' has " + plural(pos.nums.size(), "number") +
                            ", which is not a whole number of vertices (" + std::to_string(perVertex) +
                            " numbers each)",
                        false);
        vertices = pos.nums.size() / perVertex;
        if (vertices < 3) args.fail("a polygon needs at least 3 vertices, got " + std::to_string(vertices));
        if (vertices > 4) return false;
    }
    // Every count first, then the values: a wrong count is reported before a bad value.
    const ClassCounts counts = ClassCounts::face(vertices);
    checkCount(args, pos, vertices);
    for (const Param& p : params.params)
        if (&p != &pos) checkCount(args, p, counts.of(p.cls));
    key->P = pointsOf(args, pos);
    key->Cs = readColors(args, params, counts);
    key->vertexCs.clear();
    if (key->Cs.given()) {
        const bool perVertexCs = counts.of(key->Cs.cls) > 1;
        for (size_t i = 0; i < vertices; ++i) key->vertexCs.push_back(key->Cs.values[perVertexCs ? i : 0]);
    }
    key->primvars = otherParams(args, params, counts, reader.log(), true);
    return true;
}

bool faceKeysMove(Log& log, const std::vector<FaceKey>& keys, const SourceLoc& loc) {
    const FaceKey& first = keys.front();
    bool moves = false;
    for (const FaceKey& k : keys) moves = moves || k.P != first.P;
    for (const FaceKey& k : keys) {
        if (k.P.size() != first.P.size())
            throw InputError(loc, "the polygons in a motion block must have the same number of vertices (" +
                                      std::to_string(first.P.size()) + " and " + std::to_string(k.P.size()) + ")");
        if (k.vertexCs != first.vertexCs)
            log.warnOnce("motion:Cs", loc, "Cs does not change over motion keys: using the first key's");
    }
    return moves;
}

// ---- Area lights ----------------------------------------------------------------------------------
void shapeAreaLight(RibParser& reader, const std::vector<std::array<Vec3d, 4>>& patches, const SourceLoc& loc,
                    const std::string& what) {
    const int li = reader.state().attributes->areaLight;
    if (li < 0) return;
    if (patches.empty()) {
        reader.log().warnOnce("arealight-shape:" + what, loc,
                              what + " does not shape an area light (bilinear patches, polygons, spheres, cylinders, "
                                     "cones and disks do): it is drawn, but the light is not spread over it");
        return;
    }
    const Matrix4 m = reader.state().ctm.keys().front();
    std::vector<std::array<Vec3d, 4>>& shape = reader.scene().lights[size_t(li)].areaPatches;
    for (const std::array<Vec3d, 4>& p : patches) shape.push_back({m.point(p[0]), m.point(p[1]), m.point(p[2]), m.point(p[3])});
}

// ---- One primitive from the keys of a motion block -----------------------------------------------
void placePrimitive(const RibParser& reader, PrimitiveDesc& d, std::vector<double> times, const SourceLoc& loc) {
    d.times = std::move(times);
    d.objectToWorld = reader.state().ctm;
    d.attributes = reader.state().attributes;
    d.loc = loc;
}

void warnIfColorsDiffer(Log& log, const ColorPrimvar& key, const ColorPrimvar& first, const SourceLoc& loc) {
    if (key.cls != first.cls || key.values != first.values)
        log.warnOnce("motion:Cs", loc, "Cs does not change over motion keys: using the first key's");
}

void keysDiffer(const RibKeys& keys, const std::string& what) {
    const RibRequest& first = keys.requests.front();
    throw InputError(first.loc, "the " + first.name + " requests of a motion block must have the same " + what);
}

}  // namespace streyes
