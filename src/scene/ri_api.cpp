// The RI C API's calls (include/ri.h), each written as the RIB request it stands for to the
// current stream (ri_stream.h). RiBegin and RiEnd, which decide where a session's stream goes and
// render it, are the I/O stage's (src/io/ri_session.cpp).
#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <mutex>
#include <set>
#include <vector>

#include "scene/ri_stream.h"

using streyes::RiClassSizes;
using streyes::RiStream;

namespace {

// A call with no stream to go to is reported once per call name: it is a program's mistake.
RiStream* streamFor(const char* call) {
    RiStream* s = streyes::currentRiStream();
    if (!s) {
        static std::mutex mutex;
        static std::set<std::string> said;
        std::lock_guard<std::mutex> lock(mutex);
        if (said.insert(call).second)
            std::fprintf(stderr,
                         "streyes: %s called outside RiBegin/RiEnd and outside a procedural's Subdivide: ignored\n",
                         call);
    }
    return s;
}

// A varargs parameter list (token, value pairs ending with RI_NULL).
struct ParamArgs {
    std::vector<RtToken> tokens;
    std::vector<RtPointer> values;
    RtInt n() const { return RtInt(tokens.size()); }
    RtToken* t() { return tokens.data(); }
    RtPointer* v() { return values.data(); }
};

ParamArgs collect(va_list ap) {
    ParamArgs p;
    for (RtToken t = va_arg(ap, RtToken); t; t = va_arg(ap, RtToken)) {
        p.tokens.push_back(t);
        p.values.push_back(va_arg(ap, RtPointer));
    }
    return p;
}

#define COLLECT_PARAMS(last) \
    va_list ap;              \
    va_start(ap, last);      \
    ParamArgs p = collect(ap); \
    va_end(ap)

// A request with only numbers.
void numbers(const char* call, const char* request, std::initializer_list<double> values) {
    if (RiStream* s = streamFor(call)) {
        s->request(call, request);
        for (double v : values) s->number(v);
    }
}

void bare(const char* call, const char* request) {
    if (RiStream* s = streamFor(call)) s->request(call, request);
}

// A request "Name" "string" params... (Surface, Attribute, Option, Projection).
void named(const char* call, const char* request, RtToken name, RtInt n, RtToken tokens[], RtPointer values[]) {
    if (RiStream* s = streamFor(call)) {
        s->request(call, request);
        s->string(name);
        s->params(n, tokens, values, RiClassSizes{});
    }
}

void matrix(const char* call, const char* request, RtMatrix m) {
    if (RiStream* s = streamFor(call)) {
        s->request(call, request);
        s->floats(m ? &m[0][0] : nullptr, 16);
    }
}

// Varying and uniform counts of a patch mesh along one direction.
void patchCounts(bool bicubic, int n, bool periodic, int step, int* patches, int* varying) {
    if (!bicubic) *patches = periodic ? n : n - 1;
    else *patches = periodic ? n / std::max(step, 1) : (n - 4) / std::max(step, 1) + 1;
    *patches = std::max(*patches, 0);
    *varying = periodic ? *patches : *patches + 1;
}

int largestIndexPlusOne(const RtInt* v, size_t n) {
    int m = 0;
    for (size_t i = 0; v && i < n; ++i) m = std::max(m, v[i] + 1);
    return m;
}

size_t sum(const RtInt* v, RtInt n) {
    size_t s = 0;
    for (RtInt i = 0; v && i < n; ++i) s += size_t(std::max(v[i], 0));
    return s;
}

const char* basisName(RtBasis b);

}  // namespace

extern "C" {

// clang-format off
RtBasis RiBezierBasis = {{-1, 3, -3, 1}, {3, -6, 3, 0}, {-3, 3, 0, 0}, {1, 0, 0, 0}};
RtBasis RiBSplineBasis = {{-1.0f / 6, 3.0f / 6, -3.0f / 6, 1.0f / 6}, {3.0f / 6, -6.0f / 6, 3.0f / 6, 0},
                          {-3.0f / 6, 0, 3.0f / 6, 0}, {1.0f / 6, 4.0f / 6, 1.0f / 6, 0}};
RtBasis RiCatmullRomBasis = {{-0.5f, 1.5f, -1.5f, 0.5f}, {1, -2.5f, 2, -0.5f}, {-0.5f, 0, 0.5f, 0}, {0, 1, 0, 0}};
RtBasis RiHermiteBasis = {{2, 1, -2, 1}, {-3, -2, 3, -1}, {0, 1, 0, 0}, {1, 0, 0, 0}};
RtBasis RiPowerBasis = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 1}};
// clang-format on

