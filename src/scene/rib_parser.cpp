#include "scene/rib_parser.h"


#include <algorithm>
#include <atomic>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <unordered_map>

#include "geom/triangulate.h"
#include "streyes/rib.h"

namespace streyes {

namespace {

std::string formatNumber(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", v);
    return buf;
}

std::string plural(size_t n, const std::string& word) {
    return std::to_string(n) + " " + word + (n == 1 ? "" : "s");
}

// `the number 3`, `the string "a"`, `an array of 2 numbers`: what a value is, for messages.
std::string describeValue(const RibValue& v) {
    switch (v.kind) {
    case RibValue::Kind::Number: return "the number " + formatNumber(v.nums[0]);
    case RibValue::Kind::String: return "the string \"" + v.strings[0] + "\"";
    case RibValue::Kind::Array:
        if (v.nums.empty() && v.strings.empty()) return "an empty array";
        return "an array of " +
               (v.strings.empty() ? plural(v.nums.size(), "number") : plural(v.strings.size(), "string"));
    }
    return "?";
}

bool isWhole(double v) { return std::floor(v) == v; }

bool isWholeInt(double v) {
    return isWhole(v) && v >= double(std::numeric_limits<int>::min()) &&
           v <= double(std::numeric_limits<int>::max());
}

}  // namespace

// ---- RibArgs: reading one request's arguments ------------------------------------------------------
// Positional arguments first, in order, then the parameter list. Every complaint names the request
// and, for positional arguments, shows how the request is written.
class RibArgs {
  public:
    RibArgs(const RibRequest& request, const char* usage) : request_(request), usage_(usage) {}

    const std::string& name() const { return request_.name; }
    const SourceLoc& loc() const { return request_.loc; }
    const RibRequest& request() const { return request_; }
    const char* usage() const { return usage_; }
    SourceLoc locAt(int line) const { return {request_.loc.file, line}; }

    bool done() const { return next_ >= request_.args.size(); }
    size_t remaining() const { return request_.args.size() - next_; }
    const RibValue* peek() const { return done() ? nullptr : &request_.args[next_]; }
    const RibValue& take() { return request_.args[next_++]; }
    void skipRest() { next_ = request_.args.size(); }

    // Errors: at the request's line, or at the line of one value. The usage is shown for
    // positional-argument mistakes, where it is the most useful hint.
    [[noreturn]] void fail(const std::string& what) const { failAt(request_.loc.line, what, true); }
    [[noreturn]] void fail(const RibValue& at, const std::string& what) const { failAt(at.line, what, true); }
    [[noreturn]] void failAt(int line, const std::string& what, bool withUsage) const {
        std::string msg = request_.name + ": " + what;
        if (withUsage && usage_ && *usage_) msg += " (usage: " + std::string(usage_) + ")";
        throw InputError(locAt(line), msg);
    }

    // One number (or a one-number array).
    double number(const char* what) {
        if (done()) fail("missing " + std::string(what));
        const RibValue& v = take();
        if (v.isNumber() || (v.isNumericArray() && v.nums.size() == 1)) return v.nums[0];
        fail(v, std::string(what) + " must be a number, got " + describeValue(v));
    }

    // A number that must be a whole number in int range.
    int integer(const char* what) {
        const RibValue* v = peek();
        double x = number(what);
        if (!isWholeInt(x)) fail(*v, std::string(what) + " must be a whole number, got " + formatNumber(x));
        return int(x);
    }

    // One string (or a one-string array).
    std::string string(const char* what) {
        if (done()) fail("missing " + std::string(what));
        const RibValue& v = take();
        if (v.isString() || (v.isStringArray() && v.strings.size() == 1)) return v.strings[0];
        fail(v, std::string(what) + " must be a string, got " + describeValue(v));
    }

    // Exactly n numbers, written either loose (Translate 1 2 3) or as one array (Translate [1 2 3]).
    std::vector<double> numbers(size_t n, const char* what) {
        std::string expected = "expected " + plural(n, "number") + " (" + what + ")";
        if (done()) fail(expected + ", got none");
        if (peek()->kind == RibValue::Kind::Array) {
            const RibValue& v = take();
            if (!v.isNumericArray() || v.nums.size() != n) fail(v, expected + ", got " + describeValue(v));
            return v.nums;
        }
        std::vector<double> r;
        while (r.size() < n && !done() && peek()->isNumber()) r.push_back(take().nums[0]);
        if (r.size() < n) {
            if (r.empty() && !done()) fail(*peek(), expected + ", got " + describeValue(*peek()));
            fail(expected + ", got " + std::to_string(r.size()));
        }
        return r;
    }

    // Any count of numbers: one array, or loose numbers up to the next string.
    std::vector<double> numberList(const char* what) {
        if (!done() && peek()->kind == RibValue::Kind::Array) {
            const RibValue& v = take();
            if (!v.isNumericArray()) fail(v, std::string(what) + " must be numbers, got " + describeValue(v));
            return v.nums;
        }
        std::vector<double> r;
        while (!done() && peek()->isNumber()) r.push_back(take().nums[0]);
        return r;
    }

    void expectEnd() {
        if (!done()) fail(*peek(), "unexpected extra argument: " + describeValue(*peek()));
    }

  private:
    const RibRequest& request_;
    const char* usage_;
    size_t next_ = 0;
};

// One motion key of a bilinear patch: corners in RenderMan patch order, and Cs per corner.
struct RibParser::PatchKey {
    std::array<Vec3d, 4> P;
    bool hasCs = false;
    std::array<Color, 4> Cs{};
    int vertices = 4;
    bool asMesh = false;  // not a bilinear patch: a bicubic patch, or a polygon to cut into faces
};

// ---- Declarations -------------------------------------------------------------------------------
// "[class] type[n] name". The array size may also be written apart ("float [2] st").
std::string parseRibDeclaration(const std::string& text, bool withName, RibParamDecl* decl, std::string* name) {
    // Split into words, with any "[n]" as a word of its own and no spaces inside the brackets.
    std::vector<std::string> words;
    std::string word;
    bool inBrackets = false;
    for (char c : text) {
        if (c == '[') {
            if (!word.empty()) words.push_back(word);
            word = "[";
            inBrackets = true;
        } else if (inBrackets) {
            if (c == ' ' || c == '\t') continue;
            word += c;
            if (c == ']') {
                words.push_back(word);
                word.clear();
                inBrackets = false;
            }
        } else if (c == ' ' || c == '\t' || c == '\n' || c == '\r') {
            if (!word.empty()) words.push_back(word);
            word.clear();
        } else {
            word += c;
        }
    }
    if (inBrackets) return "'[' without ']'";
    if (!word.empty()) words.push_back(word);

    // clang-format off
    static const std::unordered_map<std::string, ParamClass> classes = {
        {"constant", ParamClass::Constant}, {"uniform", ParamClass::Uniform},
        {"varying", ParamClass::Varying},   {"vertex", ParamClass::Vertex},
        {"facevarying", ParamClass::FaceVarying}};
    static const std::unordered_map<std::string, ParamType> types = {
        {"float", ParamType::Float},   {"integer", ParamType::Integer}, {"int", ParamType::Integer},
        {"string", ParamType::String}, {"point", ParamType::Point},     {"vector", ParamType::Vector},
        {"normal", ParamType::Normal}, {"color", ParamType::Color},     {"hpoint", ParamType::HPoint},
        {"matrix", ParamType::Matrix}};
    // clang-format on

    RibParamDecl d;
    size_t i = 0;
    if (i < words.size() && classes.count(words[i])) d.cls = classes.at(words[i++]);
    if (i >= words.size())
        return "missing the type (float, integer, string, point, vector, normal, color, hpoint or matrix)";
    auto type = types.find(words[i]);
    if (type == types.end())
        return "unknown type '" + words[i] +
               "' (types: float, integer, string, point, vector, normal, color, hpoint, matrix; "
               "classes: constant, uniform, varying, vertex, facevarying)";
    d.type = type->second;
    ++i;
    if (i < words.size() && words[i][0] == '[') {
        const std::string& size = words[i];
        char* end = nullptr;
        long n = std::strtol(size.c_str() + 1, &end, 10);
        if (size.size() < 3 || end != size.c_str() + size.size() - 1 || n < 1 || n > 1 << 20)
            return "bad array size '" + size + "' (write a positive whole number, as in float[2])";
        d.arraySize = int(n);
        ++i;
    }
    if (withName) {
        if (i >= words.size()) return "missing the parameter name after the type";
        *name = words[i++];
    }
    if (i < words.size()) return "unexpected '" + words[i] + "'";
    *decl = d;
    return "";
}

// ---- Construction: defaults and predeclared names ------------------------------------------------
RibParser::RibParser(Scene& scene, Log& log)
    : scene_(scene), log_(log), attributes_(std::make_shared<Attributes>()) {
    using C = ParamClass;
    using T = ParamType;
    auto declare = [this](const char* name, C cls, T type, int arraySize = 1) {
        declarations_[name] = RibParamDecl{cls, type, arraySize};
    };
    declare("P", C::Vertex, T::Point);
    declare("Pw", C::Vertex, T::HPoint);
    declare("Pz", C::Vertex, T::Float);
    declare("N", C::Varying, T::Normal);
    declare("Cs", C::Varying, T::Color);
    declare("Os", C::Varying, T::Color);
    declare("s", C::Varying, T::Float);
    declare("t", C::Varying, T::Float);
    declare("st", C::Varying, T::Float, 2);
    for (const char* f : {"Ka", "Kd", "Ks", "roughness", "intensity", "fov", "falloff"})
        declare(f, C::Uniform, T::Float);
    declare("specularcolor", C::Uniform, T::Color);
    declare("lightcolor", C::Uniform, T::Color);
    declare("from", C::Uniform, T::Point);
    declare("to", C::Uniform, T::Point);
    declare("frames", C::Uniform, T::Integer, 2);
    // Standard attribute parameters: Attribute "identifier" "name", Attribute "light" "shadows".
    declare("name", C::Uniform, T::String);
    declare("shadows", C::Uniform, T::String);
}

// ---- Entry points -------------------------------------------------------------------------------
void RibParser::parseFile(const std::string& path) {
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec))
        throw InputError("cannot open scene '" + path + "': " + std::strerror(EISDIR));
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError("cannot open scene '" + path + "': " + std::strerror(errno));
    std::ostringstream text;
    text << in.rdbuf();
    if (in.bad()) throw InputError("cannot read scene '" + path + "': " + std::strerror(errno));
    if (scene_.sourceName.empty()) scene_.sourceName = path;
    parseString(text.str(), path);
}

void RibParser::parseString(const std::string& text, const std::string& sourceName) {
    // Archives that read themselves would recurse without end.
    constexpr int kMaxNesting = 64;
    if (nesting_ >= kMaxNesting)
        throw InputError(lastLoc_, "scene files nested more than " + std::to_string(kMaxNesting) +
                                       " deep (does an archive read itself?)");
    ++nesting_;
    struct Unnest {
        int& n;
        ~Unnest() { --n; }
    } unnest{nesting_};
    RibLexer lexer(text, std::make_shared<const std::string>(sourceName));
    parseTokens(lexer);
    lastLoc_ = lexer.loc(lexer.lastLine());
}

