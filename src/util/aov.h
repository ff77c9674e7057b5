// Arbitrary output variables (AOVs): what a Display mode may name beside colour, and the EXR
// channels each is written as.
//
// A mode is a comma-separated list of outputs: "rgb", "rgba", "rgbaz" (colour, as always), "a"
// (alpha), "z" (depth), and the variables N, P (camera space), s, t, Ci, Oi and motion (raster
// motion, pixels per frame). The variables are carried per sample from shading to the film; z and
// a come from the samples' own depth and coverage.
#pragma once

#include <string>
#include <vector>

namespace streyes {

enum class AovVar { N, P, s, t, Ci, Oi, Motion };

struct AovVariable {
    AovVar var;
    const char* name;      // as a Display mode names it
    const char* type;      // as DisplayChannel declares it ("normal", "point", "float", "color", "vector")
    int width;             // floats per sample
    const char* channels[3];  // EXR channel names
};

// The variable a mode or DisplayChannel names, or null.
const AovVariable* findAovVariable(const std::string& name);
// "N, P, s, t, Ci, Oi, motion": for messages.
std::string aovVariableList();

// The outputs of a mode, split at commas. Empty with *error set when one is not known (or the
// mode is empty).
std::vector<std::string> modeOutputs(const std::string& mode, std::string* error);
// The channels a mode writes, in order: "rgba,N" -> R G B A N.X N.Y N.Z.
std::vector<std::string> modeChannels(const std::string& mode);
// The variables a mode needs carried per sample, in order of first mention.
std::vector<std::string> modeVariables(const std::string& mode);

// The variables a render carries, laid out one after another per sample.
struct AovLayout {
    std::vector<const AovVariable*> vars;
    std::vector<int> offset;  // of each variable, in floats
    int count = 0;            // floats per sample
    explicit AovLayout(const std::vector<std::string>& names = {});
    // The offset of a variable, or -1 when the layout does not carry it.
    int offsetOf(AovVar v) const;
    std::vector<std::string> channelNames() const;  // count names
};

}  // namespace streyes