RtFloat RiBoxFilter(RtFloat, RtFloat, RtFloat, RtFloat) { return 1; }
RtFloat RiGaussianFilter(RtFloat x, RtFloat y, RtFloat xwidth, RtFloat ywidth) {
    x *= 2 / xwidth;
    y *= 2 / ywidth;
    return std::exp(-2 * (x * x + y * y));
}
RtFloat RiTriangleFilter(RtFloat x, RtFloat y, RtFloat xwidth, RtFloat ywidth) {
    return std::max(0.0f, 1 - std::fabs(x) / (xwidth / 2)) * std::max(0.0f, 1 - std::fabs(y) / (ywidth / 2));
}
RtFloat RiCatmullRomFilter(RtFloat x, RtFloat y, RtFloat, RtFloat) {
    auto f = [](float t) {
        t = std::fabs(t);
        if (t < 1) return 1.5f * t * t * t - 2.5f * t * t + 1;
        if (t < 2) return -0.5f * t * t * t + 2.5f * t * t - 4 * t + 2;
        return 0.0f;
    };
    return f(x) * f(y);
}
RtFloat RiSincFilter(RtFloat x, RtFloat y, RtFloat, RtFloat) {
    auto f = [](float t) { return t == 0 ? 1.0f : std::sin(float(M_PI) * t) / (float(M_PI) * t); };
    return f(x) * f(y);
}

// ---- Blocks
RtVoid RiFrameBegin(RtInt number) { numbers("RiFrameBegin", "FrameBegin", {double(number)}); }
RtVoid RiFrameEnd(void) { bare("RiFrameEnd", "FrameEnd"); }
RtVoid RiWorldBegin(void) { bare("RiWorldBegin", "WorldBegin"); }
RtVoid RiWorldEnd(void) { bare("RiWorldEnd", "WorldEnd"); }
RtVoid RiAttributeBegin(void) {
    if (RiStream* s = streamFor("RiAttributeBegin")) {
        s->request("RiAttributeBegin", "AttributeBegin");
        s->savedSteps.push_back({s->uStep, s->vStep});
    }
}
RtVoid RiAttributeEnd(void) {
    if (RiStream* s = streamFor("RiAttributeEnd")) {
        s->request("RiAttributeEnd", "AttributeEnd");
        if (!s->savedSteps.empty()) {
            s->uStep = s->savedSteps.back().first;
            s->vStep = s->savedSteps.back().second;
            s->savedSteps.pop_back();
        }
    }
}
RtVoid RiTransformBegin(void) { bare("RiTransformBegin", "TransformBegin"); }
RtVoid RiTransformEnd(void) { bare("RiTransformEnd", "TransformEnd"); }
RtVoid RiMotionBeginV(RtInt n, RtFloat times[]) {
    if (RiStream* s = streamFor("RiMotionBegin")) {
        s->request("RiMotionBegin", "MotionBegin");
        s->floats(times, size_t(std::max(n, 0)));
    }
}
RtVoid RiMotionBegin(RtInt n, ...) {
    std::vector<RtFloat> times;
    va_list ap;
    va_start(ap, n);
    for (RtInt i = 0; i < n; ++i) times.push_back(RtFloat(va_arg(ap, double)));
    va_end(ap);
    RiMotionBeginV(n, times.data());
}
RtVoid RiMotionEnd(void) { bare("RiMotionEnd", "MotionEnd"); }
RtVoid RiArchiveRecord(RtToken, const char*, ...) {}