void RibParser::parseTokens(RibLexer& lexer) {
    while (true) {
        RibToken token = lexer.next();
        if (token.kind == RibTokenKind::End) return;
        if (token.kind != RibTokenKind::Request)
            throw InputError(lexer.loc(token.line), "expected a request name, got " + describeToken(token) +
                                                        " with no request before it");
        RibRequest request = readRequest(lexer, std::move(token));
        lastLoc_ = request.loc;
        dispatch(request);
    }
}

// ---- Grouping tokens into requests ----------------------------------------------------------------
// A request's arguments are every value up to the next request name.
RibRequest RibParser::readRequest(RibLexer& lexer, RibToken nameToken) {
    RibRequest request;
    request.name = std::move(nameToken.text);
    request.loc = lexer.loc(nameToken.line);
    while (true) {
        const RibToken& t = lexer.peek();
        if (t.kind == RibTokenKind::Request || t.kind == RibTokenKind::End) break;
        RibToken token = lexer.next();
        RibValue value;
        value.line = token.line;
        switch (token.kind) {
        case RibTokenKind::Number:
            value.kind = RibValue::Kind::Number;
            value.nums.push_back(token.number);
            break;
        case RibTokenKind::String:
            value.kind = RibValue::Kind::String;
            value.strings.push_back(std::move(token.text));
            break;
        case RibTokenKind::ArrayBegin: value = readArray(lexer, token); break;
        default:
            throw InputError(lexer.loc(token.line), "unexpected ']' with no '[' before it (in " + request.name +
                                                        " at line " + std::to_string(request.loc.line) + ")");
        }
        request.args.push_back(std::move(value));
    }
    return request;
}

RibValue RibParser::readArray(RibLexer& lexer, const RibToken& open) {
    RibValue array;
    array.kind = RibValue::Kind::Array;
    array.line = open.line;
    while (true) {
        RibToken t = lexer.next();
        switch (t.kind) {
        case RibTokenKind::ArrayEnd: return array;
        case RibTokenKind::Number:
            if (!array.strings.empty())
                throw InputError(lexer.loc(t.line), "array mixes strings and numbers: " + describeToken(t) +
                                                        " in an array of strings");
            array.nums.push_back(t.number);
            break;
        case RibTokenKind::String:
            if (!array.nums.empty())
                throw InputError(lexer.loc(t.line), "array mixes numbers and strings: " + describeToken(t) +
                                                        " in an array of numbers");
            array.strings.push_back(std::move(t.text));
            break;
        case RibTokenKind::ArrayBegin:
            throw InputError(lexer.loc(t.line), "arrays cannot be nested: '[' inside the array opened at line " +
                                                    std::to_string(open.line));
        case RibTokenKind::Request:
            throw InputError(lexer.loc(open.line), "unterminated array: the '[' opened here has no ']' before " +
                                                       describeToken(t) + " at line " + std::to_string(t.line));
        case RibTokenKind::End:
            throw InputError(lexer.loc(open.line),
                             "unterminated array: the '[' opened here has no ']' before the end of the input");
        }
    }
}

// ---- Dispatch -----------------------------------------------------------------------------------
namespace {

using Handler = void (RibParser::*)(RibArgs&);

enum class Phase { Anywhere, Options, World };        // where in the file a request is valid
enum class MotionRole { None, Transform, Geometry };  // what it may be inside MotionBegin/End

struct RequestInfo {
    Handler handler;
    const char* usage;
    Phase phase;
    MotionRole motion;
};

}  // namespace

void RibParser::dispatch(const RibRequest& request) {
    using P = Phase;
    using M = MotionRole;
    static const std::unordered_map<std::string, RequestInfo> requests = [] {
        std::unordered_map<std::string, RequestInfo> r = {
            {"version", {&RibParser::version, "version number", P::Anywhere, M::None}},
            {"Declare", {&RibParser::declare, "Declare \"name\" \"class type\"", P::Anywhere, M::None}},
            // Options
            {"Format", {&RibParser::format, "Format xres yres pixelaspect", P::Options, M::None}},
            {"Projection",
             {&RibParser::projection, "Projection \"perspective\" \"fov\" degrees | Projection \"orthographic\"",
              P::Options, M::None}},
            {"ScreenWindow",
             {&RibParser::screenWindow, "ScreenWindow left right bottom top", P::Options, M::None}},
            {"FrameAspectRatio", {&RibParser::frameAspectRatio, "FrameAspectRatio ratio", P::Options, M::None}},
            {"Clipping", {&RibParser::clipping, "Clipping near far", P::Options, M::None}},
            {"Shutter", {&RibParser::shutter, "Shutter open close", P::Options, M::None}},
            {"PixelSamples", {&RibParser::pixelSamples, "PixelSamples xsamples ysamples", P::Options, M::None}},
            {"PixelFilter",
             {&RibParser::pixelFilter, "PixelFilter \"gaussian\" xwidth ywidth", P::Options, M::None}},
            {"Display", {&RibParser::display, "Display \"name\" \"type\" \"mode\"", P::Options, M::None}},
            {"Option",
             {&RibParser::option, "Option \"streyes\" \"int frames\" [first last]", P::Options, M::None}},
            // Blocks
            {"WorldBegin", {&RibParser::worldBegin, "WorldBegin", P::Anywhere, M::None}},
            {"WorldEnd", {&RibParser::worldEnd, "WorldEnd", P::Anywhere, M::None}},
            {"AttributeBegin", {&RibParser::attributeBegin, "AttributeBegin", P::Anywhere, M::None}},
            {"AttributeEnd", {&RibParser::attributeEnd, "AttributeEnd", P::Anywhere, M::None}},
            {"TransformBegin", {&RibParser::transformBegin, "TransformBegin", P::Anywhere, M::None}},
            {"TransformEnd", {&RibParser::transformEnd, "TransformEnd", P::Anywhere, M::None}},
            {"MotionBegin", {&RibParser::motionBegin, "MotionBegin [t0 t1 ...]", P::Anywhere, M::None}},
            {"MotionEnd", {&RibParser::motionEnd, "MotionEnd", P::Anywhere, M::None}},
            {"FrameBegin", {&RibParser::frameBeginEnd, "FrameBegin number", P::Anywhere, M::None}},
            {"FrameEnd", {&RibParser::frameBeginEnd, "FrameEnd", P::Anywhere, M::None}},
            // Transforms
            {"Identity", {&RibParser::transformRequest, "Identity", P::Anywhere, M::Transform}},
            {"Transform", {&RibParser::transformRequest, "Transform [16 numbers]", P::Anywhere, M::Transform}},
            {"ConcatTransform",
             {&RibParser::transformRequest, "ConcatTransform [16 numbers]", P::Anywhere, M::Transform}},
            {"Translate", {&RibParser::transformRequest, "Translate dx dy dz", P::Anywhere, M::Transform}},
            {"Rotate", {&RibParser::transformRequest, "Rotate angle dx dy dz", P::Anywhere, M::Transform}},
            {"Scale", {&RibParser::transformRequest, "Scale sx sy sz", P::Anywhere, M::Transform}},
            // Attributes
            {"Color", {&RibParser::color, "Color r g b", P::Anywhere, M::None}},
            {"Opacity", {&RibParser::opacity, "Opacity r g b", P::Anywhere, M::None}},
            {"Surface", {&RibParser::surface, "Surface \"name\" parameters...", P::Anywhere, M::None}},
            {"ShadingRate", {&RibParser::shadingRate, "ShadingRate area", P::Anywhere, M::None}},
            {"Attribute", {&RibParser::attribute, "Attribute \"category\" parameters...", P::Anywhere, M::None}},
            {"LightSource",
             {&RibParser::lightSource, "LightSource \"name\" handle parameters...", P::World, M::None}},
            {"Illuminate", {&RibParser::illuminate, "Illuminate handle onoff", P::World, M::None}},
            // Geometry
            {"Patch",
             {&RibParser::patchOrPolygon, "Patch \"bilinear\" \"P\" [12 numbers]", P::World, M::Geometry}},
            {"Polygon", {&RibParser::patchOrPolygon, "Polygon \"P\" [x y z ...]", P::World, M::Geometry}},
            {"Basis", {&RibParser::basis, "Basis ubasis ustep vbasis vstep", P::Anywhere, M::None}},
            {"PatchMesh",
             {&RibParser::curvedGeometry, "PatchMesh \"bicubic\"|\"bilinear\" nu \"nonperiodic\"|\"periodic\" nv "
              "\"nonperiodic\"|\"periodic\" \"P\" [...]", P::World, M::Geometry}},
            {"SubdivisionMesh",
             {&RibParser::curvedGeometry, "SubdivisionMesh \"catmull-clark\" [nvertices] [vertices] [tags] [nargs] "
              "[intargs] [floatargs] \"P\" [...]", P::World, M::Geometry}},
            {"Sphere", {&RibParser::curvedGeometry, "Sphere radius zmin zmax thetamax", P::World, M::Geometry}},
            {"Cylinder", {&RibParser::curvedGeometry, "Cylinder radius zmin zmax thetamax", P::World, M::Geometry}},
            {"Cone", {&RibParser::curvedGeometry, "Cone height radius thetamax", P::World, M::Geometry}},
            {"Disk", {&RibParser::curvedGeometry, "Disk height radius thetamax", P::World, M::Geometry}},
            {"Paraboloid",
             {&RibParser::curvedGeometry, "Paraboloid rmax zmin zmax thetamax", P::World, M::Geometry}},
            {"Hyperboloid",
             {&RibParser::curvedGeometry, "Hyperboloid x1 y1 z1 x2 y2 z2 thetamax", P::World, M::Geometry}},
            {"Torus",
             {&RibParser::curvedGeometry, "Torus majorradius minorradius phimin phimax thetamax", P::World,
              M::Geometry}},
            {"GeneralPolygon",
             {&RibParser::curvedGeometry, "GeneralPolygon [nvertices per loop] \"P\" [...]", P::World, M::Geometry}},
            {"PointsPolygons",
             {&RibParser::curvedGeometry, "PointsPolygons [nvertices] [vertices] \"P\" [...]", P::World, M::Geometry}},
            {"PointsGeneralPolygons",
             {&RibParser::curvedGeometry, "PointsGeneralPolygons [nloops] [nvertices] [vertices] \"P\" [...]", P::World,
              M::Geometry}},
            // Procedurals and archives.
            {"Procedural",
             {&RibParser::procedural, "Procedural \"DelayedReadArchive\" [\"file\"] [xmin xmax ymin ymax zmin zmax]",
              P::World, M::None}},
            {"ReadArchive", {&RibParser::readArchive, "ReadArchive \"file\"", P::Anywhere, M::None}},
            // Retained geometry and inline archives: their contents are skipped.
            {"ObjectBegin", {&RibParser::skippedBlockBegin, "ObjectBegin handle", P::Anywhere, M::None}},
            {"ArchiveBegin", {&RibParser::skippedBlockBegin, "ArchiveBegin \"name\"", P::Anywhere, M::None}},
        };
        // clang-format off
        // RIB requests outside the subset: warned about once and skipped.
        for (const char* name :
             {"Exposure", "Quantize", "Hider", "Imager", "GeometricApproximation", "Sides", "Orientation",
              "ReverseOrientation", "ColorSamples", "CropWindow", "DepthOfField", "RelativeDetail",
              "PixelVariance", "Atmosphere", "Interior", "Exterior", "Displacement", "Deformation", "TextureCoordinates", "Matte",
              "Bound", "Detail", "DetailRange", "Perspective", "Skew", "CoordinateSystem", "CoordSysTransform",
              "ScopedCoordinateSystem", "ShadingInterpolation", "AreaLightSource", "SolidBegin",
              "SolidEnd", "ObjectEnd", "ArchiveEnd", "MakeTexture", "MakeBump", "MakeLatLongEnvironment",
              "MakeCubeFaceEnvironment", "MakeShadow", "MakeBrickMap", "ErrorHandler", "ArchiveRecord",
              "Resource", "ResourceBegin", "ResourceEnd", "Camera", "IfBegin", "IfEnd", "Else", "ElseIf",
              "System", "Shader", "Bxdf", "Pattern", "Integrator", "DisplayFilter", "SampleFilter",
              "DisplayChannel", "PixelSampleImager", "EditBegin", "EditEnd", "EditAttributeBegin",
              "EditAttributeEnd", "EditWorldBegin", "EditWorldEnd"})
            r.emplace(name, RequestInfo{&RibParser::unsupported, "", P::Anywhere, M::None});
        // Geometry outside the subset: skipped with a warning (later features add them).
        for (const char* name :
             {"NuPatch", "TrimCurve", "HierarchicalSubdivisionMesh", "Points", "Curves", "Blobby", "Procedural2",
              "Geometry", "Volume", "ObjectInstance"})
            r.emplace(name, RequestInfo{&RibParser::unsupportedGeometry, "", P::World, M::Geometry});
        // clang-format on
        return r;
    }();

    const std::string& name = request.name;

    // Inside ObjectBegin/ObjectEnd or ArchiveBegin/ArchiveEnd: skip to the matching end.
    if (skipping_) {
        if (name == skipping_->beginName) ++skipping_->depth;
        if (name == skipping_->endName && --skipping_->depth == 0) skipping_.reset();
        return;
    }

    auto found = requests.find(name);
    if (found == requests.end()) {
        std::string hint = " (see docs/SCENE-FORMAT.md for the requests streyes reads)";
        for (const auto& [known, info] : requests) {
            if (known.size() == name.size() &&
                std::equal(known.begin(), known.end(), name.begin(),
                           [](char a, char b) { return std::tolower(a) == std::tolower(b); }))
                hint = ": did you mean '" + known + "'? (request names are case-sensitive)";
        }
        throw InputError(request.loc, "unknown request '" + name + "'" + hint);
    }
    const RequestInfo& info = found->second;

    // A request that is valid only in part of the file.
    auto checkPhase = [&] {
        if (info.phase == Phase::Options && worldState_ != WorldState::BeforeWorld)
            throw InputError(request.loc, name + " is an option: it must come before WorldBegin (line " +
                                              std::to_string(worldBegin_.line) + ")");
        if (info.phase == Phase::World && worldState_ != WorldState::InWorld) {
            std::string where =
                worldState_ == WorldState::BeforeWorld ? "it comes before WorldBegin" : "it comes after WorldEnd";
            throw InputError(request.loc, name + " is only valid between WorldBegin and WorldEnd, but " + where);
        }
    };

    // Inside MotionBegin/MotionEnd: keep the requests until MotionEnd, checking what we can now.
    if (motion_ && name != "MotionEnd") {
        std::string block = "MotionBegin at line " + std::to_string(motion_->begin.line);
        if (name == "MotionBegin")
            throw InputError(request.loc, "nested MotionBegin: the " + block + " is still open");
        if (info.motion == MotionRole::None)
            throw InputError(request.loc, name + " cannot appear inside a motion block (" + block +
                                              " has no MotionEnd yet): only transforms (Translate, Rotate, Scale, "
                                              "ConcatTransform, Transform, Identity) or geometry (Patch, PatchMesh, "
                                              "Polygon, SubdivisionMesh, a quadric, ...) can move");
        checkPhase();
        const std::vector<RibRequest>& held = motion_->requests;
        if (!held.empty() && name != held.front().name)
            throw InputError(request.loc, "every request in a motion block must be the same: " + name + " after " +
                                              held.front().name + " (" + block + ")");
        if (held.size() == motion_->times.size())
            throw InputError(request.loc, "the " + block + " gives " + plural(motion_->times.size(), "time") +
                                              ", but this is request " + std::to_string(held.size() + 1) +
                                              " in the block: give one request per time");
        motion_->requests.push_back(request);
        motion_->usage = info.usage;
        return;
    }

    checkPhase();
    RibArgs args(request, info.usage);
    (this->*info.handler)(args);
}

