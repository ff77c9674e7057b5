// Attributes: Color, Opacity, ShadingRate, Attribute and Basis change the current attributes,
// which primitives share (copy-on-write).
#include <algorithm>
#include <cmath>
#include <set>

#include "scene/bound_spaces.h"
#include "scene/rib_categories.h"
#include "scene/rib_requests.h"

namespace streyes {

// Primitives share the Attributes they were created with. Before changing the current attributes
// we copy them if anything else (a primitive, a saved block) still holds them.
Attributes& RibState::mutableAttributes() {
    if (attributes.use_count() > 1) attributes = std::make_shared<Attributes>(*attributes);
    return *attributes;
}

namespace {

void color(RibParser& reader, RibArgs& args) {
    std::vector<double> c = args.numbers(3, "r g b");
    args.expectEnd();
    reader.state().mutableAttributes().color = Color(float(c[0]), float(c[1]), float(c[2]));
}

void opacity(RibParser& reader, RibArgs& args) {
    std::vector<double> o = args.numbers(3, "r g b");
    args.expectEnd();
    for (double& v : o)
        if (!(v >= 0 && v <= 1)) {
            reader.log().warnOnce("opacity-range", args.loc(),
                                  "Opacity takes r g b in [0, 1] (1: opaque, 0: clear): " + formatNumber(v) + " clamped");
            v = v < 0 ? 0 : 1;
        }
    reader.state().mutableAttributes().opacity = Color(float(o[0]), float(o[1]), float(o[2]));
}

// Matte onoff: 1 makes the geometry a holdout (it hides what is behind it and leaves colour 0,
// alpha 0); 0, the default, as exporters write it on every object, an ordinary surface. Kept as
// the attribute "streyes:matte" (Attribute "streyes" "int matte" [1] says the same), which
// makeMaterial reads.
void matte(RibParser& reader, RibArgs& args) {
    const double on = args.number("onoff");
    args.expectEnd();
    if (!(on == 0 || on == 1)) args.fail("Matte takes 0 (off) or 1 (on), got " + formatNumber(on));
    Param p;
    p.name = "matte", p.type = ParamType::Integer, p.nums = {on}, p.loc = args.loc();
    ParamList given;
    given.params.push_back(std::move(p));
    keepCategoryValues("streyes", given, reader.state().mutableAttributes().user);
}

void shadingRate(RibParser& reader, RibArgs& args) {
    double rate = args.number("area");
    args.expectEnd();
    if (!(rate > 0)) args.fail("the shading rate must be positive, got " + formatNumber(rate));
    reader.state().mutableAttributes().shadingRate = rate;
}

// GeometricApproximation "motionfactor" value: fast movers are diced and shaded coarser
// (RenderMan's rule, docs/SCENE-FORMAT.md). The other approximations are not modelled: warned once.
void geometricApproximation(RibParser& reader, RibArgs& args) {
    const std::string type = args.string("type");
    const double value = args.number("value");
    args.expectEnd();
    if (type != "motionfactor") {
        reader.log().warnOnce("geometric-approximation-" + type, args.loc(),
                              "GeometricApproximation \"" + type + "\" is not modelled (only \"motionfactor\"): ignored");
        return;
    }
    if (!(value >= 0 && std::isfinite(value)))
        args.fail("GeometricApproximation \"motionfactor\" takes a finite value of at least 0 (0: off), got " +
                  formatNumber(value));
    reader.state().mutableAttributes().motionFactor = value;
}

// Attribute "displacementbound" "sphere" r "coordinatesystem" "space".
void displacementBound(RibParser& reader, const ParamList& params) {
    Attributes& a = reader.state().mutableAttributes();
    const double r = params.getFloat("sphere", a.displacementBound);
    if (!(r >= 0) || !std::isfinite(r))
        throw InputError(params.find("sphere")->loc,
                         "Attribute \"displacementbound\": sphere must be a radius >= 0, not " + formatNumber(r));
    std::string space = params.getString("coordinatesystem", a.displacementBoundSpace);
    const bool given = params.find("coordinatesystem") != nullptr;
    const RibState& s = reader.state();
    // The standard spaces ("current" is camera space, as in PRMan; "surface" the surface
    // shader's, as "shader" is the displacement's; the image's under an orthographic projection)
    // are placed when the render binds the displacement; a name CoordinateSystem gave, and
    // PRMan's "null" (the CTM at this request), are placed now.
    static const std::set<std::string> bound = {"object", "shader", "surface", "world", "camera", "current"};
    if (given && !bound.count(space)) {
        auto named = s.coordinateSystems.find(space);
        const SourceLoc& loc = params.find("coordinatesystem")->loc;
        if (space == "null") {
            a.displacementBoundToWorld = s.ctm;
        } else if (named != s.coordinateSystems.end() && !s.cameraSpaces.count(space)) {
            a.displacementBoundToWorld = named->second;
        } else if (isImageBoundSpace(space)) {
            if (reader.camera().projection != ProjectionKind::Orthographic) {
                reader.log().lenient("displacementbound:perspective-" + space, loc, perspectiveImageBoundMessage(space));
                space = "object";
            }
        } else {
            // Another renderer's name ("eye"), or a name not given to CoordinateSystem (in the
            // world): the bound is taken in object space.
            reader.log().lenient("displacementbound:" + space, loc,
                                 "Attribute \"displacementbound\": coordinatesystem \"" + space +
                                     "\" is none of object, shader, surface, world, camera, current, screen, NDC, "
                                     "raster, null or a name CoordinateSystem gave: the bound is taken in object space");
            space = "object";
        }
    }
    a.displacementBound = r;
    a.displacementBoundSpace = space;
    reader.warnUnusedParams(params, {"sphere", "coordinatesystem"}, "Attribute \"displacementbound\"");
}

// Every Attribute value is kept as "category:name" (Attributes::user) for the features and
// shaders that read them; those of categories streyes does not read are reviewed (silent when they
// only tune another renderer, else warned: rib_categories.h). A name nobody declared takes the
// type of its value.
void attribute(RibParser& reader, RibArgs& args) {
    static const std::set<std::string> read = {"identifier", "light",           "user",
                                               "streyes",    "displacementbound", "autoshadows"};
    const std::string category = args.string("category");
    ParamList params = reader.readParams(args, true);
    for (const Param& p : params.params) {
        if ((p.nums.size() + p.strings.size()) % size_t(p.componentsPerItem()) != 0)
            throw InputError(p.loc, "Attribute \"" + category + "\": parameter '" + p.name + "' has " +
                                        plural(p.nums.size() + p.strings.size(), "value") +
                                        ", not a whole number of " + paramTypeName(p.type) + "s");
        if (category == "light" && p.name == "shadows" && p.type == ParamType::String) {
            const std::string v = p.strings.empty() ? "" : p.strings.front();
            if (v != "on" && v != "off")
                throw InputError(p.loc, "Attribute \"light\" \"shadows\": expected \"on\" or \"off\", not \"" + v + "\"");
        }
    }
    if (category == "displacementbound") displacementBound(reader, params);
    else if (!read.count(category)) reviewAttribute(reader, category, params, args.loc());
    keepCategoryValues(category, params, reader.state().mutableAttributes().user);
}

void basis(RibParser& reader, RibArgs& args) {
    BasisDesc b[2];
    for (int i = 0; i < 2; ++i) {
        const char* which = i == 0 ? "ubasis" : "vbasis";
        if (args.done()) args.fail(std::string("missing ") + which);
        const RibValue& v = *args.peek();
        if (v.kind == RibValue::Kind::Array && v.isNumericArray() && v.nums.size() == 16) {
            std::copy(v.nums.begin(), v.nums.end(), b[i].m.begin());
            args.take();
        } else {
            std::string name = args.string(which);
            if (!basisFromName(name, &b[i]))
                args.fail(v, "unknown basis \"" + name +
                                 "\": use bezier, b-spline, catmull-rom, hermite, power or 16 numbers");
        }
        const RibValue* stepValue = args.peek();
        const int step = args.integer(i == 0 ? "ustep" : "vstep");
        if (step < 1) args.fail(*stepValue, "the step must be at least 1, got " + std::to_string(step));
        b[i].step = step;
    }
    args.expectEnd();
    Attributes& a = reader.state().mutableAttributes();
    a.uBasis = b[0];
    a.vBasis = b[1];
}

void sides(RibParser& reader, RibArgs& args) {
    const RibValue* v = args.peek();
    const int n = args.integer("sides");
    args.expectEnd();
    if (n != 1 && n != 2) args.fail(*v, "must be 1 or 2, got " + std::to_string(n));
    reader.state().mutableAttributes().twoSided = n == 2;
}

void orientation(RibParser& reader, RibArgs& args) {
    const RibValue* v = args.peek();
    const std::string name = args.string("orientation");
    args.expectEnd();
    using O = Attributes::Orientation;
    O o;
    if (name == "outside") o = O::Outside;
    else if (name == "inside") o = O::Inside;
    else if (name == "lh") o = O::LeftHanded;
    else if (name == "rh") o = O::RightHanded;
    else args.fail(*v, "unknown orientation \"" + name + "\": use \"outside\", \"inside\", \"lh\" or \"rh\"");
    reader.state().mutableAttributes().orientation = o;
}

void reverseOrientation(RibParser& reader, RibArgs& args) {
    args.expectEnd();
    using O = Attributes::Orientation;
    Attributes& a = reader.state().mutableAttributes();
    switch (a.orientation) {
        case O::Outside: a.orientation = O::Inside; break;
        case O::Inside: a.orientation = O::Outside; break;
        case O::LeftHanded: a.orientation = O::RightHanded; break;
        case O::RightHanded: a.orientation = O::LeftHanded; break;
    }
}

void shadingInterpolation(RibParser& reader, RibArgs& args) {
    const RibValue* v = args.peek();
    const std::string name = args.string("interpolation");
    args.expectEnd();
    if (name != "constant" && name != "smooth")
        args.fail(*v, "unknown shading interpolation \"" + name + "\": use \"constant\" or \"smooth\"");
    reader.state().mutableAttributes().smoothShading = name == "smooth";
}

}  // namespace

void addAttributeRequests(RibRequestTable& table) {
    table.add("Sides", {sides, "Sides 1 | 2"});
    table.add("Orientation", {orientation, "Orientation \"outside\" | \"inside\" | \"lh\" | \"rh\""});
    table.add("ReverseOrientation", {reverseOrientation, "ReverseOrientation"});
    table.add("ShadingInterpolation", {shadingInterpolation, "ShadingInterpolation \"constant\" | \"smooth\""});
    table.add("Color", {color, "Color r g b"});
    table.add("Opacity", {opacity, "Opacity r g b"});
    table.add("Matte", {matte, "Matte onoff"});
    table.add("ShadingRate", {shadingRate, "ShadingRate area"});
    table.add("GeometricApproximation", {geometricApproximation, "GeometricApproximation \"motionfactor\" value"});
    table.add("Attribute", {attribute, "Attribute \"category\" parameters..."});
    table.add("Basis", {basis, "Basis ubasis ustep vbasis vstep"});
}

}  // namespace streyes