// ---- Options
RtVoid RiFormat(RtInt xres, RtInt yres, RtFloat pixelaspect) {
    if (RiStream* s = streamFor("RiFormat")) {
        s->request("RiFormat", "Format");
        s->integer(xres);
        s->integer(yres);
        s->number(pixelaspect);
    }
}
RtVoid RiFrameAspectRatio(RtFloat ratio) { numbers("RiFrameAspectRatio", "FrameAspectRatio", {ratio}); }
RtVoid RiScreenWindow(RtFloat left, RtFloat right, RtFloat bottom, RtFloat top) {
    numbers("RiScreenWindow", "ScreenWindow", {left, right, bottom, top});
}
RtVoid RiClipping(RtFloat hither, RtFloat yon) { numbers("RiClipping", "Clipping", {hither, yon}); }
RtVoid RiDepthOfField(RtFloat fstop, RtFloat focallength, RtFloat focaldistance) {
    numbers("RiDepthOfField", "DepthOfField", {fstop, focallength, focaldistance});
}
RtVoid RiShutter(RtFloat open, RtFloat close) { numbers("RiShutter", "Shutter", {open, close}); }
RtVoid RiPixelSamples(RtFloat xsamples, RtFloat ysamples) {
    numbers("RiPixelSamples", "PixelSamples", {xsamples, ysamples});
}
RtVoid RiPixelFilter(RtFilterFunc filter, RtFloat xwidth, RtFloat ywidth) {
    RiStream* s = streamFor("RiPixelFilter");
    if (!s) return;
    s->request("RiPixelFilter", "PixelFilter");
    const char* name = filter == RiBoxFilter           ? "box"
                       : filter == RiGaussianFilter    ? "gaussian"
                       : filter == RiTriangleFilter    ? "triangle"
                       : filter == RiCatmullRomFilter  ? "catmull-rom"
                       : filter == RiSincFilter        ? "sinc"
                                                       : nullptr;
    if (!name) {
        s->fail("only the standard filters (RiBoxFilter, RiGaussianFilter, RiTriangleFilter, RiCatmullRomFilter, "
                "RiSincFilter) can be given");
        name = "gaussian";
    }
    s->string(name);
    s->number(xwidth);
    s->number(ywidth);
}
RtVoid RiProjectionV(RtToken name, RtInt n, RtToken tokens[], RtPointer values[]) {
    named("RiProjection", "Projection", name, n, tokens, values);
}
RtVoid RiProjection(RtToken name, ...) {
    COLLECT_PARAMS(name);
    RiProjectionV(name, p.n(), p.t(), p.v());
}
RtVoid RiDisplayV(RtToken name, RtToken type, RtToken mode, RtInt n, RtToken tokens[], RtPointer values[]) {
    if (RiStream* s = streamFor("RiDisplay")) {
        s->request("RiDisplay", "Display");
        s->string(name);
        s->string(type);
        s->string(mode);
        s->params(n, tokens, values, RiClassSizes{});
    }
}
RtVoid RiDisplay(RtToken name, RtToken type, RtToken mode, ...) {
    COLLECT_PARAMS(mode);
    RiDisplayV(name, type, mode, p.n(), p.t(), p.v());
}
RtVoid RiOptionV(RtToken name, RtInt n, RtToken tokens[], RtPointer values[]) {
    // Option "rib" says how RiEnd writes the file, before RiBegin (as PRMan has it) or inside: it
    // is not part of the scene.
    if (name && std::string(name) == "rib") {
        RiStream* s = streyes::currentRiStream();
        streyes::RibEncoding& encoding = s ? s->encoding : streyes::pendingRibEncoding();
        for (RtInt i = 0; i < n; ++i) {
            const RtString* v = values ? static_cast<const RtString*>(values[i]) : nullptr;
            const std::string what =
                streyes::setRibOutputOption(encoding, tokens && tokens[i] ? tokens[i] : "", v ? v[0] : nullptr);
            if (!what.empty()) std::fprintf(stderr, "streyes: RiOption: %s\n", what.c_str());
        }
        return;
    }
    RiStream* s = streamFor("RiOption");
    if (!s) return;
    s->request("RiOption", "Option");
    s->string(name);
    // The search paths are strings whatever their names (RenderMan declares them so).
    if (name && std::string(name) == "searchpath") {
        for (RtInt i = 0; i < n; ++i) {
            s->string(tokens ? tokens[i] : nullptr);
            s->strings(values ? static_cast<const RtString*>(values[i]) : nullptr, 1);
        }
        return;
    }
    s->params(n, tokens, values, RiClassSizes{});
}
RtVoid RiExposure(RtFloat gain, RtFloat gamma) { numbers("RiExposure", "Exposure", {gain, gamma}); }
RtVoid RiHiderV(RtToken type, RtInt n, RtToken tokens[], RtPointer values[]) {
    named("RiHider", "Hider", type, n, tokens, values);
}
RtVoid RiHider(RtToken type, ...) {
    COLLECT_PARAMS(type);
    RiHiderV(type, p.n(), p.t(), p.v());
}
RtVoid RiOption(RtToken name, ...) {
    COLLECT_PARAMS(name);
    RiOptionV(name, p.n(), p.t(), p.v());
}
RtToken RiDeclare(const char* name, const char* declaration) {
    RiStream* s = streamFor("RiDeclare");
    if (!s) return name;
    s->request("RiDeclare", "Declare");
    s->string(name);
    s->string(declaration);
    if (!name || !declaration) return name;
    streyes::RibParamDecl decl;
    std::string unused;
    const std::string error = streyes::parseRibDeclaration(declaration, false, &decl, &unused);
    if (!error.empty()) s->fail("bad declaration \"" + std::string(declaration) + "\": " + error);
    else s->declarations()[name] = decl;
    return name;
}