// ---- Parameter lists ----------------------------------------------------------------------------
// ("name" value) pairs. The name is a declared name or an inline declaration; the value is a
// number, a string or an array, and must fit the declared type. How many values a use needs
// (one color, four vertex points) is checked where the parameter is used.
ParamList RibParser::readParams(RibArgs& args) {
    ParamList list;
    while (!args.done()) {
        const RibValue& nameValue = args.take();
        if (!nameValue.isString())
            args.failAt(nameValue.line, "expected a parameter name (a string), got " + describeValue(nameValue),
                        true);
        if (args.done())
            args.failAt(nameValue.line, "parameter \"" + nameValue.strings[0] + "\" has no value", false);
        Param p = makeParam(args, nameValue, args.take());
        // A parameter given twice: the later value wins.
        auto same =
            std::find_if(list.params.begin(), list.params.end(), [&](const Param& q) { return q.name == p.name; });
        if (same != list.params.end())
            *same = std::move(p);
        else
            list.params.push_back(std::move(p));
    }
    return list;
}

Param RibParser::makeParam(RibArgs& args, const RibValue& nameValue, const RibValue& value) const {
    const std::string& spelled = nameValue.strings[0];
    auto fail = [&](const std::string& what) { args.failAt(nameValue.line, what, false); };

    Param p;
    p.loc = args.locAt(nameValue.line);
    RibParamDecl decl;
    if (spelled.find_first_of(" \t\n[") != std::string::npos) {
        std::string error = parseRibDeclaration(spelled, true, &decl, &p.name);
        if (!error.empty()) fail("invalid inline declaration \"" + spelled + "\": " + error);
    } else {
        auto found = declarations_.find(spelled);
        if (found == declarations_.end()) {
            std::string example = value.isString() || value.isStringArray() ? "uniform string " : "uniform float ";
            fail("parameter '" + spelled + "' is not declared: use an inline declaration like \"" + example +
                 spelled + "\" or Declare it first");
        }
        p.name = spelled;
        decl = found->second;
    }
    p.type = decl.type;
    p.cls = decl.cls;
    p.arraySize = decl.arraySize;

    std::string declared = std::string(paramClassName(p.cls)) + " " + paramTypeName(p.type);
    if (p.type == ParamType::String) {
        if (!(value.isString() || value.isStringArray()))
            fail("parameter '" + p.name + "' is declared " + declared + " but its value is " +
                 describeValue(value));
        p.strings = value.strings;
    } else {
        if (!(value.isNumber() || value.isNumericArray()))
            fail("parameter '" + p.name + "' is declared " + declared + " but its value is " +
                 describeValue(value));
        p.nums = value.nums;
        if (p.type == ParamType::Integer)
            for (double v : p.nums)
                if (!isWholeInt(v))
                    fail("parameter '" + p.name + "' is declared " + declared + " but has the value " +
                         formatNumber(v));
    }
    if (p.nums.empty() && p.strings.empty())
        fail("parameter '" + p.name + "' has an empty array: give it a value");
    return p;
}

void RibParser::warnUnusedParams(const ParamList& params, const std::vector<std::string>& known,
                                 const std::string& owner) {
    for (const Param& p : params.params)
        if (std::find(known.begin(), known.end(), p.name) == known.end())
            log_.warnOnce("param:" + owner + ":" + p.name, p.loc,
                          owner + " has no parameter '" + p.name + "': ignored");
}

// ---- Simple requests ------------------------------------------------------------------------------
void RibParser::version(RibArgs& args) { args.skipRest(); }

void RibParser::declare(RibArgs& args) {
    std::string name = args.string("name");
    const RibValue* declValue = args.peek();
    std::string text = args.string("declaration");
    args.expectEnd();
    if (name.empty() || name.find_first_of(" \t\n[") != std::string::npos)
        args.fail("the name \"" + name + "\" must be one word");
    RibParamDecl decl;
    std::string unused;
    std::string error = parseRibDeclaration(text, false, &decl, &unused);
    if (!error.empty()) args.fail(*declValue, "invalid declaration \"" + text + "\" for '" + name + "': " + error);
    declarations_[name] = decl;
}

void RibParser::unsupported(RibArgs& args) {
    log_.warnOnce("request:" + args.name(), args.loc(), "unsupported request '" + args.name() + "' ignored");
    args.skipRest();
}

void RibParser::frameBeginEnd(RibArgs& args) {
    log_.warnOnce("request:FrameBegin", args.loc(),
                  "FrameBegin/FrameEnd ignored: the frames rendered come from Option \"streyes\" \"int frames\" "
                  "or the command line");
    args.skipRest();
}

void RibParser::skippedBlockBegin(RibArgs& args) {
    std::string endName = args.name() == "ObjectBegin" ? "ObjectEnd" : "ArchiveEnd";
    log_.warnOnce("request:" + args.name(), args.loc(),
                  "unsupported request '" + args.name() + "' ignored, with everything up to its " + endName);
    args.skipRest();
    skipping_ = SkippedBlock{args.name(), endName, args.loc(), 1};
}

// ---- Options ------------------------------------------------------------------------------------
void RibParser::format(RibArgs& args) {
    const RibValue* xv = args.peek();
    int xres = args.integer("xres");
    const RibValue* yv = args.peek();
    int yres = args.integer("yres");
    const RibValue* av = args.peek();
    double aspect = args.done() ? 1.0 : args.number("pixelaspect");
    args.expectEnd();
    constexpr int kMaxRes = 65536;
    if (xres < 1 || xres > kMaxRes)
        args.fail(*xv, "xres must be between 1 and 65536, got " + std::to_string(xres));
    if (yres < 1 || yres > kMaxRes)
        args.fail(*yv, "yres must be between 1 and 65536, got " + std::to_string(yres));
    if (!(aspect > 0)) args.fail(*av, "pixelaspect must be positive, got " + formatNumber(aspect));
    scene_.camera.xres = xres;
    scene_.camera.yres = yres;
    scene_.camera.pixelAspect = aspect;
}

