// Writing test pictures through OpenImageIO (the format by the file's extension).
#pragma once

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace streyes::test {

// Writes a float picture, `channels` interleaved floats a pixel, rows from the top.
inline void writeFloatImage(const std::string& path, int w, int h, int channels, const std::vector<float>& pixels) {
    auto out = OIIO::ImageOutput::create(path);
    ASSERT_TRUE(out) << path;
    OIIO::ImageSpec spec(w, h, channels, OIIO::TypeDesc::FLOAT);
    ASSERT_TRUE(out->open(path, spec)) << out->geterror();
    ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, pixels.data())) << out->geterror();
    ASSERT_TRUE(out->close());
}

}  // namespace streyes::test