// ---- Transforms
RtVoid RiIdentity(void) { bare("RiIdentity", "Identity"); }
RtVoid RiTransform(RtMatrix transform) { matrix("RiTransform", "Transform", transform); }
RtVoid RiConcatTransform(RtMatrix transform) { matrix("RiConcatTransform", "ConcatTransform", transform); }
RtVoid RiTranslate(RtFloat dx, RtFloat dy, RtFloat dz) { numbers("RiTranslate", "Translate", {dx, dy, dz}); }
RtVoid RiRotate(RtFloat angle, RtFloat dx, RtFloat dy, RtFloat dz) {
    numbers("RiRotate", "Rotate", {angle, dx, dy, dz});
}
RtVoid RiScale(RtFloat sx, RtFloat sy, RtFloat sz) { numbers("RiScale", "Scale", {sx, sy, sz}); }

// ---- Attributes and shading
RtVoid RiColor(RtColor color) {
    if (RiStream* s = streamFor("RiColor")) {
        s->request("RiColor", "Color");
        s->floats(color, 3);
    }
}
RtVoid RiOpacity(RtColor color) {
    if (RiStream* s = streamFor("RiOpacity")) {
        s->request("RiOpacity", "Opacity");
        s->floats(color, 3);
    }
}
RtVoid RiShadingRate(RtFloat size) { numbers("RiShadingRate", "ShadingRate", {size}); }
RtVoid RiGeometricApproximation(RtToken type, RtFloat value) {
    if (RiStream* s = streamFor("RiGeometricApproximation")) {
        s->request("RiGeometricApproximation", "GeometricApproximation");
        s->string(type);
        s->floats(&value, 1);
    }
}
RtVoid RiBasis(RtBasis ubasis, RtInt ustep, RtBasis vbasis, RtInt vstep) {
    RiStream* s = streamFor("RiBasis");
    if (!s) return;
    s->request("RiBasis", "Basis");
    for (int i = 0; i < 2; ++i) {
        RtBasis& b = *(i == 0 ? reinterpret_cast<RtBasis*>(ubasis) : reinterpret_cast<RtBasis*>(vbasis));
        if (const char* name = basisName(b)) s->string(name);
        else s->floats(&b[0][0], 16);
        s->integer(i == 0 ? ustep : vstep);
    }
    s->uStep = ustep;
    s->vStep = vstep;
}
RtVoid RiSides(RtInt sides) {
    if (RiStream* s = streamFor("RiSides")) {
        s->request("RiSides", "Sides");
        s->integer(sides);
    }
}
RtVoid RiOrientation(RtToken orientation) { named("RiOrientation", "Orientation", orientation, 0, nullptr, nullptr); }
RtVoid RiReverseOrientation(void) { bare("RiReverseOrientation", "ReverseOrientation"); }
RtVoid RiShadingInterpolation(RtToken type) {
    named("RiShadingInterpolation", "ShadingInterpolation", type, 0, nullptr, nullptr);
}
RtVoid RiAttributeV(RtToken name, RtInt n, RtToken tokens[], RtPointer values[]) {
    named("RiAttribute", "Attribute", name, n, tokens, values);
}
RtVoid RiAttribute(RtToken name, ...) {
    COLLECT_PARAMS(name);
    RiAttributeV(name, p.n(), p.t(), p.v());
}
RtVoid RiSurfaceV(RtToken name, RtInt n, RtToken tokens[], RtPointer values[]) {
    named("RiSurface", "Surface", name, n, tokens, values);
}
RtVoid RiSurface(RtToken name, ...) {
    COLLECT_PARAMS(name);
    RiSurfaceV(name, p.n(), p.t(), p.v());
}
RtLightHandle RiLightSourceV(RtToken name, RtInt n, RtToken tokens[], RtPointer values[]) {
    RiStream* s = streamFor("RiLightSource");
    if (!s) return nullptr;
    const int handle = s->nextLight++;
    s->request("RiLightSource", "LightSource");
    s->string(name);
    s->integer(handle);
    s->params(n, tokens, values, RiClassSizes{});
    return reinterpret_cast<RtLightHandle>(static_cast<intptr_t>(handle));
}
RtLightHandle RiLightSource(RtToken name, ...) {
    COLLECT_PARAMS(name);
    return RiLightSourceV(name, p.n(), p.t(), p.v());
}
RtVoid RiIlluminate(RtLightHandle light, RtBoolean onoff) {
    if (RiStream* s = streamFor("RiIlluminate")) {
        s->request("RiIlluminate", "Illuminate");
        s->integer(long(reinterpret_cast<intptr_t>(light)));
        s->integer(onoff ? 1 : 0);
    }
}

