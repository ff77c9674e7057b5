#include "io/exr_file.h"

#include "streyes/image_io.h"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfThreading.h>
#include <OpenEXR/openexr.h>
#include <Imath/half.h>
#include <libdeflate.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cstring>
#include <filesystem>
#include <fstream>
#if defined(__x86_64__)
#include <cpuid.h>
#include <immintrin.h>
#endif
#include <memory>
#include <mutex>
#include <stdexcept>

#include "io/image_size.h"

namespace streyes {

namespace {

// R, G, B, A first, then the rest by name.
int channelRank(const std::string& name) {
    static const char* kFirst[] = {"R", "G", "B", "A"};
    for (int i = 0; i < 4; ++i)
        if (name == kFirst[i]) return i;
    return 4;
}

std::atomic<int> encodeThreads{1};

// ---- Writing --------------------------------------------------------------------------------------
// An animation's frames are written as fast as they render. OpenEXR 3.1 compresses ZIP with zlib:
// 25-29% of the demo's CPU time (48 frames at 640x360, rgbaz) even at zlib's fastest level. The
// ZIP format is a zlib stream, which libdeflate makes 1.7x faster at its level 1, in files 5%
// smaller than zlib's level 1 (as OpenEXR 3.2 does). So each chunk is packed, predicted and
// compressed here, and OpenEXRCore writes the file around the chunks.

constexpr int kDeflateLevel = 1;
constexpr int kLinesPerChunk = 16;  // a ZIP chunk's scanlines (the format's)

// One channel of the image: its name, file type, and where pixel (x, y) is (base + y ys + x xs).
struct Plane {
    std::string name;
    bool half;
    const unsigned char* base;
    size_t xs, ys;
};

// The ZIP format's pre-pass: the chunk's bytes split into the even ones then the odd ones, and
// each byte after the first stored as its difference from the one before, plus 128.
// Written as two independent passes (split, then differences of the split bytes, each from a
// byte the pass does not write) so that the compiler vectorises both.
void zipPredict(const unsigned char* in, size_t n, unsigned char* split, unsigned char* out) {
    const size_t half = (n + 1) / 2;
    for (size_t k = 0; k < half; ++k) split[k] = in[2 * k];
    for (size_t k = 0; k < n / 2; ++k) split[half + k] = in[2 * k + 1];
    if (n) out[0] = split[0];
    for (size_t i = 1; i < n; ++i) out[i] = static_cast<unsigned char>(split[i] - split[i - 1] + 128);
}

// A file's chunks of scanlines, each as bytes.
using Chunks = std::vector<std::vector<unsigned char>>;

// The last file encoded in each channel layout (at most kCachedLayouts of them, the most recent):
// each chunk packed as the file's scanlines, and as stored. Deflate at a fixed level is a
// function of its input, so a chunk of the next file in that layout whose packed bytes are the
// same is stored the same: an animation's frames compress only the chunks that changed (in the
// demo, about 60% of chunks are the frame before's), and each file is what compressing every
// chunk makes, bit for bit.
struct ChunkCache {
    int W = 0, H = 0;
    std::vector<std::pair<std::string, bool>> layout;  // channel names and half, in file order
    Chunks packed, stored;
};
constexpr size_t kCachedLayouts = 4;  // a frame's beauty file and a few output-variable files
struct ChunkCaches {
    std::mutex mutex;
    std::vector<std::shared_ptr<const ChunkCache>> recent;  // most recent first
    std::atomic<uint64_t> reused{0}, compressed{0};
};
ChunkCaches& chunkCaches() {
    static ChunkCaches caches;
    return caches;
}

struct DeflateDeleter {
    void operator()(libdeflate_compressor* c) const { libdeflate_free_compressor(c); }
};

// Chunks [c0, c1) of the image, each as the file stores it: scanline by scanline, each scanline's
// channels one after the other in name order, little-endian (packedChunks[c]); then compressed,
// or kept as they are where compressing would not make them smaller (readers take a chunk of its
// full size as raw); or, where `last` (the last file in this layout) packed the same bytes, what
// it stored.
void compressChunks(int W, int H, const std::vector<Plane>& planes, int c0, int c1, const ChunkCache* last,
                    Chunks& packedChunks, Chunks& chunks) {
    std::unique_ptr<libdeflate_compressor, DeflateDeleter> z;
    std::vector<unsigned char> split, predicted;
    uint64_t reused = 0, compressed = 0;
    for (int c = c0; c < c1; ++c) {
        const int y0 = c * kLinesPerChunk, y1 = std::min(H, y0 + kLinesPerChunk);
        std::vector<unsigned char>& packed = packedChunks[size_t(c)];
        packed.clear();
        for (int y = y0; y < y1; ++y)
            for (const Plane& p : planes) {
                const size_t bytes = p.half ? 2 : 4, at = packed.size();
                packed.resize(at + bytes * size_t(W));
                const unsigned char* row = p.base + size_t(y) * p.ys;
                if (p.xs == bytes) {
                    std::memcpy(packed.data() + at, row, bytes * size_t(W));
                } else {
                    for (int x = 0; x < W; ++x)
                        std::memcpy(packed.data() + at + size_t(x) * bytes, row + size_t(x) * p.xs, bytes);
                }
            }
        std::vector<unsigned char>& out = chunks[size_t(c)];
        if (last && last->packed[size_t(c)] == packed) {
            out = last->stored[size_t(c)];
            ++reused;
            continue;
        }
        if (!z) z.reset(libdeflate_alloc_compressor(kDeflateLevel));
        if (!z) throw std::bad_alloc();
        split.resize(packed.size());
        predicted.resize(packed.size());
        zipPredict(packed.data(), packed.size(), split.data(), predicted.data());
        out.resize(libdeflate_zlib_compress_bound(z.get(), predicted.size()));
        const size_t n =
            libdeflate_zlib_compress(z.get(), predicted.data(), predicted.size(), out.data(), out.size());
        if (n == 0 || n >= packed.size()) out = packed;
        else out.resize(n);
        ++compressed;
    }
    chunkCaches().reused += reused;
    chunkCaches().compressed += compressed;
}

// OpenEXRCore writes into memory (at the offsets it asks for: the chunk table last) and reports
// its errors to the encoder, not to stderr.
struct MemoryTarget {
    std::vector<unsigned char>* bytes;
    std::string error;
};

int64_t writeToMemory(exr_const_context_t, void* user, const void* buffer, uint64_t size, uint64_t offset,
                      exr_stream_error_func_ptr_t) {
    auto* target = static_cast<MemoryTarget*>(user);
    if (offset + size > target->bytes->size()) target->bytes->resize(offset + size);
    std::memcpy(target->bytes->data() + offset, buffer, size);
    return int64_t(size);
}

void keepError(exr_const_context_t ctxt, exr_result_t code, const char* message) {
    void* user = nullptr;
    if (exr_get_user_data(ctxt, &user) == EXR_ERR_SUCCESS && user) {
        auto* target = static_cast<MemoryTarget*>(user);
        if (target->error.empty())
            target->error = std::string(exr_get_error_code_as_string(code)) + ": " + (message ? message : "");
    }
}

// `window` (may be null): a crop's place, the data window at (x0, y0) in a display window of
// fullWidth x fullHeight (RenderMan's crop files); else both windows are the W x H pixels.
std::vector<unsigned char> encodeScanlines(int W, int H, std::vector<Plane> planes, const FrameWindow* window) {
    std::sort(planes.begin(), planes.end(),
              [](const Plane& a, const Plane& b) { return std::strcmp(a.name.c_str(), b.name.c_str()) < 0; });
    const int chunkCount = (H + kLinesPerChunk - 1) / kLinesPerChunk;
    auto cache = std::make_shared<ChunkCache>();
    cache->W = W, cache->H = H;
    for (const Plane& p : planes) cache->layout.emplace_back(p.name, p.half);
    auto sameLayout = [&](const std::shared_ptr<const ChunkCache>& c) {
        return c->W == W && c->H == H && c->layout == cache->layout;
    };
    std::shared_ptr<const ChunkCache> last;
    {
        ChunkCaches& caches = chunkCaches();
        std::lock_guard<std::mutex> lock(caches.mutex);
        const auto found = std::find_if(caches.recent.begin(), caches.recent.end(), sameLayout);
        if (found != caches.recent.end()) last = *found;
    }
    Chunks& packed = cache->packed;
    packed.resize(size_t(chunkCount));
    Chunks chunks(static_cast<size_t>(chunkCount));
    if (encodeThreads.load() > 1 && chunkCount > 1) {
        tbb::parallel_for(tbb::blocked_range<int>(0, chunkCount, 4), [&](const tbb::blocked_range<int>& r) {
            compressChunks(W, H, planes, r.begin(), r.end(), last.get(), packed, chunks);
        });
    } else {
        compressChunks(W, H, planes, 0, chunkCount, last.get(), packed, chunks);
    }

    size_t chunkBytes = 0;
    for (const std::vector<unsigned char>& c : chunks) chunkBytes += c.size();
    std::vector<unsigned char> bytes;
    bytes.reserve(4096 + size_t(chunkCount) * 16 + chunkBytes);  // header, offsets and chunk heads, chunks
    MemoryTarget target{&bytes, {}};
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.user_data = &target;
    init.write_fn = writeToMemory;
    init.error_handler_fn = keepError;
    exr_context_t ctxt = nullptr;
    auto check = [&](exr_result_t r) {
        if (r == EXR_ERR_SUCCESS) return;
        const std::string why = target.error.empty() ? exr_get_error_code_as_string(r) : target.error;
        if (ctxt) exr_finish(&ctxt);
        throw std::runtime_error("EXR encoding failed: " + why);
    };
    check(exr_start_write(&ctxt, "memory", EXR_WRITE_FILE_DIRECTLY, &init));
    int part = 0;
    check(exr_add_part(ctxt, nullptr, EXR_STORAGE_SCANLINE, &part));
    const int x0 = window ? window->x0 : 0, y0 = window ? window->y0 : 0;
    if (window && window->fullWidth > 0) {
        exr_attr_box2i_t display{}, data{};
        display.max.x = window->fullWidth - 1, display.max.y = window->fullHeight - 1;
        data.min.x = x0, data.min.y = y0, data.max.x = x0 + W - 1, data.max.y = y0 + H - 1;
        exr_attr_v2f_t centre{};
        check(exr_initialize_required_attr(ctxt, part, &display, &data, 1.0f, &centre, 1.0f, EXR_LINEORDER_INCREASING_Y,
                                           EXR_COMPRESSION_ZIP));
    } else {
        check(exr_initialize_required_attr_simple(ctxt, part, W, H, EXR_COMPRESSION_ZIP));
    }
    for (const Plane& p : planes)
        check(exr_add_channel(ctxt, part, p.name.c_str(), p.half ? EXR_PIXEL_HALF : EXR_PIXEL_FLOAT,
                              EXR_PERCEPTUALLY_LOGARITHMIC, 1, 1));
    check(exr_attr_set_string(ctxt, part, "software", "streyes"));
    check(exr_write_header(ctxt));
    for (int c = 0; c < chunkCount; ++c)
        check(exr_write_scanline_chunk(ctxt, part, y0 + c * kLinesPerChunk, chunks[size_t(c)].data(),
                                       chunks[size_t(c)].size()));
    check(exr_finish(&ctxt));
    // This file becomes its layout's last (replacing the one before), the most recent.
    cache->stored = std::move(chunks);
    {
        ChunkCaches& caches = chunkCaches();
        std::lock_guard<std::mutex> lock(caches.mutex);
        auto& recent = caches.recent;
        recent.erase(std::remove_if(recent.begin(), recent.end(), sameLayout), recent.end());
        recent.insert(recent.begin(), std::move(cache));
        if (recent.size() > kCachedLayouts) recent.resize(kCachedLayouts);
    }
    return bytes;
}

}  // namespace

void forgetExrChunks() {
    ChunkCaches& caches = chunkCaches();
    std::lock_guard<std::mutex> lock(caches.mutex);
    caches.recent.clear();
}

ExrChunkCounts exrChunkCounts() { return {chunkCaches().reused.load(), chunkCaches().compressed.load()}; }

void setExrEncodeThreads(int threads) {
    threads = std::max(1, threads);
    if (threads == encodeThreads.load()) return;
    Imf::setGlobalThreadCount(threads > 1 ? threads : 0);  // reading: 0, OpenEXR works on the caller's thread
    encodeThreads = threads;
}

namespace {

#if defined(__x86_64__)
__attribute__((target("avx,f16c"))) void floatsToHalvesF16C(const float* in, size_t n, uint16_t* out) {
    size_t i = 0;
    for (; i + 8 <= n; i += 8)
        _mm_storeu_si128(reinterpret_cast<__m128i*>(out + i),
                         _mm256_cvtps_ph(_mm256_loadu_ps(in + i), _MM_FROUND_TO_NEAREST_INT | _MM_FROUND_NO_EXC));
    for (; i < n; ++i) out[i] = _cvtss_sh(in[i], _MM_FROUND_TO_NEAREST_INT | _MM_FROUND_NO_EXC);
}

// F16C and AVX, with the AVX registers saved by the OS (XCR0 bits 1 and 2). By cpuid: Clang's
// __builtin_cpu_supports does not know "f16c".
bool hasF16C() {
    unsigned a = 0, b = 0, c = 0, d = 0;
    if (!__get_cpuid(1, &a, &b, &c, &d)) return false;
    if (!(c & bit_F16C) || !(c & bit_AVX) || !(c & bit_OSXSAVE)) return false;
    unsigned lo = 0, hi = 0;
    __asm__("xgetbv" : "=a"(lo), "=d"(hi) : "c"(0));
    return (lo & 6u) == 6u;
}
#endif

// The frame's first `colour` channels as half bits, a plane per channel (the file's layout, so
// that packing a chunk copies whole rows).
std::vector<half> colourPlanes(const FrameImage& image, int colour) {
    const size_t n = size_t(image.width) * size_t(image.height);
    std::vector<uint16_t> interleaved(n * 4);
    floatsToHalves(image.rgba.data(), n * 4, interleaved.data());
    std::vector<half> planes(n * size_t(colour));
    for (size_t i = 0; i < n; ++i)
        for (int c = 0; c < colour; ++c) planes[size_t(c) * n + i].setBits(interleaved[i * 4 + size_t(c)]);
    return planes;
}

}  // namespace

void floatsToHalves(const float* in, size_t n, uint16_t* out) {
#if defined(__x86_64__)
    static const bool f16c = hasF16C();
    if (f16c) return floatsToHalvesF16C(in, n, out);
#endif
    for (size_t i = 0; i < n; ++i) out[i] = half(in[i]).bits();
}

std::vector<unsigned char> encodeExr(const FrameImage& image, bool alpha, bool z, const FrameWindow* window) {
    const int W = image.width, H = image.height;
    const char* names[] = {"R", "G", "B", "A"};
    const int colour = alpha ? 4 : 3;
    const size_t n = size_t(W) * size_t(H);
    const std::vector<half> colours = colourPlanes(image, colour);
    std::vector<Plane> planes;
    for (int c = 0; c < colour; ++c)
        planes.push_back({names[c], true, reinterpret_cast<const unsigned char*>(colours.data() + size_t(c) * n),
                          sizeof(half), size_t(W) * sizeof(half)});
    if (z) {
        const auto* depth = reinterpret_cast<const unsigned char*>(image.z.data());
        planes.push_back({"Z", false, depth, sizeof(float), size_t(W) * sizeof(float)});
    }
    return encodeScanlines(W, H, std::move(planes), window);
}

std::vector<unsigned char> encodeExrChannels(int W, int H, const std::vector<std::string>& channels,
                                             const std::vector<float>& pixels, const FrameWindow* window) {
    const size_t n = size_t(W) * size_t(H), nc = channels.size();
    // Each channel planar in its file type: halves rounded as encodeExr rounds them.
    std::vector<half> halves;
    std::vector<float> floats;
    std::vector<std::pair<bool, size_t>> where;  // (half, first element) per channel
    for (size_t c = 0; c < nc; ++c) {
        const bool h = channelRank(channels[c]) < 4;
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
    std::vector<Plane> planes;
    for (size_t c = 0; c < nc; ++c) {
        const bool h = where[c].first;
        const unsigned char* base = h ? reinterpret_cast<const unsigned char*>(halves.data() + where[c].second)
                                      : reinterpret_cast<const unsigned char*>(floats.data() + where[c].second);
        const size_t xs = h ? sizeof(half) : sizeof(float);
        planes.push_back({channels[c], h, base, xs, size_t(W) * xs});
    }
    return encodeScanlines(W, H, std::move(planes), window);
}

bool readExr(const std::string& path, ImageData* out, std::string* error) {
    try {
        Imf::InputFile file(path.c_str(), 1);
        const Imath::Box2i dw = file.header().dataWindow();
        std::vector<std::pair<std::string, Imf::PixelType>> channels;
        int64_t sampleBytes = 0;
        for (auto it = file.header().channels().begin(); it != file.header().channels().end(); ++it) {
            channels.emplace_back(it.name(), it.channel().type);
            sampleBytes += it.channel().type == Imf::HALF ? 2 : 4;
        }
        // The header is believed only as far as the file can hold it: the pixels are allocated next.
        const int64_t w64 = int64_t(dw.max.x) - dw.min.x + 1, h64 = int64_t(dw.max.y) - dw.min.y + 1;
        std::error_code ec;
        const std::string implausible =
            implausibleImageSize(w64, h64, channels.empty() ? 0 : int64_t(channels.size()),
                                 channels.empty() ? 0 : (sampleBytes + int64_t(channels.size()) - 1) / int64_t(channels.size()),
                                 std::filesystem::file_size(path, ec));
        if (!implausible.empty()) {
            if (error) *error = implausible;
            return false;
        }
        const int W = int(w64), H = int(h64);
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