// Projection also makes the current coordinate system the camera's: the CTM restarts at identity.
void RibParser::projection(RibArgs& args) {
    const RibValue* nameValue = args.peek();
    std::string name = args.string("projection name");
    if (name != "perspective" && name != "orthographic")
        args.fail(*nameValue,
                  "projection \"" + name + "\" is not supported: use \"perspective\" or \"orthographic\"");
    ParamList params = readParams(args);
    if (name == "perspective") {
        double fov = params.getFloat("fov", 90.0);
        if (!(fov > 0 && fov < 180))
            throw InputError(params.find("fov")->loc,
                             "Projection: fov must be between 0 and 180 degrees, got " + formatNumber(fov));
        scene_.camera.projection = ProjectionKind::Perspective;
        scene_.camera.fov = fov;
        warnUnusedParams(params, {"fov"}, "Projection \"perspective\"");
    } else {
        scene_.camera.projection = ProjectionKind::Orthographic;
        warnUnusedParams(params, {}, "Projection \"orthographic\"");
    }
    if (!ctm_.isStatic() || ctm_.keys()[0] != Matrix4::identity())
        log_.warnOnce("projection:ctm", args.loc(),
                      "transforms before Projection are ignored: put camera transforms after Projection");
    ctm_ = MotionTransform();
}

void RibParser::screenWindow(RibArgs& args) {
    std::vector<double> w = args.numbers(4, "left right bottom top");
    args.expectEnd();
    if (w[0] == w[1] || w[2] == w[3]) args.fail("the window is empty (left = right or bottom = top)");
    std::copy(w.begin(), w.end(), scene_.camera.screenWindow);
    scene_.camera.hasScreenWindow = true;
}

void RibParser::frameAspectRatio(RibArgs& args) {
    double ratio = args.number("ratio");
    args.expectEnd();
    if (!(ratio > 0)) args.fail("the ratio must be positive, got " + formatNumber(ratio));
    scene_.camera.frameAspect = ratio;
}

void RibParser::clipping(RibArgs& args) {
    std::vector<double> c = args.numbers(2, "near far");
    args.expectEnd();
    if (!(c[0] > 0)) args.fail("near must be positive, got " + formatNumber(c[0]));
    if (!(c[1] > c[0]))
        args.fail("far must be greater than near, got near " + formatNumber(c[0]) + " and far " +
                  formatNumber(c[1]));
    scene_.camera.nearClip = c[0];
    scene_.camera.farClip = c[1];
}

void RibParser::shutter(RibArgs& args) {
    std::vector<double> s = args.numbers(2, "open close");
    args.expectEnd();
    if (s[1] < s[0])
        args.fail("close must not come before open, got open " + formatNumber(s[0]) + " and close " +
                  formatNumber(s[1]));
    scene_.settings.shutterOpen = s[0];
    scene_.settings.shutterClose = s[1];
}

void RibParser::pixelSamples(RibArgs& args) {
    std::vector<double> s = args.numbers(2, "xsamples ysamples");
    args.expectEnd();
    constexpr int kMaxSamples = 64;
    for (double v : s) {
        if (!(v >= 1)) args.fail("samples must be at least 1, got " + formatNumber(v));
        if (v > kMaxSamples) args.fail("at most 64 samples per axis are supported, got " + formatNumber(v));
    }
    scene_.settings.pixelSamplesX = int(std::ceil(s[0]));
    scene_.settings.pixelSamplesY = int(std::ceil(s[1]));
}

void RibParser::pixelFilter(RibArgs& args) {
    std::string type = args.string("filter name");
    std::vector<double> w = args.numbers(2, "xwidth ywidth");
    args.expectEnd();
    if (!(w[0] > 0 && w[1] > 0))
        args.fail("filter widths must be positive, got " + formatNumber(w[0]) + " " + formatNumber(w[1]));
    // The resolver keeps 64 taps a side, and each bucket renders a guard band of half the width.
    constexpr double kMaxFilterWidth = 32;
    if (w[0] > kMaxFilterWidth || w[1] > kMaxFilterWidth)
        args.fail("filter widths must be at most 32 pixels, got " + formatNumber(w[0]) + " " + formatNumber(w[1]));
    if (type == "catmullrom") type = "catmull-rom";
    if (type != "box" && type != "gaussian" && type != "catmull-rom") {
        log_.warnOnce(
            "pixelfilter:" + type, args.loc(),
            "pixel filter \"" + type + "\" is not supported (box, gaussian, catmull-rom): using gaussian 2 2");
        scene_.settings.filter = FilterDesc{};
        return;
    }
    scene_.settings.filter = FilterDesc{type, w[0], w[1]};
}

// A name starting with '+' adds a display; any other name replaces the displays given so far.
void RibParser::display(RibArgs& args) {
    const RibValue* nameValue = args.peek();
    std::string name = args.string("name");
    std::string type = args.string("type");
    const RibValue* modeValue = args.peek();
    std::string mode = args.string("mode");
    args.skipRest();  // display parameters (compression, quantization, ...) are not used
    if (mode != "rgb" && mode != "rgba" && mode != "rgbaz")
        args.fail(*modeValue, "display mode \"" + mode + "\" is not supported: use rgb, rgba or rgbaz");
    bool additional = !name.empty() && name[0] == '+';
    if (additional) name.erase(0, 1);
    if (name.empty()) args.fail(*nameValue, "the display name is empty");
    if (!additional) scene_.settings.displays.clear();
    scene_.settings.displays.push_back(DisplayDesc{name, type, mode, args.loc()});
}

void RibParser::option(RibArgs& args) {
    std::string category = args.string("option name");
    if (category != "streyes") {
        log_.warnOnce("option:" + category, args.loc(), "Option \"" + category + "\" is not supported: ignored");
        args.skipRest();
        return;
    }
    ParamList params = readParams(args);
    if (const Param* frames = params.find("frames")) {
        if (frames->type != ParamType::Integer || frames->nums.size() != 2)
            throw InputError(frames->loc,
                             "Option \"streyes\": frames must be two integers [first last], as in "
                             "Option \"streyes\" \"int frames\" [1 24]");
        int first = int(frames->nums[0]), last = int(frames->nums[1]);
        if (first > last)
            throw InputError(frames->loc, "Option \"streyes\": the first frame (" + std::to_string(first) +
                                              ") comes after the last (" + std::to_string(last) + ")");
        scene_.settings.hasFrames = true;
        scene_.settings.firstFrame = first;
        scene_.settings.lastFrame = last;
    }
    warnUnusedParams(params, {"frames"}, "Option \"streyes\"");
}

// ---- Blocks -------------------------------------------------------------------------------------
// WorldBegin fixes the camera: the CTM so far is world-to-camera, and the world starts at identity.
void RibParser::worldBegin(RibArgs& args) {
    args.expectEnd();
    if (fragment_) args.fail("a procedural's output is inside the world already: it cannot begin one");
    if (worldState_ != WorldState::BeforeWorld)
        args.fail("only one WorldBegin ... WorldEnd block per file is supported (the first began at line " +
                  std::to_string(worldBegin_.line) + ")");
    if (!blocks_.empty()) {
        const Block& open = blocks_.back();
        const char* kind = open.kind == BlockKind::Attribute ? "AttributeBegin" : "TransformBegin";
        throw InputError(open.begin, std::string(kind) + " is still open at WorldBegin (line " +
                                         std::to_string(args.loc().line) + "): close it before WorldBegin");
    }
    scene_.camera.worldToCamera = ctm_;
    scene_.camera.loc = args.loc();
    blocks_.push_back(Block{BlockKind::World, args.loc(), attributes_, ctm_});
    ctm_ = MotionTransform();
    worldState_ = WorldState::InWorld;
    worldBegin_ = args.loc();
}

namespace {

const char* beginName(int kind) {
    static const char* names[] = {"WorldBegin", "AttributeBegin", "TransformBegin"};
    return names[kind];
}
const char* endName(int kind) {
    static const char* names[] = {"WorldEnd", "AttributeEnd", "TransformEnd"};
    return names[kind];
}

}  // namespace

void RibParser::worldEnd(RibArgs& args) {
    args.expectEnd();
    if (fragment_) args.fail("a procedural's output cannot end the world block");
    if (worldState_ != WorldState::InWorld) args.fail("WorldEnd without WorldBegin");
    const Block& open = blocks_.back();
    if (open.kind != BlockKind::World)
        throw InputError(open.begin, std::string(beginName(int(open.kind))) + " is never closed: WorldEnd (line " +
                                         std::to_string(args.loc().line) + ") comes before its " +
                                         endName(int(open.kind)));
    attributes_ = open.attributes;
    ctm_ = open.ctm;
    blocks_.pop_back();
    worldState_ = WorldState::AfterWorld;
}

void RibParser::attributeBegin(RibArgs& args) {
    args.expectEnd();
    blocks_.push_back(Block{BlockKind::Attribute, args.loc(), attributes_, ctm_});
}

void RibParser::transformBegin(RibArgs& args) {
    args.expectEnd();
    blocks_.push_back(Block{BlockKind::Transform, args.loc(), nullptr, ctm_});
}

void RibParser::attributeEnd(RibArgs& args) {
    args.expectEnd();
    if (blocks_.empty() || blocks_.back().kind == BlockKind::World)
        args.fail("AttributeEnd without a matching AttributeBegin");
    const Block& open = blocks_.back();
    if (open.kind != BlockKind::Attribute)
        args.fail("AttributeEnd does not match the TransformBegin at line " + std::to_string(open.begin.line) +
                  ": close that with TransformEnd first");
    attributes_ = open.attributes;
    ctm_ = open.ctm;
    blocks_.pop_back();
}

void RibParser::transformEnd(RibArgs& args) {
    args.expectEnd();
    if (blocks_.empty() || blocks_.back().kind == BlockKind::World)
        args.fail("TransformEnd without a matching TransformBegin");
    const Block& open = blocks_.back();
    if (open.kind != BlockKind::Transform)
        args.fail("TransformEnd does not match the AttributeBegin at line " + std::to_string(open.begin.line) +
                  ": close that with AttributeEnd first");
    ctm_ = open.ctm;
    blocks_.pop_back();
}

// MotionBegin opens a block whose requests are held (see dispatch) and applied together at MotionEnd.
void RibParser::motionBegin(RibArgs& args) {
    std::vector<double> times = args.numberList("times");
    args.expectEnd();
    if (times.empty()) args.fail("MotionBegin needs at least one time");
    for (size_t i = 1; i < times.size(); ++i)
        if (!(times[i] > times[i - 1]))
            args.fail("motion times must increase strictly, but " + formatNumber(times[i]) + " follows " +
                      formatNumber(times[i - 1]));
    motion_ = MotionBlock{std::move(times), args.loc(), {}, ""};
}