// ---- Geometry
RtVoid RiSphereV(RtFloat radius, RtFloat zmin, RtFloat zmax, RtFloat thetamax, RtInt n, RtToken tokens[],
                 RtPointer values[]) {
    if (RiStream* s = streamFor("RiSphere")) {
        s->request("RiSphere", "Sphere");
        for (double v : {radius, zmin, zmax, thetamax}) s->number(v);
        s->params(n, tokens, values, RiClassSizes{1, 4, 4, 4});
    }
}
// RISpec fixes this signature: the last named parameter is a float, which va_start formally may
// not name (it is promoted); every ABI streyes builds for handles it, and clang's warning is off.
#ifdef __clang__
#pragma clang diagnostic push
#pragma clang diagnostic ignored "-Wvarargs"
#endif
RtVoid RiSphere(RtFloat radius, RtFloat zmin, RtFloat zmax, RtFloat thetamax, ...) {
    COLLECT_PARAMS(thetamax);
    RiSphereV(radius, zmin, zmax, thetamax, p.n(), p.t(), p.v());
}
#ifdef __clang__
#pragma clang diagnostic pop
#endif
RtVoid RiPolygonV(RtInt nvertices, RtInt n, RtToken tokens[], RtPointer values[]) {
    if (RiStream* s = streamFor("RiPolygon")) {
        s->request("RiPolygon", "Polygon");
        s->params(n, tokens, values, RiClassSizes{1, nvertices, nvertices, nvertices});
    }
}
RtVoid RiPolygon(RtInt nvertices, ...) {
    COLLECT_PARAMS(nvertices);
    RiPolygonV(nvertices, p.n(), p.t(), p.v());
}
RtVoid RiPointsPolygonsV(RtInt npolys, RtInt nvertices[], RtInt vertices[], RtInt n, RtToken tokens[],
                         RtPointer values[]) {
    RiStream* s = streamFor("RiPointsPolygons");
    if (!s) return;
    s->request("RiPointsPolygons", "PointsPolygons");
    const size_t corners = sum(nvertices, npolys);
    s->integers(nvertices, size_t(std::max(npolys, 0)));
    s->integers(vertices, corners);
    const int points = largestIndexPlusOne(vertices, corners);
    s->params(n, tokens, values, RiClassSizes{npolys, points, points, int(corners)});
}
RtVoid RiPointsPolygons(RtInt npolys, RtInt nvertices[], RtInt vertices[], ...) {
    COLLECT_PARAMS(vertices);
    RiPointsPolygonsV(npolys, nvertices, vertices, p.n(), p.t(), p.v());
}
RtVoid RiPatchV(RtToken type, RtInt n, RtToken tokens[], RtPointer values[]) {
    if (RiStream* s = streamFor("RiPatch")) {
        s->request("RiPatch", "Patch");
        s->string(type);
        const bool bicubic = type && std::string(type) == "bicubic";
        s->params(n, tokens, values, RiClassSizes{1, 4, bicubic ? 16 : 4, 4});
    }
}
RtVoid RiPatch(RtToken type, ...) {
    COLLECT_PARAMS(type);
    RiPatchV(type, p.n(), p.t(), p.v());
}
RtVoid RiPatchMeshV(RtToken type, RtInt nu, RtToken uwrap, RtInt nv, RtToken vwrap, RtInt n, RtToken tokens[],
                    RtPointer values[]) {
    RiStream* s = streamFor("RiPatchMesh");
    if (!s) return;
    s->request("RiPatchMesh", "PatchMesh");
    s->string(type);
    s->integer(nu);
    s->string(uwrap);
    s->integer(nv);
    s->string(vwrap);
    const bool bicubic = type && std::string(type) == "bicubic";
    int up, uv, vp, vv;
    patchCounts(bicubic, nu, uwrap && std::string(uwrap) == "periodic", s->uStep, &up, &uv);
    patchCounts(bicubic, nv, vwrap && std::string(vwrap) == "periodic", s->vStep, &vp, &vv);
    s->params(n, tokens, values, RiClassSizes{up * vp, uv * vv, std::max(nu, 0) * std::max(nv, 0), 4 * up * vp});
}
RtVoid RiPatchMesh(RtToken type, RtInt nu, RtToken uwrap, RtInt nv, RtToken vwrap, ...) {
    COLLECT_PARAMS(vwrap);
    RiPatchMeshV(type, nu, uwrap, nv, vwrap, p.n(), p.t(), p.v());
}
RtVoid RiSubdivisionMeshV(RtToken scheme, RtInt nfaces, RtInt nvertices[], RtInt vertices[], RtInt ntags,
                          RtToken tags[], RtInt nargs[], RtInt intargs[], RtFloat floatargs[], RtInt n,
                          RtToken tokens[], RtPointer values[]) {
    RiStream* s = streamFor("RiSubdivisionMesh");
    if (!s) return;
    s->request("RiSubdivisionMesh", "SubdivisionMesh");
    s->string(scheme);
    const size_t corners = sum(nvertices, nfaces);
    s->integers(nvertices, size_t(std::max(nfaces, 0)));
    s->integers(vertices, corners);
    ntags = std::max(ntags, 0);
    s->strings(tags, size_t(ntags));
    s->integers(nargs, 2 * size_t(ntags));
    size_t ints = 0, floats = 0;
    for (RtInt i = 0; nargs && i < ntags; ++i) {
        ints += size_t(std::max(nargs[2 * i], 0));
        floats += size_t(std::max(nargs[2 * i + 1], 0));
    }
    s->integers(intargs, ints);
    s->floats(floatargs, floats);
    const int points = largestIndexPlusOne(vertices, corners);
    s->params(n, tokens, values, RiClassSizes{nfaces, points, points, int(corners)});
}
RtVoid RiSubdivisionMesh(RtToken scheme, RtInt nfaces, RtInt nvertices[], RtInt vertices[], RtInt ntags,
                         RtToken tags[], RtInt nargs[], RtInt intargs[], RtFloat floatargs[], ...) {
    COLLECT_PARAMS(floatargs);
    RiSubdivisionMeshV(scheme, nfaces, nvertices, vertices, ntags, tags, nargs, intargs, floatargs, p.n(), p.t(),
                       p.v());
}

