// The Shading Language's colour spaces: "rgb", "hsv", "hsl", "xyz" (CIE XYZ, Rec. 709
// primaries, D65 white), "xyY", "yiq". Hue is in [0, 1).
#pragma once

#include <string>

namespace streyes::sl {

enum class ColorSpace { RGB, HSV, HSL, XYZ, XYY, YIQ, Unknown };

ColorSpace colorSpaceNamed(const std::string& name);  // case-insensitive
void toRgb(ColorSpace from, const float in[3], float out[3]);
void fromRgb(ColorSpace to, const float in[3], float out[3]);

}  // namespace streyes::sl
