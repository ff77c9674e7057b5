#include "io/exr_file.h"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfIO.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStringAttribute.h>
#include <OpenEXR/ImfThreading.h>
#include <Imath/half.h>

#include <algorithm>
#include <atomic>
#include <cstring>
#include <fstream>
#include <stdexcept>

namespace streyes {

namespace {

// OpenEXR writes through an OStream; this one fills a vector.
class MemoryStream final : public Imf::OStream {
  public:
    explicit MemoryStream(std::vector<unsigned char>& bytes) : Imf::OStream("memory"), bytes_(bytes) {}
    void write(const char c[], int n) override {
        if (pos_ + uint64_t(n) > bytes_.size()) bytes_.resize(pos_ + uint64_t(n));
        std::memcpy(bytes_.data() + pos_, c, size_t(n));
        pos_ += uint64_t(n);
    }
    uint64_t tellp() override { return pos_; }
    void seekp(uint64_t pos) override { pos_ = pos; }

  private:
    std::vector<unsigned char>& bytes_;
    uint64_t pos_ = 0;
};

// R, G, B, A first, then the rest by name.
int channelRank(const std::string& name) {
    static const char* kFirst[] = {"R", "G", "B", "A"};
    for (int i = 0; i < 4; ++i)
        if (name == kFirst[i]) return i;
    return 4;
}

std::atomic<int> encodeThreads{1};

// zlib's fastest level. An animation's frames are written as fast as they render: at OpenEXR's
// default (4) zlib took 29% of the demo's CPU time (48 frames at 640x360, rgbaz); level 1 takes
// 10% less CPU in all for files 6% larger. Readers see the same ZIP compression.
constexpr int kZipLevel = 1;

}  // namespace

void setExrEncodeThreads(int threads) {
    threads = std::max(1, threads);
    if (threads == encodeThreads.load()) return;
    Imf::setGlobalThreadCount(threads > 1 ? threads : 0);  // 0: OpenEXR works on the caller's thread
    encodeThreads = threads;
}

std::vector<unsigned char> encodeExr(const FrameImage& image, bool alpha, bool z) {
    const int W = image.width, H = image.height;
    Imf::Header header(W, H);
    header.compression() = Imf::ZIP_COMPRESSION;
    header.zipCompressionLevel() = kZipLevel;
    header.insert("software", Imf::StringAttribute("streyes"));
    const char* names[] = {"R", "G", "B", "A"};
    const int colour = alpha ? 4 : 3;
    for (int c = 0; c < colour; ++c) header.channels().insert(names[c], Imf::Channel(Imf::HALF));
    if (z) header.channels().insert("Z", Imf::Channel(Imf::FLOAT));
    // Colour to half here (Imath's conversion, round to nearest even): OpenEXR's writer takes the
    // file's own pixel type.
    const size_t n = size_t(W) * size_t(H);
    std::vector<half> colours(n * size_t(colour));
    for (size_t i = 0; i < n; ++i)
        for (int c = 0; c < colour; ++c) colours[i * size_t(colour) + size_t(c)] = half(image.rgba[i * 4 + size_t(c)]);
    Imf::FrameBuffer fb;
    const size_t xs = size_t(colour) * sizeof(half), ys = size_t(W) * xs;
    for (int c = 0; c < colour; ++c) fb.insert(names[c], Imf::Slice(Imf::HALF, (char*)(colours.data() + c), xs, ys));
    if (z) fb.insert("Z", Imf::Slice(Imf::FLOAT, (char*)image.z.data(), sizeof(float), size_t(W) * sizeof(float)));
    std::vector<unsigned char> bytes;
    bytes.reserve(size_t(W) * size_t(H) * size_t(colour * 2 + (z ? 4 : 0)) / 2 + 4096);
    MemoryStream stream(bytes);
    {
        Imf::OutputFile file(stream, header, encodeThreads.load());
        file.setFrameBuffer(fb);
        file.writePixels(H);
    }
    return bytes;
}

std::vector<unsigned char> encodeExrChannels(int W, int H, const std::vector<std::string>& channels,
                                             const std::vector<float>& pixels) {
    Imf::Header header(W, H);
    header.compression() = Imf::ZIP_COMPRESSION;
    header.zipCompressionLevel() = kZipLevel;
    header.insert("software", Imf::StringAttribute("streyes"));
    const size_t n = size_t(W) * size_t(H), nc = channels.size();
    // Each channel planar in its file type: halves rounded as encodeExr rounds them.
    std::vector<half> halves;
    std::vector<float> floats;
    std::vector<std::pair<bool, size_t>> where;  // (half, first element) per channel
    for (size_t c = 0; c < nc; ++c) {
        const bool h = channelRank(channels[c]) < 4;
        header.channels().insert(channels[c], Imf::Channel(h ? Imf::HALF : Imf::FLOAT));
        where.emplace_back(h, h ? halves.size() : floats.size());
        if (h) halves.resize(halves.size() + n);
        else floats.resize(floats.size() + n);
    }
    for (size_t c = 0; c < nc; ++c)
        for (size_t i = 0; i < n; ++i) {
            const float v = pixels[i * nc + c];
            if (where[c].first) halves[where[c].second + i] = half(v);
            else floats[where[c].second + i] = v;
        }
    Imf::FrameBuffer fb;
    for (size_t c = 0; c < nc; ++c) {
        const bool h = where[c].first;
        char* base = h ? (char*)(halves.data() + where[c].second) : (char*)(floats.data() + where[c].second);
        const size_t xs = h ? sizeof(half) : sizeof(float);
        fb.insert(channels[c], Imf::Slice(h ? Imf::HALF : Imf::FLOAT, base, xs, size_t(W) * xs));
    }
    std::vector<unsigned char> bytes;
    MemoryStream stream(bytes);
    {
        Imf::OutputFile file(stream, header, encodeThreads.load());
        file.setFrameBuffer(fb);
        file.writePixels(H);
    }
    return bytes;
}

bool readExr(const std::string& path, ImageData* out, std::string* error) {
    try {
        Imf::InputFile file(path.c_str(), 1);
        const Imath::Box2i dw = file.header().dataWindow();
        const int W = dw.max.x - dw.min.x + 1, H = dw.max.y - dw.min.y + 1;
        std::vector<std::pair<std::string, Imf::PixelType>> channels;
        for (auto it = file.header().channels().begin(); it != file.header().channels().end(); ++it)
            channels.emplace_back(it.name(), it.channel().type);
        std::stable_sort(channels.begin(), channels.end(), [](const auto& a, const auto& b) {
            const int ra = channelRank(a.first), rb = channelRank(b.first);
            return ra != rb ? ra < rb : (ra == 4 && a.first < b.first);
        });
        ImageData img;
        img.width = W, img.height = H;
        const size_t n = channels.size();
        img.pixels.assign(size_t(W) * size_t(H) * n, 0.0f);
        Imf::FrameBuffer fb;
        const size_t xs = n * sizeof(float), ys = size_t(W) * xs;
        // The slice's base is where pixel (0, 0) would be, so that (dw.min.x, dw.min.y) lands first.
        char* base = (char*)img.pixels.data() - ptrdiff_t(dw.min.x) * ptrdiff_t(xs) - ptrdiff_t(dw.min.y) * ptrdiff_t(ys);
        for (size_t c = 0; c < n; ++c) {
            img.channels.push_back(channels[c].first);
            img.formats.push_back(channels[c].second == Imf::HALF ? "half" : channels[c].second == Imf::FLOAT ? "float" : "uint");
            fb.insert(channels[c].first, Imf::Slice(Imf::FLOAT, base + c * sizeof(float), xs, ys));
        }
        file.setFrameBuffer(fb);
        file.readPixels(dw.min.y, dw.max.y);
        *out = std::move(img);
        return true;
    } catch (const std::exception& e) {
        if (error) *error = e.what();
        return false;
    }
}

bool isExrFile(const std::string& path) {
    std::ifstream f(path, std::ios::binary);
    unsigned char magic[4] = {0, 0, 0, 0};
    f.read(reinterpret_cast<char*>(magic), 4);
    return f && magic[0] == 0x76 && magic[1] == 0x2f && magic[2] == 0x31 && magic[3] == 0x01;
}

}  // namespace streyes