// ---- Procedurals
// The built-in procedurals are never called: RiProcedural writes them as RIB requests, which
// the reader makes into generators. Called directly (as some programs do), they do nothing.
RtVoid RiProcDelayedReadArchive(RtPointer, RtFloat) {}
RtVoid RiProcRunProgram(RtPointer, RtFloat) {}
RtVoid RiProcDynamicLoad(RtPointer, RtFloat) {}
RtVoid RiProcFree(RtPointer data) { std::free(data); }

RtVoid RiProcedural(RtPointer data, RtBound bound, RtProcSubdivFunc subdivfunc, RtProcFreeFunc freefunc) {
    RiStream* s = streamFor("RiProcedural");
    if (!s) return;
    s->request("RiProcedural", "Procedural");
    const RtString* strings = static_cast<const RtString*>(data);
    bool copied = true;  // the data was copied into the request: it can be freed now
    if (subdivfunc == RiProcDelayedReadArchive) {
        s->string("DelayedReadArchive");
        s->strings(strings, 1);
    } else if (subdivfunc == RiProcRunProgram || subdivfunc == RiProcDynamicLoad) {
        s->string(subdivfunc == RiProcRunProgram ? "RunProgram" : "DynamicLoad");
        s->strings(strings, 2);
    } else if (subdivfunc) {
        s->string(streyes::kRiFunctionKind);
        const std::string id = s->addFunction(data, subdivfunc, freefunc);
        s->strings(std::vector<RtString>{id.c_str()}.data(), 1);
        copied = false;
    } else {
        s->fail("no subdivide function");
    }
    s->floats(bound, 6);
    if (copied && freefunc) freefunc(data);
}

