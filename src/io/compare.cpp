#include "streyes/compare.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "streyes/error.h"

namespace streyes {

NonFiniteCounts& NonFiniteCounts::operator+=(const NonFiniteCounts& o) {
    colorNaN += o.colorNaN;
    colorInf += o.colorInf;
    zNaN += o.zNaN;
    zNegInf += o.zNegInf;
    return *this;
}

ImageErrors& ImageErrors::operator+=(const ImageErrors& o) {
    pixels += o.pixels;
    pixelsSkipped += o.pixelsSkipped;
    sumSqRGB += o.sumSqRGB;
    sumAbsRGB += o.sumAbsRGB;
    maxAbsRGB = std::max(maxAbsRGB, o.maxAbsRGB);
    sumSqA += o.sumSqA;
    maxAbsA = std::max(maxAbsA, o.maxAbsA);
    pixelsDiffering += o.pixelsDiffering;
    pixelsOverThreshold += o.pixelsOverThreshold;
    hasAlpha = hasAlpha || o.hasAlpha;
    zCompared = zCompared || o.zCompared;
    zCoverageMismatch += o.zCoverageMismatch;
    zDepthMismatch += o.zDepthMismatch;
    zMaxRelDiff = std::max(zMaxRelDiff, o.zMaxRelDiff);
    nonFiniteA += o.nonFiniteA;
    nonFiniteB += o.nonFiniteB;
    return *this;
}

double ImageErrors::rmseRGB() const { return pixels ? std::sqrt(sumSqRGB / (3.0 * double(pixels))) : 0.0; }
double ImageErrors::rmseA() const { return pixels ? std::sqrt(sumSqA / double(pixels)) : 0.0; }
double ImageErrors::meanAbsRGB() const { return pixels ? sumAbsRGB / (3.0 * double(pixels)) : 0.0; }
double ImageErrors::psnr() const {
    const double mse = pixels ? sumSqRGB / (3.0 * double(pixels)) : 0.0;
    return mse > 0 ? 10.0 * std::log10(1.0 / mse) : std::numeric_limits<double>::infinity();
}
double ImageErrors::shareDiffering() const { return pixels ? double(pixelsDiffering) / double(pixels) : 0.0; }
double ImageErrors::shareOverThreshold() const { return pixels ? double(pixelsOverThreshold) / double(pixels) : 0.0; }

namespace {

// Channel indices of the channels compare knows; -1 when absent.
struct Channels {
    int rgb[3], a, z;
    explicit Channels(const ImageData& im)
        : rgb{im.channelIndex("R"), im.channelIndex("G"), im.channelIndex("B")},
          a(im.channelIndex("A")),
          z(im.channelIndex("Z")) {}
};

std::string channelList(const ImageData& im) {
    std::string s;
    for (const std::string& c : im.channels) s += (s.empty() ? "" : ",") + c;
    return s.empty() ? "(none)" : s;
}

NonFiniteCounts countNonFinite(const ImageData& im, const Channels& ch) {
    NonFiniteCounts n;
    const size_t count = size_t(im.width) * size_t(im.height), nch = im.channels.size();
    for (size_t i = 0; i < count; ++i) {
        const float* p = &im.pixels[i * nch];
        for (int c : {ch.rgb[0], ch.rgb[1], ch.rgb[2], ch.a}) {
            if (c < 0) continue;
            if (std::isnan(p[c])) ++n.colorNaN;
            else if (std::isinf(p[c])) ++n.colorInf;
        }
        if (ch.z >= 0) {
            if (std::isnan(p[ch.z])) ++n.zNaN;
            else if (p[ch.z] == -std::numeric_limits<float>::infinity()) ++n.zNegInf;
        }
    }
    return n;
}

}  // namespace

ImageData resampleImage(const ImageData& image, int width, int height) {
    ImageData out;
    out.width = width;
    out.height = height;
    out.channels = image.channels;
    out.formats = image.formats;
    const size_t nch = image.channels.size();
    out.pixels.resize(size_t(width) * size_t(height) * nch);
    const int zc = image.channelIndex("Z");
    const double sx = double(image.width) / width, sy = double(image.height) / height;
    for (int y = 0; y < height; ++y) {
        // Pixel centres map onto pixel centres; outside the outermost centres the edge is held.
        const double fy = std::clamp((y + 0.5) * sy - 0.5, 0.0, double(image.height - 1));
        const int y0 = int(fy), y1 = std::min(y0 + 1, image.height - 1);
        const double ty = fy - y0;
        for (int x = 0; x < width; ++x) {
            const double fx = std::clamp((x + 0.5) * sx - 0.5, 0.0, double(image.width - 1));
            const int x0 = int(fx), x1 = std::min(x0 + 1, image.width - 1);
            const double tx = fx - x0;
            float* d = &out.pixels[(size_t(y) * size_t(width) + size_t(x)) * nch];
            for (size_t c = 0; c < nch; ++c) {
                if (int(c) == zc) {  // depth is not blended (+inf background would give NaN): nearest
                    d[c] = image.at(tx < 0.5 ? x0 : x1, ty < 0.5 ? y0 : y1, int(c));
                    continue;
                }
                const double top = (1 - tx) * image.at(x0, y0, int(c)) + tx * image.at(x1, y0, int(c));
                const double bottom = (1 - tx) * image.at(x0, y1, int(c)) + tx * image.at(x1, y1, int(c));
                d[c] = float((1 - ty) * top + ty * bottom);
            }
        }
    }
    return out;
}

ImageErrors compareImages(const ImageData& a, const ImageData& b, const CompareOptions& options,
                          const std::string& nameA, const std::string& nameB) {
    // Channels: the same names, R G B among them. A mismatch is an error, not a number.
    std::vector<std::string> ca = a.channels, cb = b.channels;
    std::sort(ca.begin(), ca.end());
    std::sort(cb.begin(), cb.end());
    if (ca != cb)
        throw InputError("'" + nameA + "' has channels " + channelList(a) + " but '" + nameB + "' has " +
                         channelList(b) + ": compare images written with the same channels");
    const Channels chA(a), chB(b);
    if (chA.rgb[0] < 0 || chA.rgb[1] < 0 || chA.rgb[2] < 0)
        throw InputError("'" + nameA + "' has channels " + channelList(a) + ": compare needs R, G and B");
    if (!options.resize && (a.width != b.width || a.height != b.height))
        throw InputError("'" + nameA + "' is " + std::to_string(a.width) + "x" + std::to_string(a.height) + " but '" +
                         nameB + "' is " + std::to_string(b.width) + "x" + std::to_string(b.height) +
                         ": render both at the same --res, or pass --resize to resample B to A's size");

    ImageErrors e;
    e.nonFiniteA = countNonFinite(a, chA);
    e.nonFiniteB = countNonFinite(b, chB);
    const bool resized = a.width != b.width || a.height != b.height;
    ImageData resampled;
    if (resized) resampled = resampleImage(b, a.width, a.height);
    const ImageData& bb = resized ? resampled : b;

    e.hasAlpha = chA.a >= 0;
    e.zCompared = chA.z >= 0 && !resized;
    const size_t count = size_t(a.width) * size_t(a.height), nA = a.channels.size(), nB = b.channels.size();
    const float inf = std::numeric_limits<float>::infinity();
    for (size_t i = 0; i < count; ++i) {
        const float* pa = &a.pixels[i * nA];
        const float* pb = &bb.pixels[i * nB];
        // Colour: R G B (and A) together; a pixel with a non-finite value is counted apart.
        float d[4] = {0, 0, 0, 0};
        bool finite = true;
        for (int k = 0; k < 4; ++k) {
            const int ia = k < 3 ? chA.rgb[k] : chA.a, ib = k < 3 ? chB.rgb[k] : chB.a;
            if (ia < 0) continue;
            finite = finite && std::isfinite(pa[ia]) && std::isfinite(pb[ib]);
            d[k] = std::fabs(pa[ia] - pb[ib]);
        }
        if (!finite) {
            ++e.pixelsSkipped;
        } else {
            ++e.pixels;
            for (int k = 0; k < 3; ++k) {
                e.sumSqRGB += double(d[k]) * d[k];
                e.sumAbsRGB += d[k];
                e.maxAbsRGB = std::max(e.maxAbsRGB, double(d[k]));
            }
            e.sumSqA += double(d[3]) * d[3];
            e.maxAbsA = std::max(e.maxAbsA, double(d[3]));
            const float worst = std::max({d[0], d[1], d[2], d[3]});
            if (worst > 0) ++e.pixelsDiffering;
            if (worst > options.threshold) ++e.pixelsOverThreshold;
        }
        // Depth: +inf is "no surface"; NaN and -inf were counted above and are skipped here.
        if (!e.zCompared) continue;
        const float za = pa[chA.z], zb = pb[chB.z];
        if (std::isnan(za) || std::isnan(zb) || za == -inf || zb == -inf) continue;
        if ((za == inf) != (zb == inf)) {
            ++e.zCoverageMismatch;
        } else if (za != inf) {
            const double scale = std::max(std::fabs(double(za)), std::fabs(double(zb)));
            const double rel = scale > 0 ? std::fabs(double(za) - double(zb)) / scale : 0.0;
            e.zMaxRelDiff = std::max(e.zMaxRelDiff, rel);
            if (rel > options.zTolerance) ++e.zDepthMismatch;
        }
    }
    return e;
}

}  // namespace streyes