void RibParser::motionEnd(RibArgs& args) {
    args.expectEnd();
    if (!motion_) args.fail("MotionEnd without MotionBegin");
    MotionBlock block = std::move(*motion_);
    motion_.reset();
    if (block.requests.size() != block.times.size())
        args.fail("the MotionBegin at line " + std::to_string(block.begin.line) + " gives " +
                  plural(block.times.size(), "time") + ", but the block holds " +
                  plural(block.requests.size(), "request") + ": give one request per time");

    const std::string& name = block.requests.front().name;
    if (name == "Patch" || name == "Polygon") {
        std::vector<PatchKey> keys(block.requests.size());
        for (size_t i = 0; i < keys.size(); ++i) {
            RibArgs keyArgs(block.requests[i], block.usage);
            if (!readPatchKey(keyArgs, &keys[i])) {
                // A bicubic patch or a larger polygon: the curved/polygon-mesh path.
                if (keys[i].asMesh) geometry(block.times, block.requests, block.usage);
                return;
            }
        }
        addPatch(block.times, keys, block.requests.front().loc);
    } else if (name == "Identity" || name == "Transform" || name == "ConcatTransform" || name == "Translate" ||
               name == "Rotate" || name == "Scale") {
        std::vector<Matrix4> keys;
        bool replaces = false;
        for (const RibRequest& request : block.requests) {
            RibArgs keyArgs(request, block.usage);
            keys.push_back(readTransformMatrix(keyArgs, &replaces));
        }
        applyTransform(MotionTransform(block.times, std::move(keys)), replaces, block.requests.front().loc);
    } else if (name == "PatchMesh" || name == "SubdivisionMesh" || name == "Sphere" || name == "Cylinder" ||
               name == "Cone" || name == "Disk" || name == "Paraboloid" || name == "Hyperboloid" || name == "Torus" ||
               name == "GeneralPolygon" || name == "PointsPolygons" || name == "PointsGeneralPolygons") {
        geometry(block.times, block.requests, block.usage);
    } else {
        RibArgs first(block.requests.front(), block.usage);
        unsupportedGeometry(first);
    }
}

// ---- Transforms ---------------------------------------------------------------------------------
// Row vectors: the request's matrix applies to points first, so CTM(t) = R(t) * CTM(t).
void RibParser::applyTransform(const MotionTransform& request, bool replaces, const SourceLoc& loc) {
    MotionTransform result = replaces ? request : request.then(ctm_);
    for (const Matrix4& m : result.keys())
        if (!m.isFinite())
            throw InputError(loc, "the transform overflows: its matrix has values beyond the range of doubles");
    ctm_ = std::move(result);
}

