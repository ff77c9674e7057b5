// Frame patterns on disk.
#include "streyes/image_io.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>

#include <Imath/half.h>

#include "io/exr_file.h"
#include "streyes/error.h"
#include "test_util.h"

namespace streyes {
namespace {

TEST(FramePatterns, FindFramesListsExactlyTheFilesThePatternNames) {
    const test::TempDir tempDir("find-frames");
    const std::string& dir = tempDir.path();
    for (const char* name : {"a.0001.exr", "a.0002.exr", "a.12345.exr", "a.-003.exr",  // frames 1, 2, 12345, -3
                             "a.7.exr", "a.0004.exr.tmp", "b.0005.exr", "a.00x6.exr", "a.0007.EXR"})
        std::ofstream(dir + "/" + name) << "x";
    EXPECT_EQ(findFrames(dir + "/a.####.exr"), (std::vector<int>{-3, 1, 2, 12345}));
    EXPECT_EQ(findFrames(dir + "/a.#.exr"), (std::vector<int>{7, 12345}));  // "0001" is not "1"
    EXPECT_TRUE(findFrames(dir + "/c.####.exr").empty());
    EXPECT_TRUE(findFrames(dir + "/missing/a.####.exr").empty());
    EXPECT_THROW(findFrames(dir + "/f##/a.####.exr"), InputError);
}

std::string fileBytes(const std::string& path) {
    std::ifstream f(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>());
}

// A frame whose pixels equal the last frame written reuses that encoding: the file must be the one
// encoding it would have given, and a frame that differs in one bit must not reuse it.
TEST(FrameFiles, IdenticalFramesReuseTheirEncodingBitForBit) {
    const test::TempDir tempDir("reuse");
    const std::string& dir = tempDir.path();
    FrameImage a, b;
    a.resize(8, 4);
    for (size_t i = 0; i < a.rgba.size(); ++i) a.rgba[i] = float(i % 7) * 0.125f;
    for (size_t i = 0; i < a.z.size(); ++i) a.z[i] = 1.0f + float(i);
    b = a;
    b.z[5] = std::nextafter(b.z[5], 100.0f);  // one bit apart
    writeFrame(dir + "/a1.exr", a, "rgbaz");   // encoded
    writeFrame(dir + "/b.exr", b, "rgbaz");    // encoded: differs
    writeFrame(dir + "/a2.exr", a, "rgbaz");   // encoded again (the last was b)
    writeFrame(dir + "/a3.exr", a, "rgbaz");   // reused
    writeFrame(dir + "/a4.exr", a, "rgba");    // another mode: encoded
    const std::string a1 = fileBytes(dir + "/a1.exr");
    ASSERT_FALSE(a1.empty());
    EXPECT_EQ(fileBytes(dir + "/a2.exr"), a1);
    EXPECT_EQ(fileBytes(dir + "/a3.exr"), a1);
    EXPECT_NE(fileBytes(dir + "/b.exr"), a1);
    EXPECT_NE(fileBytes(dir + "/a4.exr"), a1);
    const ImageData rb = readImage(dir + "/b.exr"), ra = readImage(dir + "/a3.exr"), r4 = readImage(dir + "/a4.exr");
    ASSERT_EQ(rb.channels.size(), 5u);
    EXPECT_EQ(rb.at(5, 0, 4), b.z[5]);
    EXPECT_EQ(ra.at(5, 0, 4), a.z[5]);
    EXPECT_EQ(r4.channels.size(), 4u);
}

// OpenEXR compressing a frame's scanline blocks on several threads writes the same bytes as one
// thread (files must not depend on the thread count), and they read back as the frame.
TEST(FrameFiles, EncodingThreadsDoNotChangeTheBytes) {
    FrameImage f;
    f.resize(37, 100);  // seven blocks of 16 scanlines, the last short
    uint32_t h = 12345;
    for (float& v : f.rgba) v = float((h = h * 1664525u + 1013904223u) >> 8) / float(1 << 24);
    for (size_t i = 0; i < f.z.size(); ++i) f.z[i] = 1.0f + float(i % 13) * 0.5f;
    f.rgba[(50 * 37 + 3) * 4] = 0.375f;  // exact in half
    std::vector<float> rz(37 * 100 * 2);
    for (size_t i = 0; i < rz.size(); ++i) rz[i] = float(i % 29) * 0.125f;
    // Every chunk compressed each time (none reused from the file before, which is the same).
    const ExrChunkCounts before = exrChunkCounts();
    setExrEncodeThreads(1);
    forgetExrChunks();
    const std::vector<unsigned char> one = encodeExr(f, true, true);
    const std::vector<unsigned char> channels = encodeExrChannels(37, 100, {"R", "Z"}, rz);
    setExrEncodeThreads(3);
    forgetExrChunks();
    const std::vector<unsigned char> three = encodeExr(f, true, true);
    const std::vector<unsigned char> channels3 = encodeExrChannels(37, 100, {"R", "Z"}, rz);
    setExrEncodeThreads(1);
    EXPECT_EQ(exrChunkCounts().compressed - before.compressed, 4u * 7u);
    EXPECT_EQ(exrChunkCounts().reused, before.reused);
    ASSERT_GT(one.size(), 1000u);
    EXPECT_TRUE(one == three);
    EXPECT_TRUE(channels == channels3);
    const test::TempDir tempDir("threads");
    const std::string path = tempDir.path() + "/f.exr";
    std::ofstream(path, std::ios::binary)
        .write(reinterpret_cast<const char*>(three.data()), std::streamsize(three.size()));
    const ImageData back = readImage(path);
    ASSERT_EQ(back.channels.size(), 5u);
    EXPECT_EQ(back.at(36, 99, 4), f.z[99 * 37 + 36]);
    EXPECT_EQ(back.at(3, 50, 0), 0.375f);
}

// An animation's next frame stores the chunks of 16 scanlines it shares with the last file of
// the same size and channels as that file stored them, and compresses the others: the file is
// the same, bit for bit, as one with every chunk compressed. A chunk differing in one half, one
// depth, or only in the sign of a zero depth is compressed again; files of other channels or
// another size in between do not make the frame's chunks forgotten or wrongly reused.
TEST(FrameFiles, AFramesUnchangedChunksAreStoredAsTheLastFilesWereWithTheSameBytes) {
    FrameImage a;
    a.resize(37, 100);  // seven chunks, the last short
    uint32_t h = 777;
    for (float& v : a.rgba) v = float((h = h * 1664525u + 1013904223u) >> 8) / float(1 << 24);
    for (size_t i = 0; i < a.z.size(); ++i) a.z[i] = 1.0f + float(i % 11) * 0.25f;
    a.z[3] = 0.0f;
    FrameImage b = a;
    b.rgba[(40 * 37 + 5) * 4] += 0.25f;  // chunk 2: a half that changes
    b.z[97 * 37 + 36] += 1.0f;           // chunk 6 (the short one): a depth
    FrameImage c = b;
    c.z[3] = -0.0f;  // chunk 0: the same number, other bits
    auto cold = [](const FrameImage& f) {
        forgetExrChunks();
        return encodeExr(f, true, true);
    };
    const std::vector<unsigned char> coldB = cold(b), coldC = cold(c);
    ASSERT_NE(coldB, coldC);
    forgetExrChunks();
    encodeExr(a, true, true);
    // In between: other channels, and the same channels at another size.
    encodeExrChannels(37, 100, {"R", "Z"}, std::vector<float>(37 * 100 * 2, 0.5f));
    FrameImage small;
    small.resize(37, 99);
    encodeExr(small, true, true);
    ExrChunkCounts n0 = exrChunkCounts();
    EXPECT_EQ(encodeExr(b, true, true), coldB);
    ExrChunkCounts n1 = exrChunkCounts();
    EXPECT_EQ(n1.reused - n0.reused, 5u);      // chunks 0, 1, 3, 4, 5 from a's file
    EXPECT_EQ(n1.compressed - n0.compressed, 2u);  // chunks 2 and 6
    EXPECT_EQ(encodeExr(c, true, true), coldC);
    const ExrChunkCounts n2 = exrChunkCounts();
    EXPECT_EQ(n2.reused - n1.reused, 6u);
    EXPECT_EQ(n2.compressed - n1.compressed, 1u);  // chunk 0: -0 is not 0 in the file
    // The files read back as their frames.
    const test::TempDir tempDir("chunks");
    const std::string path = tempDir.path() + "/c.exr";
    std::ofstream(path, std::ios::binary)
        .write(reinterpret_cast<const char*>(coldC.data()), std::streamsize(coldC.size()));
    const ImageData back = readImage(path);
    EXPECT_TRUE(std::signbit(back.at(3, 0, 4)));
    EXPECT_EQ(back.at(36, 97, 4), c.z[97 * 37 + 36]);
}

// Frames' colour goes to half floats eight at a time (F16C where the CPU has it): every float
// rounds as Imath's half(float) rounds it, ties to even, subnormals, overflow to infinity and
// infinities; NaN stays NaN. Over every exponent and random mantissas.
TEST(FrameFiles, HalvesRoundAsImathRoundsThem) {
    std::vector<float> in;
    uint32_t h = 99;
    for (uint32_t e = 0; e < 256; ++e)
        for (int k = 0; k < 64; ++k) {
            h = h * 1664525u + 1013904223u;
            // Random mantissas, and ones exactly halfway between two halves (ties).
            const uint32_t m = k % 4 == 0 ? (h & 0x7fe000u) | 0x1000u : (h >> 9);
            const uint32_t bits = (uint32_t(k & 1) << 31) | (e << 23) | (m & 0x7fffffu);
            float f;
            std::memcpy(&f, &bits, sizeof f);
            in.push_back(f);
        }
    in.push_back(65504.0f), in.push_back(65520.0f), in.push_back(-0.0f), in.push_back(5.96e-8f);
    std::vector<uint16_t> out(in.size());
    floatsToHalves(in.data(), in.size(), out.data());
    int wrong = 0, nans = 0;
    for (size_t i = 0; i < in.size(); ++i) {
        const half fast(half::FromBits, out[i]), ref(in[i]);
        if (std::isnan(in[i])) {
            nans += fast.isNan();
            wrong += !fast.isNan();
        } else {
            wrong += out[i] != ref.bits();
        }
    }
    EXPECT_EQ(wrong, 0);
    EXPECT_GT(nans, 0);
}

// The frames' ZIP chunks are made here (libdeflate, exr_file.cpp) and read by OpenEXR's reader:
// every pixel comes back as written, from a chunk that compresses (a flat colour), one that
// cannot (random bits, stored as it is) and a short last chunk; a flat frame really shrinks.
TEST(FrameFiles, EveryPixelReadsBackFromCompressedAndStoredChunks) {
    const int W = 53, H = 40;  // chunks of 16 scanlines: flat, noise, and 8 lines of a ramp
    FrameImage f;
    f.resize(W, H);
    uint32_t h = 777;
    auto next = [&] { return h = h * 1664525u + 1013904223u; };
    auto noiseHalf = [&] {  // a random finite half, as a float (converts back exactly)
        const uint32_t b = next() >> 16;
        return float(half(half::FromBits, uint16_t((b & 0x83ffu) | ((b % 31u) << 10))));
    };
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            const size_t i = size_t(y) * size_t(W) + size_t(x);
            for (int c = 0; c < 4; ++c)
                f.rgba[i * 4 + size_t(c)] = y < 16 ? 0.25f * float(c + 1) : y < 32 ? noiseHalf() : float(x) / 64.0f;
            uint32_t zb = (next() & 0x007fffffu) | ((1u + next() % 250u) << 23);  // finite, positive
            float z;
            std::memcpy(&z, &zb, sizeof z);
            f.z[i] = y < 16 ? 5.0f : y < 32 ? z : 1.0f + float(y);
        }
    const std::vector<unsigned char> bytes = encodeExr(f, true, true);
    const test::TempDir tempDir("chunks");
    const std::string path = tempDir.path() + "/f.exr";
    std::ofstream(path, std::ios::binary)
        .write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
    const ImageData back = readImage(path);
    ASSERT_EQ(back.width, W);
    ASSERT_EQ(back.height, H);
    ASSERT_EQ(back.channels, (std::vector<std::string>{"R", "G", "B", "A", "Z"}));
    int wrong = 0;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            const size_t i = size_t(y) * size_t(W) + size_t(x);
            for (int c = 0; c < 4; ++c)
                wrong += std::memcmp(&back.pixels[i * 5 + size_t(c)], &f.rgba[i * 4 + size_t(c)], 4) != 0;
            wrong += std::memcmp(&back.pixels[i * 5 + 4], &f.z[i], 4) != 0;
        }
    EXPECT_EQ(wrong, 0);
    // Random bits cannot shrink: the noise chunk alone holds W * 16 * (4 * 2 + 4) bytes.
    EXPECT_GT(bytes.size(), size_t(W) * 16 * 12);
    FrameImage flat;
    flat.resize(W, H);
    std::fill(flat.rgba.begin(), flat.rgba.end(), 0.5f);
    std::fill(flat.z.begin(), flat.z.end(), 3.0f);
    EXPECT_LT(encodeExr(flat, true, true).size(), size_t(W) * size_t(H) * 12 / 10);
}

}  // namespace
}  // namespace streyes
