// A shot of thousands of frame files (shot.####.rib, as pipelines write them) is read a block of
// frames at a time (streyes/sequence.h): memory holds one block, whatever the shot's length. The
// peak resident memory of 5,000 frames must be that of 500, within a margin far below what keeping
// the frames read would cost (measured here too: one block of 500 frames).
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>

#include "cli_run.h"
#include "streyes/image_io.h"
#include "test_util.h"

namespace streyes {
namespace {

namespace fs = std::filesystem;
using test::MeasuredRun;
using test::runStreyesMeasured;

// A folder for thousands of small files: in memory (/dev/shm) where there is one, so that the
// frames' writes (each synced to disk) do not make the test slow; removed with what it holds.
struct ShotFolder {
    std::string path;
    ShotFolder() {
        std::error_code ec;
        const std::string base = fs::is_directory("/dev/shm", ec) && access("/dev/shm", W_OK) == 0
                                     ? "/dev/shm"
                                     : fs::temp_directory_path().string();
        std::string tmpl = base + "/streyes-long-shot-XXXXXX";
        if (!mkdtemp(tmpl.data())) throw std::runtime_error("mkdtemp failed for " + tmpl);
        path = tmpl;
    }
    ~ShotFolder() {
        std::error_code ec;
        fs::remove_all(path, ec);
    }
};

// Frame f: a square a little nearer each frame (so that no two frames are the same primitive), in
// its own colour, written under the frame's own Display name.
void writeShot(const std::string& dir, int frames) {
    for (int f = 1; f <= frames; ++f) {
        char name[32];
        std::snprintf(name, sizeof name, "/shot.%04d.rib", f);
        char text[512];
        std::snprintf(text, sizeof text,
                      "Format 8 8 1\nProjection \"orthographic\"\nScreenWindow 0 8 0 8\nPixelSamples 1 1\n"
                      "Display \"out/f.####.exr\" \"openexr\" \"rgba\"\nWorldBegin\nSurface \"constant\"\n"
                      "Color [%.3f 0.5 0.5]\nPatch \"bilinear\" \"P\" [0 0 5  8 0 5  0 8 5  8 8 %.4f]\nWorldEnd\n",
                      double(f % 7) / 7.0, 5.0 + f * 0.0001);
        std::FILE* out = std::fopen((dir + name).c_str(), "w");
        ASSERT_NE(out, nullptr) << dir + name;
        std::fputs(text, out);
        std::fclose(out);
    }
}

// The render's peak resident memory (--stats "peak_memory_bytes": VmHWM, its own), or -1.
long renderShot(const std::string& dir, int frames, const std::string& frameBlock = "64") {
    fs::remove_all(dir + "/out");
    fs::create_directories(dir + "/out");
    // One thread: frames are parsed two at a time, so that the peak does not depend on how many a
    // batch of the parser's holds on this machine.
    const MeasuredRun r = runStreyesMeasured({"render", "shot.####.rib", "--frames", "1-" + std::to_string(frames),
                                              "--frame-block", frameBlock, "--threads", "1", "--quiet", "--stats",
                                              "stats.json"},
                                             dir);
    EXPECT_EQ(r.exitCode, 0) << r.output;
    const std::string stats = test::readFile(dir + "/stats.json"), key = "\"peak_memory_bytes\": ";
    const size_t at = stats.find(key);
    EXPECT_NE(at, std::string::npos) << stats;
    return r.exitCode == 0 && at != std::string::npos ? std::atol(stats.c_str() + at + key.size()) : -1;
}

TEST(LongShot, FiveThousandFrameFilesReadInMemoryBoundedByTheFrameBlock) {
    if (test::kAddressSanitizer)
        GTEST_SKIP() << "the address sanitizer's quarantine holds freed memory: peaks grow with what was allocated";
    const ShotFolder dir;
    writeShot(dir.path, 5000);
    const long few = renderShot(dir.path, 500);
    const long many = renderShot(dir.path, 5000);
    ASSERT_GT(few, 0);
    ASSERT_GT(many, 0);
    EXPECT_TRUE(isCompleteFrame(dir.path + "/out/f.5000.exr", 8, 8, "rgba"));
    EXPECT_TRUE(isCompleteFrame(dir.path + "/out/f.2500.exr", 8, 8, "rgba"));
    // What keeping frames costs: 500 frames in one block hold every one of them at once.
    const long held = renderShot(dir.path, 500, "500");
    ASSERT_GT(held, 0);
    const double mib = 1024.0 * 1024.0;
    std::cout << "peak resident memory: 500 frames " << few / mib << " MiB, 5000 frames " << many / mib
              << " MiB (blocks of 64); 500 frames in one block " << held / mib << " MiB\n";
    RecordProperty("peak_500_frames_bytes", std::to_string(few));
    RecordProperty("peak_5000_frames_bytes", std::to_string(many));
    // The margin: 2 MiB and 10% (the allocator's slack between runs). Keeping the 4,500 frames
    // more would cost nine times what holding 436 more costs in one block.
    const long margin = std::max(2l << 20, few / 10);
    EXPECT_LE(many, few + margin);
    EXPECT_GT((held - few) * 9, 2 * margin) << "frames held would not show past the margin: the comparison would prove little";
}

}  // namespace
}  // namespace streyes