Matrix4 RibParser::readTransformMatrix(RibArgs& args, bool* replaces) {
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

void RibParser::transformRequest(RibArgs& args) {
    bool replaces = false;
    Matrix4 m = readTransformMatrix(args, &replaces);
    applyTransform(MotionTransform(m), replaces, args.loc());
}

// ---- Attributes ---------------------------------------------------------------------------------
// Primitives share the Attributes they were created with. Before changing the current attributes
// we copy them if anything else (a primitive, a saved block) still holds them.
Attributes& RibParser::mutableAttributes() {
    if (attributes_.use_count() > 1) attributes_ = std::make_shared<Attributes>(*attributes_);
    return *attributes_;
}

void RibParser::color(RibArgs& args) {
    std::vector<double> c = args.numbers(3, "r g b");
    args.expectEnd();
    mutableAttributes().color = Color(float(c[0]), float(c[1]), float(c[2]));
}

void RibParser::opacity(RibArgs& args) {
    std::vector<double> o = args.numbers(3, "r g b");
    args.expectEnd();
    if (o[0] < 1 || o[1] < 1 || o[2] < 1)
        log_.warnOnce("opacity", args.loc(), "transparency is not supported yet: rendering as opaque");
    mutableAttributes().opacity = Color(float(o[0]), float(o[1]), float(o[2]));
}

void RibParser::shadingRate(RibArgs& args) {
    double rate = args.number("area");
    args.expectEnd();
    if (!(rate > 0)) args.fail("the shading rate must be positive, got " + formatNumber(rate));
    mutableAttributes().shadingRate = rate;
}

void RibParser::surface(RibArgs& args) {
    static const std::map<std::string, std::vector<std::string>> shaders = {
        {"constant", {}},
        {"defaultsurface", {}},
        {"matte", {"Ka", "Kd"}},
        {"plastic", {"Ka", "Kd", "Ks", "roughness", "specularcolor"}}};
    std::string name = args.string("shader name");
    auto shader = shaders.find(name);
    if (shader == shaders.end()) {
        log_.warnOnce("surface:" + name, args.loc(),
                      "surface shader \"" + name +
                          "\" is not supported (constant, matte, plastic, "
                          "defaultsurface): using defaultsurface");
        args.skipRest();
        mutableAttributes().surface = ShaderDesc{"defaultsurface", {}, args.loc()};
        return;
    }
    ParamList params = readParams(args);
    // Check the values now, so that a bad one is reported here rather than while shading.
    for (const char* f : {"Ka", "Kd", "Ks"}) params.getFloat(f, 0);
    if (params.getFloat("roughness", 0.1) <= 0)
        throw InputError(params.find("roughness")->loc, "Surface: roughness must be positive");
    params.getColor("specularcolor", Color(1, 1, 1));
    warnUnusedParams(params, shader->second, "Surface \"" + name + "\"");
    mutableAttributes().surface = ShaderDesc{name, std::move(params), args.loc()};
}

// Attribute "category" values are kept as "category:name" for the features that read them.
void RibParser::attribute(RibArgs& args) {
    static const std::set<std::string> categories = {"identifier", "light", "user", "streyes"};
    std::string category = args.string("category");
    if (!categories.count(category)) {
        log_.warnOnce("attribute:" + category, args.loc(),
                      "Attribute \"" + category + "\" is not supported: ignored");
        args.skipRest();
        return;
    }
    ParamList params = readParams(args);
    Attributes& a = mutableAttributes();
    for (Param& p : params.params) {
        if ((p.nums.size() + p.strings.size()) % size_t(p.componentsPerItem()) != 0)
            throw InputError(p.loc, "Attribute \"" + category + "\": parameter '" + p.name + "' has " +
                                        plural(p.nums.size() + p.strings.size(), "value") +
                                        ", not a whole number of " + paramTypeName(p.type) + "s");
        if (category == "light" && p.name == "shadows" && p.type == ParamType::String) {
            const std::string v = p.strings.empty() ? "" : p.strings.front();
            if (v != "on" && v != "off")
                throw InputError(p.loc, "Attribute \"light\" \"shadows\": expected \"on\" or \"off\", not \"" + v + "\"");
        }
        p.name = category + ":" + p.name;
        auto same = std::find_if(a.user.params.begin(), a.user.params.end(),
                                 [&](const Param& q) { return q.name == p.name; });
        if (same != a.user.params.end())
            *same = std::move(p);
        else
            a.user.params.push_back(std::move(p));
    }
}

// ---- Lights -------------------------------------------------------------------------------------
// A light is on in the attribute block where it is declared (and the blocks inside it): its index
// goes into the current attributes' light list, which AttributeEnd restores.
void RibParser::lightSource(RibArgs& args) {
    static const std::map<std::string, std::vector<std::string>> shaders = {
        {"ambientlight", {"intensity", "lightcolor"}},
        {"distantlight", {"intensity", "lightcolor", "from", "to"}},
        {"pointlight", {"intensity", "lightcolor", "from"}}};
    std::string name = args.string("shader name");

    // The handle: a number (RIB 3.2) or a string (later versions). Parameters come in pairs, so a
    // string before an odd number of remaining values is a handle.
    std::string handle;
    if (const RibValue* v = args.peek()) {
        if (v->isNumber() || (v->isString() && args.remaining() % 2 == 1)) {
            handle = v->isNumber() ? std::to_string(args.integer("handle")) : args.string("handle");
        }
    }

    auto shader = shaders.find(name);
    if (shader == shaders.end()) {
        log_.warnOnce("light:" + name, args.loc(),
                      "light shader \"" + name +
                          "\" is not supported (ambientlight, distantlight, pointlight): "
                          "light skipped");
        args.skipRest();
        if (!handle.empty()) skippedLightHandles_.insert(handle);
        return;
    }
    ParamList params = readParams(args);
    params.getFloat("intensity", 1.0);
    params.getColor("lightcolor", Color(1, 1, 1));
    params.getPoint("from", Vec3d(0, 0, 0));
    params.getPoint("to", Vec3d(0, 0, 1));
    warnUnusedParams(params, shader->second, "LightSource \"" + name + "\"");

    int index = int(scene_.lights.size());
    const bool shadows = attributes_->user.getString("light:shadows", "off") == "on";
    scene_.lights.push_back(LightDesc{name, std::move(params), ctm_, args.loc(), shadows});
    mutableAttributes().lights.push_back(index);
    if (!handle.empty()) {
        lightHandles_[handle] = index;
        skippedLightHandles_.erase(handle);
    }
}

void RibParser::illuminate(RibArgs& args) {
    if (args.done()) args.fail("missing handle");
    std::string handle = args.peek()->isNumber() ? std::to_string(args.integer("handle")) : args.string("handle");
    int on = args.integer("onoff");
    args.expectEnd();
    if (skippedLightHandles_.count(handle)) return;
    auto light = lightHandles_.find(handle);
    if (light == lightHandles_.end()) args.fail("no light has the handle '" + handle + "'");
    std::vector<int>& lights = mutableAttributes().lights;
    auto it = std::find(lights.begin(), lights.end(), light->second);
    if (on && it == lights.end()) lights.push_back(light->second);
    if (!on && it != lights.end()) lights.erase(it);
}

// ---- Geometry -----------------------------------------------------------------------------------
namespace {

// How many items a parameter of class `cls` has on a single face with `vertices` vertices.
size_t itemsOnFace(ParamClass cls, int vertices) {
    return cls == ParamClass::Constant || cls == ParamClass::Uniform ? 1 : size_t(vertices);
}

size_t valueCount(const Param& p) { return p.type == ParamType::String ? p.strings.size() : p.nums.size(); }

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

}  // namespace

// Reads `Patch "bilinear" ...` or `Polygon ...` into one key. Returns false when the primitive is
// outside the subset (a warning has been given) and should be skipped.
bool RibParser::readPatchKey(RibArgs& args, PatchKey* key) {
    int vertices = 4;
    if (args.name() == "Patch") {
        const RibValue* typeValue = args.peek();
        std::string type = args.string("type");
        if (type == "bicubic") {
            key->asMesh = true;  // read as a patch mesh
            return false;
        }
        if (type != "bilinear")
            args.fail(*typeValue, "the patch type must be \"bilinear\" or \"bicubic\", got \"" + type + "\"");
    }
    ParamList params = readParams(args);

    // Positions: "P" (x y z) or "Pw" (x y z w) per vertex.
    if (const Param* pz = params.find("Pz"))
        args.failAt(pz->loc.line, "\"Pz\" is not supported: give \"P\" with x y z for every vertex", false);
    const Param* P = params.find("P");
    const Param* Pw = params.find("Pw");
    if (P && Pw) args.failAt(Pw->loc.line, "give either \"P\" or \"Pw\", not both", false);
    if (!P && !Pw) args.fail("missing \"P\": give x y z for every vertex (or \"Pw\" with x y z w)");
    const Param& pos = P ? *P : *Pw;
    ParamType posType = P ? ParamType::Point : ParamType::HPoint;
    if (pos.type != posType || pos.arraySize != 1)
        args.failAt(pos.loc.line, "\"" + pos.name + "\" must be declared as " + (P ? "point" : "hpoint"), false);
    size_t perVertex = size_t(pos.componentsPerItem());
    if (args.name() == "Polygon") {
        if (pos.nums.size() % perVertex != 0)
            args.failAt(pos.loc.line,
                        "parameter '" + pos.name + "' has " + plural(pos.nums.size(), "number") +
                            ", which is not a whole number of vertices (" + std::to_string(perVertex) +
                            " numbers each)",
                        false);
        vertices = int(pos.nums.size() / perVertex);
        if (vertices < 3) args.fail("a polygon needs at least 3 vertices, got " + std::to_string(vertices));
        if (vertices > 4) {
            key->asMesh = true;  // cut into faces as a polygon mesh
            return false;
        }
    }
    checkCount(args, pos, size_t(vertices));
    for (const Param& p : params.params) {
        if (&p == &pos) continue;
        checkCount(args, p, itemsOnFace(p.cls, vertices));
    }

    std::vector<Vec3d> points(static_cast<size_t>(vertices));
    for (size_t i = 0; i < points.size(); ++i) {
        const double* v = &pos.nums[i * perVertex];
        if (Pw) {
            if (v[3] == 0) args.failAt(pos.loc.line, "\"Pw\" vertex " + std::to_string(i) + " has w = 0", false);
            points[i] = Vec3d(v[0] / v[3], v[1] / v[3], v[2] / v[3]);
        } else {
            points[i] = Vec3d(v[0], v[1], v[2]);
        }
    }

    // A concave quad would fold as a bilinear patch: it is cut into triangles instead.
    std::vector<std::array<int, 4>> faces;
    if (args.name() == "Polygon" && vertices == 4 && cutPolygon(points, {{0, 1, 2, 3}}, &faces) && faces.size() > 1) {
        key->asMesh = true;
        return false;
    }

    // Corner c takes vertex order[c]. A quad's vertices go around its edge (0 1 2 3), a patch's
    // corners row by row (0 1 / 2 3); a triangle repeats its last vertex as a collapsed edge.
    static const int patchOrder[4] = {0, 1, 2, 3};
    static const int quadOrder[4] = {0, 1, 3, 2};
    static const int triangleOrder[4] = {0, 1, 2, 2};
    const int* order = args.name() == "Patch" ? patchOrder : vertices == 4 ? quadOrder : triangleOrder;

    key->vertices = vertices;
    for (int c = 0; c < 4; ++c) key->P[size_t(c)] = points[size_t(order[c])];
    key->hasCs = false;
    if (const Param* cs = params.find("Cs")) {
        if (cs->type != ParamType::Color || cs->arraySize != 1)
            args.failAt(cs->loc.line, "\"Cs\" must be declared as a color", false);
        bool perVertexCs = itemsOnFace(cs->cls, vertices) > 1;
        key->hasCs = true;
        for (int c = 0; c < 4; ++c) {
            size_t i = perVertexCs ? size_t(order[c]) : 0;
            key->Cs[size_t(c)] =
                Color(float(cs->nums[3 * i]), float(cs->nums[3 * i + 1]), float(cs->nums[3 * i + 2]));
        }
    }
    for (const Param& p : params.params)
        if (p.name != "P" && p.name != "Pw" && p.name != "Cs")
            log_.warnOnce("geometry-param:" + p.name, p.loc,
                          "parameter '" + p.name + "' on " + args.name() + " is not supported yet: ignored");
    return true;
}

void RibParser::addPatch(const std::vector<double>& times, const std::vector<PatchKey>& keys,
                         const SourceLoc& loc) {
    BilinearPatchDesc patch;
    // Keys that are all equal are one static patch.
    bool moves = false;
    for (const PatchKey& k : keys) moves = moves || k.P != keys.front().P;
    patch.times = moves ? times : std::vector<double>{times.front()};
    for (size_t i = 0; i < (moves ? keys.size() : 1); ++i) patch.P.push_back(keys[i].P);
    for (const PatchKey& k : keys) {
        if (k.vertices != keys.front().vertices)
            throw InputError(loc, "the polygons in a motion block must have the same number of vertices (" +
                                      std::to_string(keys.front().vertices) + " and " +
                                      std::to_string(k.vertices) + ")");
        if (k.hasCs != keys.front().hasCs || k.Cs != keys.front().Cs)
            log_.warnOnce("motion:Cs", loc, "Cs does not change over motion keys: using the first key's");
    }
    patch.hasCs = keys.front().hasCs;
    patch.Cs = keys.front().Cs;
    patch.objectToWorld = ctm_;
    patch.attributes = attributes_;
    patch.loc = loc;
    scene_.patches.push_back(std::move(patch));
}

void RibParser::patchOrPolygon(RibArgs& args) {
    PatchKey key;
    if (readPatchKey(args, &key)) addPatch({0.0}, {key}, args.loc());
    else if (key.asMesh)
        geometry({0.0}, {args.request()},
                 args.name() == "Patch" ? "Patch \"bicubic\" \"P\" [48 numbers]" : "Polygon \"P\" [x y z ...]");
}

// Procedural "kind" [args] [xmin xmax ymin ymax zmin zmax]: a bound now, children when the
// bound is seen (procedural.h).
void RibParser::procedural(RibArgs& args) {
    ProceduralDesc p;
    const std::string kind = args.string("procedural kind");
    if (args.done()) args.fail("missing the argument array");
    const RibValue& a = args.take();
    std::vector<std::string> strings;
    if (a.isString()) strings = a.strings;
    else if (a.isStringArray()) strings = a.strings;
    else args.fail(a, "the arguments must be an array of strings, got " + describeValue(a));
    std::vector<double> b = args.numbers(6, "bound: xmin xmax ymin ymax zmin zmax");
    args.expectEnd();
    if (b[0] > b[1] || b[2] > b[3] || b[4] > b[5])
        args.fail("the bound must be xmin xmax ymin ymax zmin zmax with each min <= max");
    p.bound = Bounds3d({b[0], b[2], b[4]}, {b[1], b[3], b[5]});
    p.kind = kind;
    p.args = std::move(strings);
    if (args.loc().file) p.directory = std::filesystem::path(*args.loc().file).parent_path().string();
    p.objectToWorld = ctm_;
    p.attributes = attributes_;
    p.loc = args.loc();
    scene_.procedurals.push_back(std::move(p));
}

// An archive path: relative to the folder of the file that names it, else as given.
std::string RibParser::resolveArchive(const std::string& name, const SourceLoc& loc) const {
    namespace fs = std::filesystem;
    std::error_code ec;
    if (fs::path(name).is_relative() && loc.file) {
        fs::path beside = fs::path(*loc.file).parent_path() / name;
        if (fs::exists(beside, ec)) return beside.string();
    }
    return name;
}

// ReadArchive "file": the file's requests, here and now, under the current state.
void RibParser::readArchive(RibArgs& args) {
    const std::string name = args.string("archive file name");
    args.expectEnd();
    if (!sceneAccess().files) args.fail("reading other files is not allowed here");
    const std::string path = resolveArchive(name, args.loc());
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(args.loc(), "ReadArchive: cannot open '" + name + "': " + std::strerror(errno));
    std::ostringstream text;
    text << in.rdbuf();
    parseString(text.str(), path);
}

void RibParser::beginFragment(const MotionTransform& ctm, const AttributesPtr& attributes) {
    worldState_ = WorldState::InWorld;
    ctm_ = ctm;
    attributes_ = std::make_shared<Attributes>(attributes ? *attributes : Attributes());
    fragment_ = true;
}

void RibParser::finishFragment() {
    if (motion_) throw InputError(motion_->begin, "MotionBegin is never closed: missing MotionEnd");
    if (skipping_)
        throw InputError(skipping_->begin, skipping_->beginName + " is never closed: missing " + skipping_->endName);
    if (!blocks_.empty()) {
        const Block& open = blocks_.back();
        throw InputError(open.begin, std::string(open.kind == BlockKind::Attribute ? "AttributeBegin" : "TransformBegin") +
                                         " is never closed in the procedural's output");
    }
}

void RibParser::unsupportedGeometry(RibArgs& args) {
    log_.warnOnce("request:" + args.name(), args.loc(),
                  "unsupported request '" + args.name() + "' ignored (not supported yet)");
    args.skipRest();
}

// ---- Curved and polygon-mesh geometry ---------------------------------------------------------------
// PatchMesh and Patch "bicubic", SubdivisionMesh, the quadrics, and polygons beyond four vertices
// (Polygon, GeneralPolygon, PointsPolygons, PointsGeneralPolygons). Each reader takes one request
// (one motion key); geometry() checks that the keys of a motion block agree and adds the
// primitive to the scene.
namespace {

// How many items a parameter of each storage class has on one primitive.
struct ClassCounts {
    size_t uniform = 1, varying = 1, vertex = 1, faceVarying = 1;
    size_t of(ParamClass c) const {
        switch (c) {
        case ParamClass::Constant: return 1;
        case ParamClass::Uniform: return uniform;
        case ParamClass::Varying: return varying;
        case ParamClass::Vertex: return vertex;
        case ParamClass::FaceVarying: return faceVarying;
        }
        return 1;
    }
};

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

// Parameters other than positions and Cs: checked for size, then ignored with a warning.
void otherParams(const RibArgs& args, const ParamList& params, const ClassCounts& counts, Log& log) {
    for (const Param& p : params.params) {
        if (p.name == "P" || p.name == "Pw" || p.name == "Cs") continue;
        checkCount(args, p, counts.of(p.cls));
        log.warnOnce("geometry-param:" + p.name, p.loc,
                     "parameter '" + p.name + "' on " + args.name() + " is not supported yet: ignored");
    }
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

bool wrapMode(RibArgs& args, const char* what) {
    const RibValue* v = args.peek();
    std::string mode = args.string(what);
    if (mode != "periodic" && mode != "nonperiodic")
        args.fail(*v, std::string(what) + " must be \"periodic\" or \"nonperiodic\", got \"" + mode + "\"");
    return mode == "periodic";
}

}  // namespace

void RibParser::basis(RibArgs& args) {
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
    Attributes& a = mutableAttributes();
    a.uBasis = b[0];
    a.vBasis = b[1];
}

void RibParser::curvedGeometry(RibArgs& args) {
    geometry({0.0}, {args.request()}, args.usage());
    args.skipRest();
}

bool RibParser::readPatchMeshKey(RibArgs& args, PatchMeshDesc* d) {
    const RibValue* typeValue = args.peek();
    const std::string type = args.string("type");
    if (args.name() == "Patch") {
        d->nu = d->nv = 4;
    } else {
        if (type != "bicubic" && type != "bilinear")
            args.fail(*typeValue, "the patch type must be \"bilinear\" or \"bicubic\", got \"" + type + "\"");
        const RibValue* nuValue = args.peek();
        d->nu = args.integer("nu");
        d->uPeriodic = wrapMode(args, "uwrap");
        const RibValue* nvValue = args.peek();
        d->nv = args.integer("nv");
        d->vPeriodic = wrapMode(args, "vwrap");
        d->bicubic = type == "bicubic";
        d->uBasis = attributes_->uBasis;
        d->vBasis = attributes_->vBasis;
        // The control points must make whole patches (RenderMan's rule).
        auto check = [&](const RibValue* at, int n, bool periodic, int step, const char* axis) {
            const std::string name(axis);
            if (!d->bicubic) {
                if (n < 2) args.fail(*at, "a bilinear patch mesh needs at least 2 points along " + name);
                return;
            }
            if (periodic ? n < 1 || n % step != 0 : n < 4 || (n - 4) % step != 0)
                args.fail(*at, std::to_string(n) + " points along " + name + " do not make whole " +
                                   (periodic ? "periodic" : "nonperiodic") + " patches with a basis step of " +
                                   std::to_string(step) +
                                   (periodic ? " (the count must be a multiple of the step)"
                                             : " (the count must be 4 plus a multiple of the step)"));
        };
        check(nuValue, d->nu, d->uPeriodic, d->uBasis.step, "u");
        check(nvValue, d->nv, d->vPeriodic, d->vBasis.step, "v");
    }
    if (args.name() == "Patch") {
        d->bicubic = true;
        d->uBasis = attributes_->uBasis;
        d->vBasis = attributes_->vBasis;
    }
    ParamList params = readParams(args);
    const Param& pos = positionParam(args, params);
    checkCount(args, pos, size_t(d->nu) * size_t(d->nv));
    ClassCounts counts;
    counts.uniform = size_t(d->uPatches()) * size_t(d->vPatches());
    counts.varying = counts.faceVarying = size_t(d->uVarying()) * size_t(d->vVarying());
    counts.vertex = size_t(d->nu) * size_t(d->nv);
    d->P = {pointsOf(args, pos)};
    d->Cs = readColors(args, params, counts);
    otherParams(args, params, counts, log_);
    return true;
}

bool RibParser::readSubdivisionKey(RibArgs& args, SubdivisionMeshDesc* d) {
    const RibValue* schemeValue = args.peek();
    const std::string scheme = args.string("scheme");
    if (scheme != "catmull-clark") {
        if (scheme == "loop" || scheme == "bilinear") {
            log_.warnOnce("subdivision:" + scheme, args.loc(),
                          "SubdivisionMesh \"" + scheme + "\" is not supported (only \"catmull-clark\"): skipped");
            args.skipRest();
            return false;
        }
        args.fail(*schemeValue, "unknown subdivision scheme \"" + scheme + "\" (use \"catmull-clark\")");
    }
    d->faceSizes = intArray(args, "nvertices", 3);
    d->faceVertices = intArray(args, "vertices", 0);
    if (d->faceVertices.size() != sum(d->faceSizes))
        args.fail("vertices has " + indexCount(d->faceVertices.size()) + " but the faces in nvertices need " +
                  std::to_string(sum(d->faceSizes)));
    d->vertexCount = 0;
    for (int v : d->faceVertices) d->vertexCount = std::max(d->vertexCount, v + 1);
    // A face that names a vertex twice has no sensible limit surface.
    std::set<std::pair<int, int>> edges;
    for (size_t f = 0, at = 0; f < d->faceSizes.size(); at += size_t(d->faceSizes[f]), ++f) {
        const int n = d->faceSizes[f];
        for (int i = 0; i < n; ++i) {
            const int a = d->faceVertices[at + size_t(i)], b = d->faceVertices[at + size_t((i + 1) % n)];
            for (int j = i + 1; j < n; ++j)
                if (d->faceVertices[at + size_t(j)] == a)
                    args.fail("face " + std::to_string(f) + " uses vertex " + std::to_string(a) + " twice");
            edges.insert({std::min(a, b), std::max(a, b)});
        }
    }

    // Tags, if any: [tags] [nargs] [intargs] [floatargs] (and [stringargs] with 3 counts per tag).
    if (!args.done() && args.peek()->kind == RibValue::Kind::Array) {
        const std::vector<std::string> tags = takeArray(args, "tags", true).strings;
        const std::vector<int> nargs = intArray(args, "nargs", 0);
        const std::vector<double> ints = takeArray(args, "intargs", false).nums;
        const std::vector<double> floats = takeArray(args, "floatargs", false).nums;
        const size_t per = tags.empty() ? 2 : nargs.size() / tags.size();
        if ((per != 2 && per != 3) || nargs.size() != per * tags.size())
            args.fail("nargs must hold 2 (or 3) counts per tag: " + plural(tags.size(), "tag") + " and " +
                      plural(nargs.size(), "count"));
        if (per == 3) takeArray(args, "stringargs", true);
        size_t ii = 0, fi = 0;
        for (size_t t = 0; t < tags.size(); ++t) {
            const size_t ni = size_t(nargs[t * per]), nf = size_t(nargs[t * per + 1]);
            if (ii + ni > ints.size() || fi + nf > floats.size())
                args.fail("the tag \"" + tags[t] + "\" (tag " + std::to_string(t) +
                          ") asks for more intargs or floatargs than given");
            std::vector<int> iv;
            for (size_t k = 0; k < ni; ++k) {
                const double x = ints[ii + k];
                if (!isWholeInt(x)) args.fail("intargs must be whole numbers, got " + formatNumber(x));
                iv.push_back(int(x));
            }
            const std::vector<double> fv(floats.begin() + long(fi), floats.begin() + long(fi + nf));
            ii += ni, fi += nf;
            const std::string& tag = tags[t];
            auto fail = [&](const std::string& what) { args.fail("tag \"" + tag + "\": " + what); };
            auto checkVertex = [&](int v) {
                if (v < 0 || v >= d->vertexCount)
                    fail("vertex " + std::to_string(v) + " is not in the mesh (vertices 0 to " +
                         std::to_string(d->vertexCount - 1) + ")");
            };
            for (double s : fv)
                if (!(s >= 0)) fail("sharpness must not be negative, got " + formatNumber(s));
            if (tag == "crease") {
                if (iv.size() < 2 || fv.size() != 1)
                    fail("give a chain of at least 2 vertices in intargs and one sharpness in floatargs");
                for (size_t k = 0; k + 1 < iv.size(); ++k) {
                    checkVertex(iv[k]);
                    checkVertex(iv[k + 1]);
                    if (!edges.count({std::min(iv[k], iv[k + 1]), std::max(iv[k], iv[k + 1])}))
                        fail("vertices " + std::to_string(iv[k]) + " and " + std::to_string(iv[k + 1]) +
                             " are not joined by an edge of the mesh");
                    d->creaseEdges.push_back(iv[k]);
                    d->creaseEdges.push_back(iv[k + 1]);
                    d->creaseSharpness.push_back(float(fv[0]));
                }
            } else if (tag == "corner") {
                if (iv.empty() || (fv.size() != 1 && fv.size() != iv.size()))
                    fail("give the vertices in intargs and one sharpness (or one per vertex) in floatargs");
                for (size_t k = 0; k < iv.size(); ++k) {
                    checkVertex(iv[k]);
                    d->corners.push_back(iv[k]);
                    d->cornerSharpness.push_back(float(fv[fv.size() == 1 ? 0 : k]));
                }
            } else if (tag == "interpolateboundary") {
                if (iv.size() > 1 || !fv.empty()) fail("takes at most one integer (0, 1 or 2)");
                const int mode = iv.empty() ? 1 : iv[0];
                if (mode < 0 || mode > 2) fail("the mode must be 0, 1 or 2, got " + std::to_string(mode));
                d->interpolateBoundary = mode;
            } else if (tag == "hole") {
                for (int f : iv) {
                    if (f < 0 || size_t(f) >= d->faceSizes.size())
                        fail("face " + std::to_string(f) + " is not in the mesh (" +
                             plural(d->faceSizes.size(), "face") + ")");
                    d->holes.push_back(f);
                }
            } else {
                log_.warnOnce("subdivision-tag:" + tag, args.loc(),
                              "SubdivisionMesh tag \"" + tag + "\" is not supported: ignored");
            }
        }
    }
    ParamList params = readParams(args);
    const Param& pos = positionParam(args, params);
    checkCount(args, pos, size_t(d->vertexCount));
    ClassCounts counts;
    counts.uniform = d->faceSizes.size();
    counts.varying = counts.vertex = size_t(d->vertexCount);
    counts.faceVarying = d->faceVertices.size();
    d->P = {pointsOf(args, pos)};
    d->Cs = readColors(args, params, counts);
    if (d->Cs.given() && d->Cs.cls == ParamClass::FaceVarying) {
        log_.warnOnce("subdivision:facevarying", args.loc(),
                      "facevarying \"Cs\" on SubdivisionMesh is not supported: using the Color attribute");
        d->Cs = {};
    }
    otherParams(args, params, counts, log_);
    return true;
}

bool RibParser::readQuadricKey(RibArgs& args, QuadricDesc* d) {
    struct Kind {
        QuadricKind kind;
        size_t count;
        const char* what;
    };
    static const std::map<std::string, Kind> kinds = {
        {"Sphere", {QuadricKind::Sphere, 4, "radius zmin zmax thetamax"}},
        {"Cylinder", {QuadricKind::Cylinder, 4, "radius zmin zmax thetamax"}},
        {"Cone", {QuadricKind::Cone, 3, "height radius thetamax"}},
        {"Disk", {QuadricKind::Disk, 3, "height radius thetamax"}},
        {"Paraboloid", {QuadricKind::Paraboloid, 4, "rmax zmin zmax thetamax"}},
        {"Hyperboloid", {QuadricKind::Hyperboloid, 7, "x1 y1 z1 x2 y2 z2 thetamax"}},
        {"Torus", {QuadricKind::Torus, 5, "majorradius minorradius phimin phimax thetamax"}}};
    const Kind& k = kinds.at(args.name());
    std::vector<double> v = args.numbers(k.count, k.what);
    // thetamax is the last argument; RenderMan clamps it to a full turn.
    v.back() = std::max(-360.0, std::min(360.0, v.back()));
    if (k.kind == QuadricKind::Paraboloid && !(v[2] > 0 && v[1] >= 0 && v[1] <= v[2]))
        args.fail("needs 0 <= zmin <= zmax and zmax > 0, got zmin " + formatNumber(v[1]) + " and zmax " +
                  formatNumber(v[2]));
    d->kind = k.kind;
    std::array<double, 7> params{};
    std::copy(v.begin(), v.end(), params.begin());
    d->params = {params};
    ParamList list = readParams(args);
    ClassCounts counts;
    counts.varying = counts.vertex = counts.faceVarying = 4;
    d->Cs = readColors(args, list, counts);
    otherParams(args, list, counts, log_);
    return true;
}

bool RibParser::readPolygonsKey(RibArgs& args, std::vector<Vec3d>* points,
                                std::vector<std::vector<std::vector<int>>>* polygons, ColorPrimvar* Cs) {
    const std::string& name = args.name();
    std::vector<int> loopsPerPolygon, loopSizes, indices;
    if (name == "GeneralPolygon") {
        loopSizes = intArray(args, "nvertices", 3);
        loopsPerPolygon = {int(loopSizes.size())};
    } else if (name == "PointsPolygons") {
        loopSizes = intArray(args, "nvertices", 3);
        loopsPerPolygon.assign(loopSizes.size(), 1);
        indices = intArray(args, "vertices", 0);
    } else if (name == "PointsGeneralPolygons") {
        loopsPerPolygon = intArray(args, "nloops", 1);
        loopSizes = intArray(args, "nvertices", 3);
        if (loopSizes.size() != sum(loopsPerPolygon))
            args.fail("nvertices has " + plural(loopSizes.size(), "loop") + " but nloops asks for " +
                      std::to_string(sum(loopsPerPolygon)));
        indices = intArray(args, "vertices", 0);
    }
    if (!indices.empty() || name == "PointsPolygons" || name == "PointsGeneralPolygons")
        if (indices.size() != sum(loopSizes))
            args.fail("vertices has " + indexCount(indices.size()) + " but nvertices asks for " +
                      std::to_string(sum(loopSizes)));
    ParamList params = readParams(args);
    const Param& pos = positionParam(args, params);
    const size_t per = size_t(pos.componentsPerItem());
    size_t npoints = 0;
    if (name == "Polygon") {
        if (pos.nums.size() % per != 0)
            args.failAt(pos.loc.line,
                        "parameter '" + pos.name + "' has " + plural(pos.nums.size(), "number") +
                            ", which is not a whole number of vertices (" + std::to_string(per) + " numbers each)",
                        false);
        npoints = pos.nums.size() / per;
        loopSizes = {int(npoints)};
        loopsPerPolygon = {1};
    } else if (name == "GeneralPolygon") {
        npoints = sum(loopSizes);
    } else {
        for (int i : indices) npoints = std::max(npoints, size_t(i) + 1);
    }
    checkCount(args, pos, npoints);
    *points = pointsOf(args, pos);
    // Loops as indices into the points.
    polygons->clear();
    for (size_t p = 0, loop = 0, at = 0; p < loopsPerPolygon.size(); ++p) {
        std::vector<std::vector<int>> loops;
        for (int l = 0; l < loopsPerPolygon[p]; ++l, ++loop) {
            std::vector<int> ring;
            for (int k = 0; k < loopSizes[loop]; ++k, ++at) ring.push_back(indices.empty() ? int(at) : indices[at]);
            loops.push_back(std::move(ring));
        }
        polygons->push_back(std::move(loops));
    }
    ClassCounts counts;
    counts.uniform = polygons->size();
    counts.varying = counts.vertex = npoints;
    counts.faceVarying = sum(loopSizes);
    *Cs = readColors(args, params, counts);
    otherParams(args, params, counts, log_);
    return true;
}

// Reads every key of a curved or polygon-mesh primitive, checks that they describe the same
// shape, and adds it. Keys whose positions are all equal make a static primitive.
void RibParser::geometry(const std::vector<double>& times, const std::vector<RibRequest>& requests,
                         const char* usage) {
    const std::string& name = requests.front().name;
    const SourceLoc& loc = requests.front().loc;
    auto differ = [&](const std::string& what) {
        throw InputError(loc, "the " + name + " requests of a motion block must have the same " + what);
    };
    auto place = [&](PrimitiveDesc& d, std::vector<double> t) {
        d.times = std::move(t);
        d.objectToWorld = ctm_;
        d.attributes = attributes_;
        d.loc = loc;
    };
    auto colorsDiffer = [&](const ColorPrimvar& a, const ColorPrimvar& b) {
        if (a.cls != b.cls || a.values != b.values)
            log_.warnOnce("motion:Cs", loc, "Cs does not change over motion keys: using the first key's");
    };
    // Reads every key with `read` and checks that it has the first key's shape (what may not
    // change is named by `what`); false when the primitive is skipped.
    auto readKeys = [&](auto& keys, auto read, auto sameShape, const char* what) {
        for (size_t i = 0; i < keys.size(); ++i) {
            RibArgs a(requests[i], usage);
            if (!(this->*read)(a, &keys[i])) return false;
            if (!sameShape(keys[i], keys[0])) differ(what);
            colorsDiffer(keys[i].Cs, keys[0].Cs);
        }
        return true;
    };
    // The first key's primitive with the positions of every key (`positions` picks the member
    // that moves), or of the first alone when they are all equal.
    auto mergeKeys = [&](auto& keys, auto positions) {
        auto d = keys[0];
        bool moves = false;
        for (size_t i = 1; i < keys.size(); ++i) moves = moves || positions(keys[i]) != positions(keys[0]);
        place(d, moves ? times : std::vector<double>{times.front()});
        positions(d).clear();
        for (size_t i = 0; i < d.times.size(); ++i) positions(d).push_back(positions(keys[i])[0]);
        return d;
    };

    if (name == "Patch" || name == "PatchMesh") {
        std::vector<PatchMeshDesc> keys(requests.size());
        auto same = [](const PatchMeshDesc& k, const PatchMeshDesc& f) {
            return k.bicubic == f.bicubic && k.nu == f.nu && k.nv == f.nv && k.uPeriodic == f.uPeriodic &&
                   k.vPeriodic == f.vPeriodic;
        };
        if (!readKeys(keys, &RibParser::readPatchMeshKey, same, "type, size and wrap")) return;
        scene_.patchMeshes.push_back(mergeKeys(keys, [](PatchMeshDesc& d) -> auto& { return d.P; }));
    } else if (name == "SubdivisionMesh") {
        std::vector<SubdivisionMeshDesc> keys(requests.size());
        auto same = [](const SubdivisionMeshDesc& k, const SubdivisionMeshDesc& f) {
            return k.faceSizes == f.faceSizes && k.faceVertices == f.faceVertices && k.creaseEdges == f.creaseEdges &&
                   k.creaseSharpness == f.creaseSharpness && k.corners == f.corners &&
                   k.cornerSharpness == f.cornerSharpness && k.holes == f.holes &&
                   k.interpolateBoundary == f.interpolateBoundary;
        };
        if (!readKeys(keys, &RibParser::readSubdivisionKey, same, "topology and tags (only \"P\" may change)")) return;
        scene_.subdivisionMeshes.push_back(mergeKeys(keys, [](SubdivisionMeshDesc& d) -> auto& { return d.P; }));
    } else if (name == "Polygon" || name == "GeneralPolygon" || name == "PointsPolygons" ||
               name == "PointsGeneralPolygons") {
        std::vector<std::vector<Vec3d>> P(requests.size());
        std::vector<std::vector<std::vector<int>>> polygons, first;
        ColorPrimvar Cs, firstCs;
        for (size_t i = 0; i < requests.size(); ++i) {
            RibArgs a(requests[i], usage);
            readPolygonsKey(a, &P[i], i == 0 ? &first : &polygons, i == 0 ? &firstCs : &Cs);
            if (i > 0 && polygons != first) {
                if (name == "Polygon")
                    throw InputError(loc, "the polygons in a motion block must have the same number of vertices (" +
                                              std::to_string(first[0][0].size()) + " and " +
                                              std::to_string(polygons[0][0].size()) + ")");
                differ("polygons and vertex indices (only \"P\" may change)");
            }
            if (i > 0) colorsDiffer(Cs, firstCs);
        }
        PolygonMeshDesc d;
        bool moves = false;
        for (size_t i = 1; i < P.size(); ++i) moves = moves || P[i] != P[0];
        place(d, moves ? times : std::vector<double>{times.front()});
        for (size_t i = 0; i < d.times.size(); ++i) d.P.push_back(P[i]);
        // Cut every polygon once (at the first key) into triangles and convex quads.
        size_t faceVertex = 0;
        for (size_t p = 0; p < first.size(); ++p) {
            std::vector<std::array<int, 4>> faces;
            if (!cutPolygon(P[0], first[p], &faces)) {
                log_.warnOnce("polygon:degenerate", loc,
                              name + ": a polygon has no area (its points are on one line): skipped");
            }
            // Facevarying colours: the polygon's own corners, by point.
            std::map<int, size_t> cornerOf;
            for (const std::vector<int>& loop : first[p])
                for (int v : loop) cornerOf.emplace(v, faceVertex++);
            for (const std::array<int, 4>& f : faces) {
                d.faces.push_back(f);
                if (!firstCs.given()) continue;
                std::array<Color, 4> c;
                for (size_t k = 0; k < 4; ++k) {
                    const int v = f[k];
                    switch (firstCs.cls) {
                    case ParamClass::Constant: c[k] = firstCs.values[0]; break;
                    case ParamClass::Uniform: c[k] = firstCs.values[p]; break;
                    case ParamClass::FaceVarying: c[k] = firstCs.values[cornerOf[v]]; break;
                    default: c[k] = firstCs.values[size_t(v)];
                    }
                }
                d.faceCs.push_back(c);
            }
        }
        if (!d.faces.empty()) scene_.polygonMeshes.push_back(std::move(d));
    } else {
        std::vector<QuadricDesc> keys(requests.size());
        readKeys(keys, &RibParser::readQuadricKey, [](const QuadricDesc&, const QuadricDesc&) { return true; }, "");
        scene_.quadrics.push_back(mergeKeys(keys, [](QuadricDesc& d) -> auto& { return d.params; }));
    }
}

// ---- End of input -------------------------------------------------------------------------------
void RibParser::finish() {
    if (motion_) throw InputError(motion_->begin, "MotionBegin is never closed: missing MotionEnd");
    if (skipping_)
        throw InputError(skipping_->begin,
                         skipping_->beginName + " is never closed: missing " + skipping_->endName);
    if (!blocks_.empty()) {
        const Block& open = blocks_.back();
        if (open.kind == BlockKind::World)
            throw InputError(lastLoc_, "missing WorldEnd at the end of the file (WorldBegin at line " +
                                           std::to_string(open.begin.line) + ")");
        throw InputError(open.begin, std::string(beginName(int(open.kind))) + " is never closed: missing " +
                                         endName(int(open.kind)) + " before the end of the file");
    }
    if (worldState_ == WorldState::BeforeWorld)
        throw InputError(lastLoc_,
                         "no WorldBegin: a scene needs WorldBegin ... WorldEnd around its lights and "
                         "geometry");
}

// ---- Public entry points (streyes/rib.h) ------------------------------------------------------------
Scene parseRibFile(const std::string& path, Log& log) {
    Scene scene;
    scene.sourceName = path;
    RibParser parser(scene, log);
    parser.parseFile(path);
    parser.finish();
    return scene;
}

Scene parseRibString(const std::string& text, const std::string& sourceName, Log& log) {
    Scene scene;
    scene.sourceName = sourceName;
    RibParser parser(scene, log);
    parser.parseString(text, sourceName);
    parser.finish();
    return scene;
}

Scene parseRibFragment(const std::string& text, const std::string& sourceName, const MotionTransform& ctm,
                       const AttributesPtr& attributes, Log& log) {
    Scene scene;
    RibParser parser(scene, log);
    parser.beginFragment(ctm, attributes);
    parser.parseString(text, sourceName);
    parser.finishFragment();
    return scene;
}

namespace {
std::atomic<bool> programsAllowed{true}, filesAllowed{true};
}  // namespace

void setSceneAccess(SceneAccess access) {
    programsAllowed = access.programs;
    filesAllowed = access.files;
}

SceneAccess sceneAccess() { return {programsAllowed.load(), filesAllowed.load()}; }

}  // namespace streyes
