// Declarations and parameter lists: Declare, the predeclared names, and reading ("name" value)
// pairs into a typed ParamList.
#include "scene/rib_params.h"

#include <algorithm>
#include <cstdlib>
#include <unordered_map>

#include "scene/rib_requests.h"

namespace streyes {

// ---- Declarations -------------------------------------------------------------------------------
// "[class] type[n] name". The array size may also be written apart ("float [2] st").
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
        {"matrix", ParamType::Matrix},
        // PRMan's "mpoint" (a Blobby leaf's reference frame, "vertex mpoint Pref") is a matrix.
        {"mpoint", ParamType::Matrix}};
    // clang-format on

    RibParamDecl d;
    size_t i = 0;
    if (i < words.size() && classes.count(words[i])) d.cls = classes.at(words[i++]);
    if (i >= words.size())
        return "missing the type (float, integer, string, point, vector, normal, color, hpoint or matrix)";
    auto type = types.find(words[i]);
    if (type == types.end())
        return "unknown type '" + words[i] +
               "' (types: float, integer, string, point, vector, normal, color, hpoint, matrix, mpoint; "
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

std::map<std::string, RibParamDecl> predeclaredParams() {
    using C = ParamClass;
    using T = ParamType;
    std::map<std::string, RibParamDecl> d;
    auto declare = [&d](const char* name, C cls, T type, int arraySize = 1) {
        d[name] = RibParamDecl{cls, type, arraySize};
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
    declare("width", C::Varying, T::Float);        // Curves, Points
    declare("constantwidth", C::Constant, T::Float);
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
    // Option "searchpath" and Option "shading".
    for (const char* f : {"shader", "texture", "archive", "procedural", "builtin", "coordinatesystem"})
        declare(f, C::Uniform, T::String);
    declare("sphere", C::Uniform, T::Float);  // Attribute "displacementbound"
    // Option "limits", Hider "hidden".
    declare("bucketsize", C::Uniform, T::Integer, 2);
    declare("gridsize", C::Uniform, T::Integer);
    declare("jitter", C::Uniform, T::Integer);
    declare("depthfilter", C::Uniform, T::String);
    // Option "shadow" (bias1, bias0: PRMan's and Aqsis's range; streyes takes one bias).
    for (const char* f : {"bias", "bias0", "bias1"}) declare(f, C::Uniform, T::Float);
    return d;
}

namespace {

void declare(RibParser& reader, RibArgs& args) {
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
    reader.state().declarations[name] = decl;
}

}  // namespace

void addParamRequests(RibRequestTable& table) {
    table.add("Declare", {declare, "Declare \"name\" \"class type\""});
}

// ---- Parameter lists ----------------------------------------------------------------------------
// ("name" value) pairs. The name is a declared name or an inline declaration; the value is a
// number, a string or an array, and must fit the declared type. How many values a use needs
// (one color, four vertex points) is checked where the parameter is used.
ParamList RibParser::readParams(RibArgs& args, bool shaderParams) const {
    ParamList list;
    while (!args.done()) {
        const RibValue& nameValue = args.take();
        if (!nameValue.isString())
            args.failAt(nameValue.line, "expected a parameter name (a string), got " + describeValue(nameValue),
                        true);
        if (args.done())
            args.failAt(nameValue.line, "parameter \"" + nameValue.strings[0] + "\" has no value", false);
        Param p = makeParam(args, nameValue, args.take(), shaderParams);
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

Param RibParser::makeParam(RibArgs& args, const RibValue& nameValue, const RibValue& value, bool shaderParam) const {
    const std::string& spelled = nameValue.strings[0];
    auto fail = [&](const std::string& what) { args.failAt(nameValue.line, what, false); };

    Param p;
    p.loc = args.locAt(nameValue.line);
    RibParamDecl decl;
    if (spelled.find_first_of(" \t\n[") != std::string::npos) {
        std::string error = parseRibDeclaration(spelled, true, &decl, &p.name);
        if (!error.empty()) fail("invalid inline declaration \"" + spelled + "\": " + error);
    } else {
        auto found = state_.declarations.find(spelled);
        if (found == state_.declarations.end() && shaderParam && (value.isString() || value.isStringArray() ||
                                                                  value.isNumber() || value.isNumericArray())) {
            // A shader's parameter: its declaration in the shader gives the type (as RenderMan does).
            p.name = spelled;
            p.declared = false;
            p.cls = ParamClass::Uniform;
            p.type = value.isString() || value.isStringArray() ? ParamType::String : ParamType::Float;
            p.strings = value.strings;
            p.nums = value.nums;
            if (p.nums.empty() && p.strings.empty())
                fail("parameter '" + p.name + "' has an empty array: give it a value");
            return p;
        }
        if (found == state_.declarations.end()) {
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
    // An empty array is a count of 0 items: right for the per-face and per-vertex classes of an
    // empty primitive (a procedural's PointsPolygons with no faces), checked where it is used.
    if (p.nums.empty() && p.strings.empty() && p.cls == ParamClass::Constant)
        fail("parameter '" + p.name + "' has an empty array: give it a value");
    return p;
}

void RibParser::warnUnusedParams(const ParamList& params, const std::vector<std::string>& known,
                                 const std::string& owner) {
    for (const Param& p : params.params)
        if (std::find(known.begin(), known.end(), p.name) == known.end())
            log_.lenient("param:" + owner + ":" + p.name, p.loc,
                          owner + " has no parameter '" + p.name + "': ignored");
}

}  // namespace streyes
