// The Shading Language checker: the calls with rules of their own (texture, environment and shadow;
// the ray-traced functions; bake3d and texture3d; gather; spline; printf, format and concat; filterstep).
#include "shade/sl/checker_impl.h"
#include "shade/vm/ray_source.h"

namespace streyes::sl::detail {

SlType Checker::checkTexture(Expr& e, SlType want) {
    const auto& cands = findBuiltins(e.text);
    const Special kind = cands[0]->special;
    if (e.args.empty() || !e.args[0]->type.isString()) fail(e.loc, e.text + " needs a map name (a string) first");
    if (e.channel) expectType(*e.channel, BaseType::Float, "a channel");
    size_t i = 1;
    size_t coords = 0;
    while (i < e.args.size() && !e.args[i]->type.isString()) ++i, ++coords;
    if (kind == Special::Texture) {
        if (coords != 0 && coords != 2 && coords != 8)
            fail(e.loc, "texture takes (name), (name, s, t) or (name, s1, t1, ..., s4, t4), not " +
                            std::to_string(coords) + " coordinates");
        for (size_t k = 1; k <= coords; ++k) expectType(*e.args[k], BaseType::Float, "a texture coordinate");
    } else {
        if (coords != 1 && coords != 4)
            fail(e.loc, e.text + " takes (name, P) or (name, P1, P2, P3, P4), not " + std::to_string(coords) + " positions");
        for (size_t k = 1; k <= coords; ++k) {
            SlType t = e.args[k]->type;
            if (!t.isPointLike()) fail(e.args[k]->loc, e.text + " needs a point or vector, not a " + t.name());
        }
    }
    for (; i < e.args.size(); i += 2) {
        Expr& name = *e.args[i];
        if (name.kind != ExprKind::String) fail(name.loc, "a texture option's name must be a string literal");
        if (!kTextureOptions.count(name.text)) fail(name.loc, "unknown texture option \"" + name.text + "\"");
        if (i + 1 >= e.args.size()) fail(name.loc, "texture option \"" + name.text + "\" has no value");
        SlType vt = e.args[i + 1]->type;
        if (name.text == "filter" ? !vt.isString() : !vt.isFloat())
            fail(e.args[i + 1]->loc, "texture option \"" + name.text + "\" needs a " + (name.text == "filter" ? "string" : "float"));
    }
    e.builtin = (want.base == BaseType::Color || (want.isTriple() && kind != Special::Shadow)) ? cands[1] : cands[0];
    return e.builtin->ret;
}

// occlusion(P, N [, samples]), indirectdiffuse(P, N [, samples]), trace(P, R),
// transmission(Pfrom, Pto), each followed by (name, value) option pairs; occlusion may take a
// map name first (Aqsis's form).
SlType Checker::checkRay(Expr& e) {
    const Builtin* b = findBuiltins(e.text)[0];
    size_t i = 0;
    if (b->name == "occlusion" && !e.args.empty() && e.args[0]->type.isString()) i = 1;
    const size_t first = i;
    while (i < e.args.size() && !e.args[i]->type.isString()) ++i;
    const size_t given = i - first, listed = b->args.size();
    const size_t least = b->args.back().isFloat() ? listed - 1 : listed;  // the sample count may be left out
    if (given < least || given > listed) {
        std::string form;
        for (size_t k = 0; k < listed; ++k) form += (k ? ", " : "") + b->args[k].name();
        fail(e.loc, e.text + " takes (" + form + (least < listed ? " (optional)" : "") + ", options...), not " +
                        std::to_string(given) + " positional argument" + (given == 1 ? "" : "s"));
    }
    static const char* const what[] = {"its first argument", "its second argument", "the sample count"};
    for (size_t k = 0; k < given; ++k) {
        Expr& a = *e.args[first + k];
        const SlType t = b->args[k];
        if (a.kind == ExprKind::Tuple && flexibleTuple(a, t)) continue;
        if (t.isPointLike() ? !a.type.isPointLike() && !a.type.isFloat() : conversionCost(a.type, t) < 0)
            fail(a.loc, "cannot use a " + a.type.name() + " as " + e.text + "'s " + what[k] + " (" + t.name() + ")");
        if (a.type.isArray()) fail(a.loc, "cannot use an array as " + e.text + "'s " + what[k]);
    }
    for (; i < e.args.size(); i += 2) {
        Expr& name = *e.args[i];
        if (name.kind != ExprKind::String)
            fail(name.loc, e.text + ": an option's name must be a string literal (or too many positional arguments)");
        if (isRayOutputOption(b->name, name.text)) {  // written: a variable of the output's type
            if (i + 1 >= e.args.size()) fail(name.loc, e.text + " output \"" + name.text + "\" has no variable");
            Expr& v = *e.args[i + 1];
            const bool wantFloat = name.text == "occlusion";
            if (v.type.isArray() || (wantFloat ? !v.type.isFloat() : !v.type.isTriple()))
                fail(v.loc, e.text + " output \"" + name.text + "\" needs a " + (wantFloat ? "float" : "color") +
                                " variable, not a " + v.type.name());
            requireVariable(v, e.text + "'s \"" + name.text + "\"");
            continue;
        }
        const bool isFloat = kRayFloatOptions.count(name.text) > 0, isString = kRayStringOptions.count(name.text) > 0;
        if (!isFloat && !isString) fail(name.loc, "unknown " + e.text + " option \"" + name.text + "\"");
        if (i + 1 >= e.args.size()) fail(name.loc, e.text + " option \"" + name.text + "\" has no value");
        const SlType vt = e.args[i + 1]->type;
        if ((vt.isFloat() && !isFloat) || (vt.isString() && !isString) || (!vt.isFloat() && !vt.isString()))
            fail(e.args[i + 1]->loc, e.text + " option \"" + name.text + "\" needs a " + (isFloat ? "float" : "string") +
                                         ", not a " + vt.name());
    }
    e.builtin = b;
    return b->ret;
}

// bake3d(file, displaychannels, P, N, pairs...) and texture3d(file, P, N, pairs...): each pair a
// name (a string) and a float, triple or matrix (texture3d: a variable, written), or one of
// the options (bake3d's "interpolate", "radius", "radiusscale"; both's "coordsystem").
SlType Checker::checkPointCloud(Expr& e) {
    const Builtin* b = findBuiltins(e.text)[0];
    const bool bake = b->name == "bake3d";
    const size_t positional = bake ? 4 : 3;
    if (e.args.size() < positional || (e.args.size() - positional) % 2 != 0)
        fail(e.loc, bake ? "bake3d takes (string file, string displaychannels, point P, normal N, then \"name\", value pairs)"
                         : "texture3d takes (string file, point P, normal N, then \"name\", variable pairs)");
    for (size_t k = 0; k < positional - 2; ++k)
        if (!e.args[k]->type.isString())
            fail(e.args[k]->loc, e.text + "'s " + (k == 0 ? "first argument is a file name" : "second argument names the display channels") + " (a string)");
    for (size_t k = positional - 2; k < positional; ++k) {
        Expr& a = *e.args[k];
        if (a.kind == ExprKind::Tuple && flexibleTuple(a, BaseType::Point)) continue;
        if (a.type.isArray() || !(a.type.isPointLike() || a.type.isFloat()))
            fail(a.loc, "cannot use a " + a.type.name() + " as " + e.text + "'s " + (k == positional - 2 ? "position" : "normal"));
    }
    for (size_t i = positional; i < e.args.size(); i += 2) {
        Expr& name = *e.args[i];
        Expr& v = *e.args[i + 1];
        if (!name.type.isString()) fail(name.loc, e.text + ": a channel's name must be a string");
        const bool literal = name.kind == ExprKind::String;
        if (literal && name.text == "coordsystem") {
            if (!v.type.isString()) fail(v.loc, e.text + "'s \"coordsystem\" needs a string (a space name)");
            continue;
        }
        if (literal && (bake ? name.text == "interpolate" || name.text == "radius" || name.text == "radiusscale"
                             : name.text == "filterradius" || name.text == "filterscale" || name.text == "maxdepth")) {
            if (!v.type.isFloat()) fail(v.loc, e.text + "'s \"" + name.text + "\" needs a float");
            continue;
        }
        if (v.type.isArray() || !(v.type.isFloat() || v.type.isTriple() || v.type.isMatrix()))
            fail(v.loc, e.text + "'s channel \"" + (literal ? name.text : std::string("...")) +
                            "\" must be a float, color, point, vector, normal or matrix, not a " + v.type.name());
        if (!bake) requireVariable(v, "texture3d's channel \"" + (literal ? name.text : std::string("...")) + "\"");
    }
    e.builtin = b;
    return BaseType::Float;
}

// $gather(category, P, dir, angle, samples, sample, pairs...): the pairs are outputs
// ("surface:Ci", variable) or options ("maxdist", value).
SlType Checker::checkGather(Expr& e) {
    if (!e.args[0]->type.isString()) fail(e.args[0]->loc, "gather's first argument is a category (a string)");
    static const char* const what[] = {"position (point)", "direction (vector)", "cone angle (float)", "sample count (float)"};
    for (size_t k = 1; k <= 4; ++k) {
        Expr& a = *e.args[k];
        const bool ok = k <= 2 ? (a.type.isPointLike() || a.type.isFloat() || (a.kind == ExprKind::Tuple && flexibleTuple(a, BaseType::Point)))
                               : a.type.isFloat();
        if (!ok) fail(a.loc, "cannot use a " + a.type.name() + " as gather's " + what[k - 1]);
    }
    for (size_t i = 6; i < e.args.size(); i += 2) {
        Expr& name = *e.args[i];
        if (name.kind != ExprKind::String)
            fail(name.loc, "gather: an output's or option's name must be a string literal (\"surface:Ci\", \"maxdist\")");
        if (i + 1 >= e.args.size()) fail(name.loc, "gather's \"" + name.text + "\" has no value");
        Expr& v = *e.args[i + 1];
        if (name.text.find(':') != std::string::npos) {
            const SlType want = gatherOutputType(name.text);
            if (want.isVoid())
                fail(name.loc, "unknown gather output \"" + name.text +
                                   "\" (streyes gives surface:Ci, surface:Oi, surface:P, surface:N, ray:length, "
                                   "ray:direction, ray:origin)");
            requireVariable(v, "gather's \"" + name.text + "\" variable");
            if (!(v.type == want || (v.type.isPointLike() && want.isPointLike())))
                fail(v.loc, "gather's \"" + name.text + "\" is a " + want.name() + ", not a " + v.type.name());
            continue;
        }
        const bool isFloat = name.text == "maxdist" || name.text == "bias" || name.text == "samplebase";
        const bool isString = name.text == "distribution" || name.text == "label" || name.text == "subset" ||
                              name.text == "hitmode";
        if (!isFloat && !isString) fail(name.loc, "unknown gather option \"" + name.text + "\"");
        if (isFloat ? !v.type.isFloat() : !v.type.isString())
            fail(v.loc, "gather option \"" + name.text + "\" needs a " + (isFloat ? "float" : "string") + ", not a " + v.type.name());
        if (name.text == "distribution" && v.kind == ExprKind::String && v.text != "uniform" && v.text != "cosine")
            fail(v.loc, "gather's distribution is \"uniform\" or \"cosine\", not \"" + v.text + "\"");
    }
    e.builtin = findBuiltins(e.text)[0];
    return BaseType::Float;
}

SlType Checker::checkSpline(Expr& e) {
    size_t i = 0;
    if (!e.args.empty() && e.args[0]->type.isString()) {
        if (e.args[0]->kind == ExprKind::String) {
            static const std::set<std::string> bases = {"catmull-rom", "bezier", "bspline", "hermite", "linear"};
            if (!bases.count(e.args[0]->text)) fail(e.args[0]->loc, "unknown spline basis \"" + e.args[0]->text + "\"");
        }
        i = 1;
    }
    if (e.args.size() < i + 2) fail(e.loc, "spline takes ([basis,] value, knots...)");
    expectType(*e.args[i], BaseType::Float, "the spline's parameter");
    const SlType k0 = e.args[i + 1]->type;
    SlType knot = k0.isArray() ? k0.element() : k0;
    if (!(knot.isFloat() || knot.isTriple())) fail(e.loc, "spline knots must be floats, colors or points");
    if (knot.isPointLike()) knot = BaseType::Point;
    if (k0.isArray()) {
        if (e.args.size() != i + 2) fail(e.loc, "spline with an array of knots takes ([basis,] value, array)");
        if (!k0.isResizable() && k0.arrayLen < 4) fail(e.loc, "a spline needs at least 4 knots");
    } else {
        if (e.args.size() - i - 1 < 4) fail(e.loc, "a spline needs at least 4 knots");
        for (size_t k = i + 1; k < e.args.size(); ++k) expectType(*e.args[k], knot, "a spline knot");
    }
    for (const Builtin* b : findBuiltins("spline"))
        if (b->ret == knot) e.builtin = b;
    return knot;
}

SlType Checker::checkFormat(Expr& e) {
    const Builtin* b = findBuiltins(e.text)[0];
    if (e.args.empty() || !e.args[0]->type.isString()) fail(e.loc, e.text + " needs a string first");
    for (size_t i = 1; i < e.args.size(); ++i) {
        SlType t = e.args[i]->type;
        if (t.isVoid()) fail(e.args[i]->loc, "a void value cannot be printed");
        if (b->special == Special::Concat && !t.isString()) fail(e.args[i]->loc, "concat joins strings, not a " + t.name());
    }
    e.builtin = b;
    return b->ret;
}

SlType Checker::checkFilterstep(Expr& e) {
    size_t i = 0;
    while (i < e.args.size() && !e.args[i]->type.isString()) ++i;
    if (i != 2 && i != 3) fail(e.loc, "filterstep takes (edge, s1 [, s2] [, \"width\", w])");
    for (size_t k = 0; k < i; ++k) expectType(*e.args[k], BaseType::Float, "a filterstep argument");
    for (; i < e.args.size(); i += 2) {
        Expr& name = *e.args[i];
        if (name.kind != ExprKind::String || name.text != "width")
            fail(name.loc, "filterstep's only option is \"width\"");
        if (i + 1 >= e.args.size()) fail(name.loc, "\"width\" has no value");
        expectType(*e.args[i + 1], BaseType::Float, "the width");
    }
    e.builtin = findBuiltins("filterstep")[0];
    return BaseType::Float;
}

}  // namespace streyes::sl::detail
