// The pixels' alpha after an Imager shader: its own alpha when it names it, else the mean of the
// Oi it leaves, as Aqsis takes it (the fisheye example's imager draws a disc over an empty world
// by setting Oi); an imager that names neither keeps the rendered alpha.
#include <gtest/gtest.h>


#include "shader_test_util.h"
#include "test_util.h"

namespace streyes {
namespace {

test::RenderResult render(const test::ShaderDir& d, const std::string& imager) {
    // The left half covered by an opaque square; the right half empty.
    return test::renderRib("Format 8 8 1\nProjection \"orthographic\"\nScreenWindow 0 8 0 8\nPixelFilter \"box\" 1 1\n"
                           "PixelSamples 2 2\n" +
                           d.option() + "Imager \"" + imager + "\"\nWorldBegin\nSurface \"constant\"\n" +
                           test::square(0, 4, 0, 8, 10) + "WorldEnd\n");
}

TEST(ImagerAlpha, TheMeanOfTheImagersOiWhenItSetsIt) {
    test::ShaderDir d{"imager-alpha"};
    d.add("opacity", "imager opacity() { Oi = color(0.1, 0.2, 0.6); Ci = Oi; }\n");
    const test::RenderResult r = render(d, "opacity");
    for (int x = 0; x < 8; ++x) {
        EXPECT_NEAR(r.alpha(0, x, 3), 0.3f, 1e-6f) << x;  // covered or not
        EXPECT_NEAR(r.channel(0, x, 3, 2), 0.6f, 1e-6f) << x;
    }
}

TEST(ImagerAlpha, ItsOwnAlphaWhenItNamesIt) {
    test::ShaderDir d{"imager-alpha"};
    d.add("both", "imager both() { Oi = 0.25; alpha = 0.75; }\n");
    const test::RenderResult r = render(d, "both");
    for (int x = 0; x < 8; ++x) EXPECT_NEAR(r.alpha(0, x, 3), 0.75f, 1e-6f) << x;
}

TEST(ImagerAlpha, TheRenderedAlphaWhenItNamesNeither) {
    test::ShaderDir d{"imager-alpha"};
    d.add("tint", "imager tint() { Ci *= 0.5; }\n");
    const test::RenderResult r = render(d, "tint");
    for (int x = 0; x < 8; ++x) {
        EXPECT_EQ(r.alpha(0, x, 3), x < 4 ? 1.0f : 0.0f) << x;
        EXPECT_EQ(r.channel(0, x, 3, 0), x < 4 ? 0.5f : 0.0f) << x;
    }
}

}  // namespace
}  // namespace streyes