RtVoid RiReadArchive(RtToken name, RtVoid (*)(RtToken, const char*, ...), ...) {
    if (RiStream* s = streamFor("RiReadArchive")) {
        s->request("RiReadArchive", "ReadArchive");
        s->string(name);
    }
}

}  // extern "C"

namespace {

const char* basisName(RtBasis b) {
    auto same = [&](RtBasis o) { return std::equal(&b[0][0], &b[0][0] + 16, &o[0][0]); };
    if (same(RiBezierBasis)) return "bezier";
    if (same(RiBSplineBasis)) return "b-spline";
    if (same(RiCatmullRomBasis)) return "catmull-rom";
    if (same(RiHermiteBasis)) return "hermite";
    if (same(RiPowerBasis)) return "power";
    return nullptr;
}

}  // namespace

namespace streyes {

int riApiFunctionCount() {
    // Taking every function's address links them all (this file is one object of the archive).
    static const void* const all[] = {
        (void*)RiFrameBegin, (void*)RiFrameEnd, (void*)RiWorldBegin, (void*)RiWorldEnd, (void*)RiAttributeBegin,
        (void*)RiAttributeEnd, (void*)RiTransformBegin, (void*)RiTransformEnd, (void*)RiMotionBegin,
        (void*)RiMotionBeginV, (void*)RiMotionEnd, (void*)RiArchiveRecord, (void*)RiFormat,
        (void*)RiFrameAspectRatio, (void*)RiScreenWindow, (void*)RiClipping, (void*)RiDepthOfField, (void*)RiShutter,
        (void*)RiPixelSamples,
        (void*)RiPixelFilter, (void*)RiProjection, (void*)RiProjectionV, (void*)RiDisplay, (void*)RiDisplayV,
        (void*)RiOption, (void*)RiOptionV, (void*)RiExposure, (void*)RiHider, (void*)RiHiderV,
        (void*)RiSides, (void*)RiOrientation, (void*)RiReverseOrientation, (void*)RiShadingInterpolation,
        (void*)RiDeclare, (void*)RiIdentity, (void*)RiTransform,
        (void*)RiConcatTransform, (void*)RiTranslate, (void*)RiRotate, (void*)RiScale, (void*)RiColor,
        (void*)RiOpacity, (void*)RiShadingRate, (void*)RiGeometricApproximation, (void*)RiBasis, (void*)RiAttribute,
        (void*)RiAttributeV,
        (void*)RiSurface, (void*)RiSurfaceV, (void*)RiLightSource, (void*)RiLightSourceV, (void*)RiIlluminate,
        (void*)RiSphere, (void*)RiSphereV, (void*)RiPolygon, (void*)RiPolygonV, (void*)RiPointsPolygons,
        (void*)RiPointsPolygonsV, (void*)RiPatch, (void*)RiPatchV, (void*)RiPatchMesh, (void*)RiPatchMeshV,
        (void*)RiSubdivisionMesh, (void*)RiSubdivisionMeshV, (void*)RiProcedural, (void*)RiProcDelayedReadArchive,
        (void*)RiProcRunProgram, (void*)RiProcDynamicLoad, (void*)RiProcFree, (void*)RiReadArchive,
        (void*)RiBoxFilter, (void*)RiGaussianFilter, (void*)RiTriangleFilter, (void*)RiCatmullRomFilter,
        (void*)RiSincFilter, (void*)&RiBezierBasis, (void*)&RiBSplineBasis, (void*)&RiCatmullRomBasis,
        (void*)&RiHermiteBasis, (void*)&RiPowerBasis};
    volatile size_t n = sizeof all / sizeof all[0];
    return all[0] ? int(n) : 0;
}

}  // namespace streyes
