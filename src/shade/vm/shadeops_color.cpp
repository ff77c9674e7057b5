// Colour-space conversions: ctransform and the color "space" (a, b, c) constructors.
#include <algorithm>
#include <cctype>
#include <cmath>

#include "shade/vm/color_spaces.h"
#include "shade/vm/ops.h"

namespace streyes::sl {

ColorSpace colorSpaceNamed(const std::string& name) {
    std::string s;
    for (char c : name) s += char(std::tolower(static_cast<unsigned char>(c)));
    if (s == "rgb") return ColorSpace::RGB;
    if (s == "hsv") return ColorSpace::HSV;
    if (s == "hsl") return ColorSpace::HSL;
    if (s == "xyz") return ColorSpace::XYZ;
    if (s == "xyy") return ColorSpace::XYY;
    if (s == "yiq") return ColorSpace::YIQ;
    return ColorSpace::Unknown;
}

namespace {

float hueToRgb(float p, float q, float h) {
    h -= std::floor(h);
    if (h < 1.0f / 6) return p + (q - p) * 6 * h;
    if (h < 0.5f) return q;
    if (h < 2.0f / 3) return p + (q - p) * (2.0f / 3 - h) * 6;
    return p;
}

void rgbToHsvHue(const float c[3], float mx, float mn, float* h) {
    const float d = mx - mn;
    if (d <= 0) {
        *h = 0;
        return;
    }
    float hh;
    if (mx == c[0]) hh = (c[1] - c[2]) / d;
    else if (mx == c[1]) hh = 2 + (c[2] - c[0]) / d;
    else hh = 4 + (c[0] - c[1]) / d;
    hh /= 6;
    *h = hh - std::floor(hh);
}

}  // namespace

void toRgb(ColorSpace from, const float in[3], float out[3]) {
    switch (from) {
        case ColorSpace::HSV: {
            float h = in[0] - std::floor(in[0]), s = in[1], v = in[2];
            if (s <= 0) {
                out[0] = out[1] = out[2] = v;
                return;
            }
            float h6 = h * 6;
            int k = int(h6) % 6;
            float f = h6 - std::floor(h6), p = v * (1 - s), q = v * (1 - s * f), t = v * (1 - s * (1 - f));
            const float table[6][3] = {{v, t, p}, {q, v, p}, {p, v, t}, {p, q, v}, {t, p, v}, {v, p, q}};
            for (int c = 0; c < 3; ++c) out[c] = table[k][c];
            return;
        }
        case ColorSpace::HSL: {
            float h = in[0], s = in[1], l = in[2];
            if (s <= 0) {
                out[0] = out[1] = out[2] = l;
                return;
            }
            float q = l < 0.5f ? l * (1 + s) : l + s - l * s, p = 2 * l - q;
            out[0] = hueToRgb(p, q, h + 1.0f / 3);
            out[1] = hueToRgb(p, q, h);
            out[2] = hueToRgb(p, q, h - 1.0f / 3);
            return;
        }
        case ColorSpace::XYY: {
            float xyz[3];
            float y = in[1], Y = in[2];
            if (y == 0) {
                xyz[0] = xyz[1] = xyz[2] = 0;
            } else {
                xyz[0] = in[0] * Y / y;
                xyz[1] = Y;
                xyz[2] = (1 - in[0] - y) * Y / y;
            }
            toRgb(ColorSpace::XYZ, xyz, out);
            return;
        }
        case ColorSpace::XYZ:
            out[0] = 3.2404542f * in[0] - 1.5371385f * in[1] - 0.4985314f * in[2];
            out[1] = -0.9692660f * in[0] + 1.8760108f * in[1] + 0.0415560f * in[2];
            out[2] = 0.0556434f * in[0] - 0.2040259f * in[1] + 1.0572252f * in[2];
            return;
        case ColorSpace::YIQ:
            out[0] = in[0] + 0.9563f * in[1] + 0.6210f * in[2];
            out[1] = in[0] - 0.2721f * in[1] - 0.6474f * in[2];
            out[2] = in[0] - 1.1070f * in[1] + 1.7046f * in[2];
            return;
        default:
            out[0] = in[0];
            out[1] = in[1];
            out[2] = in[2];
    }
}

void fromRgb(ColorSpace to, const float in[3], float out[3]) {
    const float mx = std::max(in[0], std::max(in[1], in[2])), mn = std::min(in[0], std::min(in[1], in[2]));
    switch (to) {
        case ColorSpace::HSV:
            rgbToHsvHue(in, mx, mn, &out[0]);
            out[1] = mx > 0 ? (mx - mn) / mx : 0;
            out[2] = mx;
            return;
        case ColorSpace::HSL: {
            rgbToHsvHue(in, mx, mn, &out[0]);
            float l = (mx + mn) / 2, d = mx - mn;
            out[1] = d <= 0 ? 0 : (l < 0.5f ? d / (mx + mn) : d / (2 - mx - mn));
            out[2] = l;
            return;
        }
        case ColorSpace::XYZ:
            out[0] = 0.4124564f * in[0] + 0.3575761f * in[1] + 0.1804375f * in[2];
            out[1] = 0.2126729f * in[0] + 0.7151522f * in[1] + 0.0721750f * in[2];
            out[2] = 0.0193339f * in[0] + 0.1191920f * in[1] + 0.9503041f * in[2];
            return;
        case ColorSpace::XYY: {
            float xyz[3];
            fromRgb(ColorSpace::XYZ, in, xyz);
            float s = xyz[0] + xyz[1] + xyz[2];
            out[0] = s > 0 ? xyz[0] / s : 0;
            out[1] = s > 0 ? xyz[1] / s : 0;
            out[2] = xyz[1];
            return;
        }
        case ColorSpace::YIQ:
            out[0] = 0.299f * in[0] + 0.587f * in[1] + 0.114f * in[2];
            out[1] = 0.595716f * in[0] - 0.274453f * in[1] - 0.321263f * in[2];
            out[2] = 0.211456f * in[0] - 0.522591f * in[1] + 0.311135f * in[2];
            return;
        default:
            out[0] = in[0];
            out[1] = in[1];
            out[2] = in[2];
    }
}

namespace ops {

// a0 = a3 from colour space a1 (-1: rgb) to a2. An unknown space name is rgb (and counted).
void ctransform(Exec& x, const Instr& in) {
    RegView d = x.view(in.a[0]), c = x.view(in.a[3]);
    ColorSpace from = in.a[1] >= 0 ? colorSpaceNamed(x.str(in.a[1])) : ColorSpace::RGB;
    ColorSpace to = colorSpaceNamed(x.str(in.a[2]));
    if (from == ColorSpace::Unknown || to == ColorSpace::Unknown) ++x.stats.unknownSpaces;
    for (int i = 0; i < d.w; ++i) {
        V3 v = load3(c, i);
        float a[3] = {v.x, v.y, v.z}, rgb[3], out[3];
        toRgb(from, a, rgb);
        fromRgb(to, rgb, out);
        store3(d, i, {out[0], out[1], out[2]});
    }
}

}  // namespace ops
}  // namespace streyes::sl
