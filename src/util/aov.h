// Arbitrary output variables (AOVs): what a Display mode may name beside colour, and the EXR
// channels each is written as.
//
// A mode is a comma-separated list of outputs: "rgb", "rgba", "rgbaz" (colour, as always), "a"
// (alpha), "z" (depth), the variables N, P (camera space), s, t, Ci, Oi and motion (raster
// motion, pixels per frame), and output parameters of surface shaders declared with
// DisplayChannel ("color diffuse"). The variables are carried per sample from shading to the film;
// z and a come from the samples' own depth and coverage.
#pragma once

#include <string>
#include <vector>

namespace streyes {

enum class AovVar { N, P, s, t, Ci, Oi, Cs, Motion, Shader };

struct AovVariable {
    AovVar var;
    const char* name;      // as a Display mode names it
    const char* type;      // as DisplayChannel declares it ("normal", "point", "float", "color", "vector")
    int width;             // floats per sample
    const char* channels[3];  // EXR channel names
};

// The built-in variable a mode or DisplayChannel names, or null.
const AovVariable* findAovVariable(const std::string& name);
// "N, P, s, t, Ci, Oi, motion": for messages.
std::string aovVariableList();
// Floats of a shader output of Shading Language type `type` (float 1; color, point, vector,
// normal 3), or 0 for a type that cannot be written.
int aovTypeWidth(const std::string& type);

// The outputs of a mode, split at commas. Empty with *error set when one is not known (or the
// mode is empty). `declared`: the shader outputs DisplayChannel declared so far; null accepts any
// name as a shader output (a file writer, which has the frame's channels to check against).
std::vector<std::string> modeOutputs(const std::string& mode, std::string* error,
                                     const std::vector<std::string>* declared = nullptr);
// The channels of the colour and built-in outputs of a mode, in order: "rgba,N" -> R G B A N.X
// N.Y N.Z. A shader output's channels are the frame's channels of its name (image_io.cpp).
std::vector<std::string> modeChannels(const std::string& mode);
// The variables (built in, or shader outputs) a mode needs carried per sample, in order.
std::vector<std::string> modeVariables(const std::string& mode);

// One variable of a layout.
struct AovEntry {
    AovVar var;
    std::string name;
    int width = 0;
    std::vector<std::string> channels;
};

// The variables a render carries, laid out one after another per sample. Names are built-in
// variables, or "type name" for a shader output ("color diffuse" -> diffuse.R diffuse.G
// diffuse.B; a float is one channel named as the variable, a point, vector or normal .X .Y .Z).
struct AovLayout {
    std::vector<AovEntry> vars;
    std::vector<int> offset;  // of each variable, in floats
    int count = 0;            // floats per sample
    bool shaderOutputs = false;
    explicit AovLayout(const std::vector<std::string>& names = {});
    // The offset of a built-in variable, or -1 when the layout does not carry it.
    int offsetOf(AovVar v) const;
    std::vector<std::string> channelNames() const;  // count names
};

}  // namespace streyes
