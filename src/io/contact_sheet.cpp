#include "io/contact_sheet.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>

#include "film/film.h"
#include "io/image_library.h"
#include "streyes/image_io.h"
#include "streyes/error.h"

namespace streyes {

SheetLayout layoutSheet(int count, int frameWidth, int frameHeight, const SheetOptions& options) {
    SheetLayout l;
    l.count = count;
    l.columns = options.columns > 0 ? options.columns : std::max(1, int(std::ceil(std::sqrt(double(count)))));
    l.columns = std::max(1, std::min(l.columns, count));
    l.rows = (count + l.columns - 1) / l.columns;
    l.cellWidth = options.cellWidth > 0 ? options.cellWidth : frameWidth;
    l.cellHeight = options.cellWidth > 0
                       ? std::max(1, int(std::lround(double(frameHeight) * options.cellWidth / frameWidth)))
                       : frameHeight;
    l.gap = std::max(0, options.gap);
    l.width = l.gap + l.columns * (l.cellWidth + l.gap);
    l.height = l.gap + l.rows * (l.cellHeight + l.gap);
    return l;
}

namespace {

// Linear light to the sRGB transfer curve, clamped to [0, 1] (the sheet is for looking at).
float encodeSRGB(float c) {
    if (!(c > 0)) return 0;  // also NaN
    if (c >= 1) return 1;
    return c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1 / 2.4f) - 0.055f;
}

// Frame numbers in a 3x5 pixel font: one row a byte, bit 2 the leftmost pixel. '-' is index 10.
constexpr unsigned char kDigits[11][5] = {
    {7, 5, 5, 5, 7}, {2, 6, 2, 2, 7}, {7, 1, 7, 4, 7}, {7, 1, 7, 1, 7}, {5, 5, 7, 1, 1}, {7, 4, 7, 1, 7},
    {7, 4, 7, 5, 7}, {7, 1, 1, 1, 1}, {7, 5, 7, 5, 7}, {7, 5, 7, 1, 7}, {0, 0, 7, 0, 0},
};

// White digits on a black box in the lower-left corner of the cell at (cx, cy); nothing when the
// label does not fit the cell.
void drawLabel(FrameImage& sheet, int cx, int cy, int cellW, int cellH, int frame) {
    const std::string text = std::to_string(frame);
    const int s = std::clamp(cellH / 45, 1, 4);               // pixel size of a font pixel
    const int boxW = (4 * int(text.size()) + 1) * s, boxH = 7 * s;  // glyphs 3 wide, 1 apart, 1 of padding
    if (boxW + 2 * s > cellW || boxH + 2 * s > cellH) return;
    const int x0 = cx + s, y0 = cy + cellH - s - boxH;
    auto set = [&](int x, int y, float v) {
        float* p = &sheet.rgba[(size_t(y) * size_t(sheet.width) + size_t(x)) * 4];
        p[0] = p[1] = p[2] = v;
    };
    for (int y = 0; y < boxH; ++y)
        for (int x = 0; x < boxW; ++x) set(x0 + x, y0 + y, 0);
    for (size_t k = 0; k < text.size(); ++k) {
        const unsigned char* g = kDigits[text[k] == '-' ? 10 : text[k] - '0'];
        for (int row = 0; row < 5; ++row)
            for (int col = 0; col < 3; ++col)
                if (g[row] & (4 >> col))
                    for (int dy = 0; dy < s; ++dy)
                        for (int dx = 0; dx < s; ++dx)
                            set(x0 + (1 + 4 * int(k) + col) * s + dx, y0 + (1 + row) * s + dy, 1);
    }
}

// R G B of a frame as a 3-channel float buffer, scaled to w x h with OpenImageIO's filtered resize
// (through the image library module).
std::vector<float> frameRGB(const ImageData& im, const std::string& path, int w, int h) {
    const int c[3] = {im.channelIndex("R"), im.channelIndex("G"), im.channelIndex("B")};
    if (c[0] < 0 || c[1] < 0 || c[2] < 0) throw InputError("'" + path + "' has no R, G and B channels");
    std::vector<float> rgb(size_t(im.width) * size_t(im.height) * 3);
    for (size_t i = 0, n = size_t(im.width) * size_t(im.height); i < n; ++i)
        for (int k = 0; k < 3; ++k) rgb[i * 3 + size_t(k)] = im.pixels[i * im.channels.size() + size_t(c[k])];
    if (w == im.width && h == im.height) return rgb;
    std::vector<float> out(size_t(w) * size_t(h) * 3);
    std::string why;
    if (!imageLibrary().resize(rgb.data(), im.width, im.height, out.data(), w, h, &why))
        throw RenderError("cannot scale '" + path + "': " + why);
    return out;
}

}  // namespace

void writeContactSheet(const std::vector<SheetFrame>& frames, const std::string& path, const SheetOptions& options) {
    std::string ext = std::filesystem::path(path).extension().string();
    for (char& ch : ext) ch = char(std::tolower(static_cast<unsigned char>(ch)));
    if (ext != ".png" && ext != ".jpg" && ext != ".jpeg")
        throw InputError("contact sheet '" + path + "': write a .png or .jpg file");
    if (frames.empty()) throw InputError("contact sheet '" + path + "': no frames");

    SheetLayout layout;
    FrameImage sheet;
    int frameW = 0, frameH = 0;  // the first frame's size: every frame must have it
    for (size_t i = 0; i < frames.size(); ++i) {
        ImageData im;
        try {
            im = readImage(frames[i].path);
        } catch (const RenderError& e) {
            throw InputError(e.what());
        }
        if (i == 0) {
            frameW = im.width;
            frameH = im.height;
            layout = layoutSheet(int(frames.size()), im.width, im.height, options);
            sheet.resize(layout.width, layout.height);
            std::fill(sheet.rgba.begin(), sheet.rgba.end(), 1.0f);  // a white page
        } else if (im.width != frameW || im.height != frameH) {
            throw InputError("'" + frames[i].path + "' is " + std::to_string(im.width) + "x" +
                             std::to_string(im.height) + " but '" + frames[0].path + "' is " +
                             std::to_string(frameW) + "x" + std::to_string(frameH) +
                             ": a contact sheet needs frames of one size");
        }
        const std::vector<float> rgb = frameRGB(im, frames[i].path, layout.cellWidth, layout.cellHeight);
        const int cx = layout.cellX(int(i)), cy = layout.cellY(int(i));
        for (int y = 0; y < layout.cellHeight; ++y)
            for (int x = 0; x < layout.cellWidth; ++x) {
                float* d = &sheet.rgba[(size_t(cy + y) * size_t(layout.width) + size_t(cx + x)) * 4];
                const float* s = &rgb[(size_t(y) * size_t(layout.cellWidth) + size_t(x)) * 3];
                for (int k = 0; k < 3; ++k) d[k] = encodeSRGB(s[k]);
            }
        if (options.labels) drawLabel(sheet, cx, cy, layout.cellWidth, layout.cellHeight, frames[i].frame);
    }
    writeFrame(path, sheet, "rgb");
}

}  // namespace streyes
