// The writer thread: frames written as queued, and a failed write stops what follows.
#include "io/frame_writer.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <set>

#include "streyes/error.h"
#include "streyes/image_io.h"
#include "test_util.h"

namespace streyes {
namespace {

FrameImage frameOf(int frame, float value) {
    FrameImage f;
    f.frame = frame;
    f.resize(4, 2);
    for (float& v : f.rgba) v = value;
    for (float& z : f.z) z = 2.0f + value;
    return f;
}

TEST(FrameWriter, WritesEveryQueuedFrameWithItsPixels) {
    const test::TempDir tempDir("writer");
    const std::string& dir = tempDir.path();
    FrameWriter writer(1);  // a queue of one: write() waits for the thread
    for (int f = 1; f <= 5; ++f) {
        FrameImage img = frameOf(f, 0.125f * float(f));
        writer.write(img, {{dir + "/f." + std::to_string(f) + ".exr", "rgbaz", {}, {}}});
        img.rgba.assign(img.rgba.size(), -1.0f);  // the renderer reuses its images: the writer holds a copy
    }
    writer.finish();
    for (int f = 1; f <= 5; ++f) {
        const ImageData im = readImage(dir + "/f." + std::to_string(f) + ".exr");
        ASSERT_EQ(im.channels.size(), 5u);
        EXPECT_EQ(im.at(3, 1, 0), 0.125f * float(f)) << f;
        EXPECT_EQ(im.at(3, 1, 4), 2.0f + 0.125f * float(f)) << f;
    }
}

// handOver queues the caller's pixels themselves and gives back the buffers of frames already
// written: every frame's file has its own pixels, and a shot cycles through a few buffers.
TEST(FrameWriter, HandOverTakesThePixelsAndGivesBackWrittenBuffers) {
    const test::TempDir tempDir("writer-hand-over");
    const std::string& dir = tempDir.path();
    FrameWriter writer(1);
    FrameImage img;
    std::set<const float*> buffers;  // every rgba buffer the caller has filled
    for (int f = 1; f <= 8; ++f) {
        const float value = 0.125f * float(f);
        if (img.rgba.empty()) {
            img = frameOf(f, value);
        } else {  // a written frame's buffers, of the same shape: filled again, as the renderer does
            ASSERT_EQ(img.rgba.size(), 4u * 2u * 4u);
            img.frame = f;
            for (float& v : img.rgba) v = value;
            for (float& z : img.z) z = 2.0f + value;
        }
        const float* filled = img.rgba.data();
        buffers.insert(filled);
        writer.handOver(img, {{dir + "/f." + std::to_string(f) + ".exr", "rgbaz", {}, {}}});
        EXPECT_NE(img.rgba.data(), filled) << "frame " << f << " was copied, not taken";
    }
    writer.finish();
    EXPECT_LE(buffers.size(), 4u);  // the queue (1), the frame being written, the spares (2)
    for (int f = 1; f <= 8; ++f) {
        const ImageData im = readImage(dir + "/f." + std::to_string(f) + ".exr");
        ASSERT_EQ(im.channels.size(), 5u);
        EXPECT_EQ(im.at(0, 0, 0), 0.125f * float(f)) << f;
        EXPECT_EQ(im.at(3, 1, 4), 2.0f + 0.125f * float(f)) << f;
    }
}

TEST(FrameWriter, AFailedWriteStopsTheFramesAfterIt) {
    const test::TempDir tempDir("writer-fails");
    const std::string& dir = tempDir.path();
    FrameWriter writer(4);
    writer.write(frameOf(1, 0.5f), {{dir + "/a.exr", "rgba", {}, {}}});
    writer.write(frameOf(2, 0.5f), {{dir + "/missing/b.exr", "rgba", {}, {}}});
    bool thrown = false;
    try {
        writer.write(frameOf(3, 0.5f), {{dir + "/c.exr", "rgba", {}, {}}});
        writer.finish();
    } catch (const RenderError& e) {
        thrown = true;
        EXPECT_NE(std::string(e.what()).find("missing/b.exr"), std::string::npos) << e.what();
    }
    EXPECT_TRUE(thrown);
    EXPECT_TRUE(std::filesystem::exists(dir + "/a.exr"));
    EXPECT_FALSE(std::filesystem::exists(dir + "/c.exr"));
    EXPECT_THROW(writer.finish(), RenderError);  // the error stays
}

}  // namespace
}  // namespace streyes
