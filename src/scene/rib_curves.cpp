// Curves and Points: ribbons along curves and camera-facing discs, with their widths, normals and
// colours, alone or as the keys of a motion block.
#include <algorithm>

#include "scene/rib_geometry.h"

namespace streyes {

namespace {

// The parameters read here, apart from P and Cs: the rest are checked for size and warned about.
ParamList withoutHandled(const ParamList& params, std::initializer_list<const char*> handled) {
    ParamList rest;
    for (const Param& p : params.params)
        if (std::none_of(handled.begin(), handled.end(), [&](const char* n) { return p.name == n; }))
            rest.params.push_back(p);
    return rest;
}

// "width" (by its class, counted in `counts`) or "constantwidth": non-negative floats. Absent: 1.
void readWidth(const RibArgs& args, const ParamList& params, const ClassCounts& counts, ParamClass* cls,
               std::vector<double>* width) {
    const Param* w = params.find("width");
    const Param* cw = params.find("constantwidth");
    if (w && cw) args.failAt(cw->loc.line, "give either \"width\" or \"constantwidth\", not both", false);
    const Param* p = w ? w : cw;
    if (!p) return;
    if (p->type != ParamType::Float || p->arraySize != 1)
        args.failAt(p->loc.line, "\"" + p->name + "\" must be declared as a float", false);
    if (cw && p->cls != ParamClass::Constant)
        args.failAt(p->loc.line, "\"constantwidth\" must be constant", false);
    if (w && p->cls != ParamClass::Varying && p->cls != ParamClass::Vertex)
        args.failAt(p->loc.line, "\"width\" must be varying or vertex", false);
    checkCount(args, *p, counts.of(p->cls));
    for (size_t i = 0; i < p->nums.size(); ++i)
        if (!(p->nums[i] >= 0))
            args.failAt(p->loc.line,
                        "\"" + p->name + "\" value " + std::to_string(i) + " is " + formatNumber(p->nums[i]) +
                            ": widths must be at least 0",
                        false);
    *cls = p->cls;
    *width = p->nums;
}

// One key of Curves.
bool readCurvesKey(RibParser& reader, RibArgs& args, CurvesDesc* d) {
    const RibValue* typeValue = args.peek();
    const std::string type = args.string("type");
    if (type != "linear" && type != "cubic")
        args.fail(*typeValue, "the curve type must be \"linear\" or \"cubic\", got \"" + type + "\"");
    d->cubic = type == "cubic";
    const RibValue* countsValue = args.peek();
    d->nvertices = intArray(args, "nvertices", 1);
    const RibValue* wrapValue = args.peek();
    const std::string wrap = args.string("wrap");
    if (wrap != "periodic" && wrap != "nonperiodic")
        args.fail(*wrapValue, "the wrap must be \"periodic\" or \"nonperiodic\", got \"" + wrap + "\"");
    d->periodic = wrap == "periodic";
    d->basis = reader.state().attributes->vBasis;
    if (d->nvertices.empty()) {
        args.skipRest();
        emptyPrimitive(reader, args, 0, "curves");
        return false;
    }
    const int step = d->basis.step;
    for (size_t i = 0; i < d->nvertices.size(); ++i) {
        const int n = d->nvertices[i];
        std::string why;
        if (!d->cubic && n < 2) why = "a linear curve needs at least 2";
        if (d->cubic && !d->periodic && (n < 4 || (n - 4) % step != 0))
            why = "a nonperiodic cubic curve needs 4 plus a multiple of the basis step (" + std::to_string(step) + ")";
        if (d->cubic && d->periodic && n % step != 0)
            why = "a periodic cubic curve needs a multiple of the basis step (" + std::to_string(step) + ")";
        if (!why.empty())
            args.fail(*countsValue, "curve " + std::to_string(i) + " has " + std::to_string(n) + " vertices: " + why);
    }
    ParamList params = reader.readParams(args);
    const Param& pos = positionParam(args, params);
    ClassCounts counts;
    counts.uniform = d->nvertices.size();
    counts.vertex = sum(d->nvertices);
    counts.varying = counts.faceVarying = 0;
    for (size_t i = 0; i < d->nvertices.size(); ++i) counts.varying += size_t(d->varying(i));
    counts.faceVarying = counts.varying;
    checkCount(args, pos, counts.vertex);
    d->P = {pointsOf(args, pos)};
    d->Cs = readColors(args, params, counts);
    readWidth(args, params, counts, &d->widthClass, &d->width);
    if (const Param* N = params.find("N")) {
        if (N->type != ParamType::Normal || N->arraySize != 1)
            args.failAt(N->loc.line, "\"N\" must be declared as a normal", false);
        if (N->cls != ParamClass::Varying && N->cls != ParamClass::Vertex)
            args.failAt(N->loc.line, "\"N\" on Curves must be varying or vertex", false);
        checkCount(args, *N, counts.of(N->cls));
        d->normalClass = N->cls;
        for (size_t i = 0; i + 2 < N->nums.size(); i += 3) d->N.emplace_back(N->nums[i], N->nums[i + 1], N->nums[i + 2]);
    }
    d->primvars = otherParams(args, withoutHandled(params, {"width", "constantwidth", "N"}), counts, reader.log());
    return true;
}

void curvesKeys(RibParser& reader, const RibKeys& keys) {
    auto sameShape = [](const CurvesDesc& k, const CurvesDesc& f) {
        return k.cubic == f.cubic && k.periodic == f.periodic && k.nvertices == f.nvertices;
    };
    auto positions = [](CurvesDesc& d) -> auto& { return d.P; };
    if (auto d = mergeKeys<CurvesDesc>(reader, keys, readCurvesKey, sameShape, "type, nvertices and wrap", positions))
        reader.scene().curves.push_back(std::move(*d));
}

// One key of Points.
bool readPointsKey(RibParser& reader, RibArgs& args, PointsDesc* d) {
    ParamList params = reader.readParams(args);
    const Param& pos = positionParam(args, params);
    const size_t n = pos.nums.size() / size_t(pos.componentsPerItem());
    if (emptyPrimitive(reader, args, n, "points")) return false;
    ClassCounts counts;
    counts.uniform = 1;
    counts.varying = counts.vertex = counts.faceVarying = n;
    checkCount(args, pos, n);
    d->P = {pointsOf(args, pos)};
    d->Cs = readColors(args, params, counts);
    ParamClass cls = ParamClass::Constant;
    readWidth(args, params, counts, &cls, &d->width);
    d->primvars = otherParams(args, withoutHandled(params, {"width", "constantwidth"}), counts, reader.log());
    return true;
}

void pointsKeys(RibParser& reader, const RibKeys& keys) {
    auto sameShape = [](const PointsDesc& k, const PointsDesc& f) { return k.P[0].size() == f.P[0].size(); };
    auto positions = [](PointsDesc& d) -> auto& { return d.P; };
    if (auto d = mergeKeys<PointsDesc>(reader, keys, readPointsKey, sameShape, "number of points", positions))
        reader.scene().points.push_back(std::move(*d));
}

}  // namespace

void addCurveRequests(RibRequestTable& table) {
    const RibPhase world = RibPhase::World;
    table.add("Curves", {oneKey<curvesKeys>,
                         "Curves \"linear\"|\"cubic\" [nvertices] \"nonperiodic\"|\"periodic\" \"P\" [...] "
                         "\"width\"|\"constantwidth\" [...]",
                         world, curvesKeys});
    table.add("Points", {oneKey<pointsKeys>, "Points \"P\" [...] \"width\"|\"constantwidth\" [...]", world, pointsKeys});
}

}  // namespace streyes
