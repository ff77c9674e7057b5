// NURBS: NuPatch (a rational B-spline surface of any order, with its motion keys) and TrimCurve
// (loops of rational B-spline curves in the parameter space of the NuPatches that follow).
#include <algorithm>

#include "scene/rib_geometry.h"

namespace streyes {

namespace {

// Orders above this are refused: evaluation keeps its scratch on the stack (geom/nurbs.h's
// kMaxNurbsOrder; the scene stage cannot include it).
constexpr int kMaxOrder = 32;

// What a knot vector must be for n control points of an order, with the range [tmin, tmax] inside
// its valid part [knot[order - 1], knot[n]]. `what` names the direction ("u", "v", "trim curve 2").
void checkKnots(RibArgs& args, const RibValue& at, const std::string& what, int n, int order,
                const std::vector<double>& knot, double tmin, double tmax) {
    if (order < 1 || order > kMaxOrder)
        args.fail(at, what + " order must be 1 to " + std::to_string(kMaxOrder) + ", got " + std::to_string(order));
    if (n < order)
        args.fail(at, what + ": " + plural(size_t(n), "control point") + " are fewer than the order " +
                          std::to_string(order));
    if (knot.size() != size_t(n) + size_t(order))
        args.fail(at, what + " knots: " + plural(knot.size(), "value") + ", expected " + std::to_string(n + order) +
                          " (control points + order)");
    for (size_t i = 1; i < knot.size(); ++i)
        if (!(knot[i] >= knot[i - 1]))
            args.fail(at, what + " knots must not decrease: knot " + std::to_string(i) + " is " +
                              formatNumber(knot[i]) + " after " + formatNumber(knot[i - 1]));
    const double lo = knot[size_t(order - 1)], hi = knot[size_t(n)];
    if (!(lo < hi))
        args.fail(at, what + " knots leave no span between knot " + std::to_string(order - 1) + " and knot " +
                          std::to_string(n));
    if (!(tmin >= lo && tmax <= hi && tmin < tmax))
        args.fail(at, what + " range [" + formatNumber(tmin) + ", " + formatNumber(tmax) +
                          "] must be a non-empty part of the knots' range [" + formatNumber(lo) + ", " +
                          formatNumber(hi) + "]");
}

// One direction of a NuPatch: n order [knot] min max.
void readDirection(RibArgs& args, const char* axis, int* n, int* order, std::vector<double>* knot, double* tmin,
                   double* tmax) {
    const std::string a(axis);
    const RibValue* at = args.peek();
    *n = args.integer(("n" + a).c_str());
    *order = args.integer((a + "order").c_str());
    *knot = takeArray(args, a + "knot", false).nums;
    *tmin = args.number((a + "min").c_str());
    *tmax = args.number((a + "max").c_str());
    checkKnots(args, at ? *at : args.request().args.front(), a, *n, *order, *knot, *tmin, *tmax);
}

// One key: the knots and ranges, positions ("P", or homogeneous "Pw") and "Cs".
bool readNuPatchKey(RibParser& reader, RibArgs& args, NuPatchDesc* d) {
    readDirection(args, "u", &d->nu, &d->uorder, &d->uknot, &d->umin, &d->umax);
    readDirection(args, "v", &d->nv, &d->vorder, &d->vknot, &d->vmin, &d->vmax);
    ParamList params = reader.readParams(args);
    const Param& pos = positionParam(args, params);
    const size_t count = size_t(d->nu) * size_t(d->nv);
    checkCount(args, pos, count);
    d->w.assign(count, 1.0);
    if (pos.componentsPerItem() == 4)
        for (size_t i = 0; i < count; ++i) {
            d->w[i] = pos.nums[i * 4 + 3];
            // The convex hull property (the bound) and the evaluation need positive weights.
            if (!(d->w[i] > 0))
                args.failAt(pos.loc.line,
                            "\"Pw\" vertex " + std::to_string(i) + " has weight " + formatNumber(d->w[i]) +
                                ": NuPatch weights must be positive",
                            false);
        }
    d->P = {pointsOf(args, pos)};
    ClassCounts counts;
    counts.uniform = size_t(d->uSpans()) * size_t(d->vSpans());
    counts.varying = counts.faceVarying = size_t(d->uSpans() + 1) * size_t(d->vSpans() + 1);
    counts.vertex = count;
    d->Cs = readColors(args, params, counts);
    d->primvars = otherParams(args, params, counts, reader.log());
    d->trim = reader.state().attributes->trim;
    return true;
}

void nuPatchKeys(RibParser& reader, const RibKeys& keys) {
    auto sameShape = [](const NuPatchDesc& k, const NuPatchDesc& f) {
        return k.nu == f.nu && k.uorder == f.uorder && k.nv == f.nv && k.vorder == f.vorder && k.uknot == f.uknot &&
               k.vknot == f.vknot && k.umin == f.umin && k.umax == f.umax && k.vmin == f.vmin && k.vmax == f.vmax &&
               k.w == f.w;
    };
    auto positions = [](NuPatchDesc& d) -> auto& { return d.P; };
    const char* what = "sizes, orders, knots, ranges and weights";
    if (auto d = mergeKeys<NuPatchDesc>(reader, keys, readNuPatchKey, sameShape, what, positions))
        reader.scene().nuPatches.push_back(std::move(*d));
}

// TrimCurve [ncurves] [order] [knot] [min] [max] [n] [u] [v] [w]: nloops is the size of ncurves.
void trimCurve(RibParser& reader, RibArgs& args) {
    const std::vector<int> ncurves = intArray(args, "ncurves", 0);
    const RibValue* orderValue = args.peek();
    const std::vector<int> order = intArray(args, "order", 1);
    const std::vector<double> knot = takeArray(args, "knot", false).nums;
    const std::vector<double> tmin = takeArray(args, "min", false).nums;
    const std::vector<double> tmax = takeArray(args, "max", false).nums;
    const std::vector<int> n = intArray(args, "n", 1);
    const std::vector<double> u = takeArray(args, "u", false).nums;
    const std::vector<double> v = takeArray(args, "v", false).nums;
    const std::vector<double> w = takeArray(args, "w", false).nums;
    args.expectEnd();
    const size_t curves = sum(ncurves);
    auto need = [&](size_t have, size_t want, const char* what) {
        if (have != want)
            args.fail(what + std::string(" has ") + plural(have, "value") + ", expected " + std::to_string(want));
    };
    need(order.size(), curves, "order");
    need(tmin.size(), curves, "min");
    need(tmax.size(), curves, "max");
    need(n.size(), curves, "n");
    size_t knots = 0, points = 0;
    for (size_t c = 0; c < curves; ++c) knots += size_t(n[c]) + size_t(order[c]), points += size_t(n[c]);
    need(knot.size(), knots, "knot");
    need(u.size(), points, "u");
    need(v.size(), points, "v");
    need(w.size(), points, "w");
    auto trim = std::make_shared<TrimLoops>();
    trim->loc = args.loc();
    size_t c = 0, k = 0, p = 0;
    for (int count : ncurves) {
        std::vector<TrimCurveDesc>& loop = trim->loops.emplace_back();
        for (int i = 0; i < count; ++i, ++c) {
            TrimCurveDesc t;
            t.order = order[c];
            t.knot.assign(knot.begin() + long(k), knot.begin() + long(k + size_t(n[c] + order[c])));
            t.tmin = tmin[c], t.tmax = tmax[c];
            t.u.assign(u.begin() + long(p), u.begin() + long(p + size_t(n[c])));
            t.v.assign(v.begin() + long(p), v.begin() + long(p + size_t(n[c])));
            t.w.assign(w.begin() + long(p), w.begin() + long(p + size_t(n[c])));
            checkKnots(args, *orderValue, "trim curve " + std::to_string(c), n[c], t.order, t.knot, t.tmin, t.tmax);
            for (double x : t.w)
                if (!(x > 0))
                    args.fail("trim curve " + std::to_string(c) + " has weight " + formatNumber(x) +
                              ": weights must be positive");
            k += t.knot.size(), p += t.u.size();
            loop.push_back(std::move(t));
        }
        if (loop.empty()) trim->loops.pop_back();
    }
    // An empty TrimCurve ([] for ncurves) turns trimming off.
    reader.state().mutableAttributes().trim = trim->loops.empty() ? nullptr : std::move(trim);
}

}  // namespace

void addNurbsRequests(RibRequestTable& table) {
    const RibPhase world = RibPhase::World;
    table.add("NuPatch", {oneKey<nuPatchKeys>,
                          "NuPatch nu uorder [uknot] umin umax nv vorder [vknot] vmin vmax \"P\"|\"Pw\" [...]", world,
                          nuPatchKeys});
    table.add("TrimCurve", {trimCurve, "TrimCurve [ncurves] [order] [knot] [min] [max] [n] [u] [v] [w]", world});
}

}  // namespace streyes
