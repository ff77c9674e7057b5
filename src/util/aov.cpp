#include "util/aov.h"

#include <algorithm>
#include <cctype>

namespace streyes {

namespace {

// Channel names as compositors read them: a layer name and the component (OpenEXR's
// "layer.channel" convention, as pbrt-v4 writes N.X N.Y N.Z and P.X P.Y P.Z).
const AovVariable kVariables[] = {
    {AovVar::N, "N", "normal", 3, {"N.X", "N.Y", "N.Z"}},
    {AovVar::P, "P", "point", 3, {"P.X", "P.Y", "P.Z"}},
    {AovVar::s, "s", "float", 1, {"s", nullptr, nullptr}},
    {AovVar::t, "t", "float", 1, {"t", nullptr, nullptr}},
    {AovVar::Ci, "Ci", "color", 3, {"Ci.R", "Ci.G", "Ci.B"}},
    {AovVar::Oi, "Oi", "color", 3, {"Oi.R", "Oi.G", "Oi.B"}},
    {AovVar::Cs, "Cs", "color", 3, {"Cs.R", "Cs.G", "Cs.B"}},
    {AovVar::Motion, "motion", "vector", 2, {"motion.X", "motion.Y", nullptr}},
};

bool isColourOutput(const std::string& o) { return o == "rgb" || o == "rgba" || o == "rgbaz" || o == "a" || o == "z"; }

}  // namespace

const AovVariable* findAovVariable(const std::string& name) {
    for (const AovVariable& v : kVariables)
        if (name == v.name) return &v;
    return nullptr;
}

std::string aovVariableList() {
    std::string s;
    for (const AovVariable& v : kVariables) s += (s.empty() ? "" : ", ") + std::string(v.name);
    return s;
}

int aovTypeWidth(const std::string& type) {
    if (type == "float") return 1;
    if (type == "color" || type == "point" || type == "vector" || type == "normal") return 3;
    return 0;
}

namespace {
bool isIdentifier(const std::string& s) {
    if (s.empty() || !(std::isalpha(static_cast<unsigned char>(s[0])) || s[0] == '_')) return false;
    for (char c : s)
        if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_')) return false;
    return true;
}
}  // namespace

std::vector<std::string> modeOutputs(const std::string& mode, std::string* error, const std::vector<std::string>* declared) {
    std::vector<std::string> out;
    size_t a = 0;
    for (;;) {
        const size_t b = std::min(mode.find(',', a), mode.size());
        std::string o = mode.substr(a, b - a);
        // Spaces around the commas are harmless: "rgba, N".
        while (!o.empty() && o.front() == ' ') o.erase(0, 1);
        while (!o.empty() && o.back() == ' ') o.pop_back();
        if (o == "Z") o = "z";
        if (o == "A") o = "a";
        const bool shaderOutput = !isColourOutput(o) && !findAovVariable(o) && isIdentifier(o) &&
                                  (!declared || std::find(declared->begin(), declared->end(), o) != declared->end());
        if (o.empty() || (!isColourOutput(o) && !findAovVariable(o) && !shaderOutput)) {
            if (error)
                *error = o.empty() ? "an empty output"
                                   : "unknown output variable \"" + o + "\" (known: rgb, rgba, rgbaz, a, z, " +
                                         aovVariableList() + ", and shader outputs declared with DisplayChannel)";
            return {};
        }
        out.push_back(o);
        if (b == mode.size()) break;
        a = b + 1;
    }
    return out;
}

std::vector<std::string> modeChannels(const std::string& mode) {
    std::vector<std::string> ch;
    auto add = [&](const char* c) {
        for (const std::string& have : ch)
            if (have == c) return;  // "rgba,a": A once
        ch.push_back(c);
    };
    for (const std::string& o : modeOutputs(mode, nullptr)) {
        if (o == "rgb" || o == "rgba" || o == "rgbaz") {
            add("R"), add("G"), add("B");
            if (o != "rgb") add("A");
            if (o == "rgbaz") add("Z");
        } else if (o == "a") {
            add("A");
        } else if (o == "z") {
            add("Z");
        } else if (const AovVariable* v = findAovVariable(o)) {
            for (int c = 0; c < v->width; ++c) add(v->channels[c]);
        }
    }
    return ch;
}

std::vector<std::string> modeVariables(const std::string& mode) {
    std::vector<std::string> vars;
    for (const std::string& o : modeOutputs(mode, nullptr))
        if (!isColourOutput(o) && std::find(vars.begin(), vars.end(), o) == vars.end()) vars.push_back(o);
    return vars;
}

AovLayout::AovLayout(const std::vector<std::string>& names) {
    for (const std::string& n : names) {
        AovEntry e;
        const size_t space = n.rfind(' ');
        if (space == std::string::npos) {
            const AovVariable* v = findAovVariable(n);
            if (!v) continue;
            e.var = v->var;
            e.name = v->name;
            e.width = v->width;
            for (int c = 0; c < v->width; ++c) e.channels.push_back(v->channels[c]);
        } else {
            const std::string type = n.substr(0, space);
            e.var = AovVar::Shader;
            e.name = n.substr(space + 1);
            e.width = aovTypeWidth(type);
            if (e.width == 0) continue;
            if (e.width == 1) e.channels = {e.name};
            else if (type == "color") e.channels = {e.name + ".R", e.name + ".G", e.name + ".B"};
            else e.channels = {e.name + ".X", e.name + ".Y", e.name + ".Z"};
            shaderOutputs = true;
        }
        bool have = false;
        for (const AovEntry& o : vars) have = have || o.name == e.name;
        if (have) continue;
        offset.push_back(count);
        count += e.width;
        vars.push_back(std::move(e));
    }
}

int AovLayout::offsetOf(AovVar v) const {
    for (size_t i = 0; i < vars.size(); ++i)
        if (vars[i].var == v) return offset[i];
    return -1;
}

std::vector<std::string> AovLayout::channelNames() const {
    std::vector<std::string> n;
    for (const AovEntry& v : vars) n.insert(n.end(), v.channels.begin(), v.channels.end());
    return n;
}

}  // namespace streyes
