// Retained objects (ObjectBegin / ObjectEnd / ObjectInstance): an instance draws exactly what the
// object's geometry written out under the instance's transform and attributes draws, is culled
// before it is expanded, and mistakes are errors naming file:line.
#include <gtest/gtest.h>

#include "streyes/rib.h"
#include "test_util.h"

namespace streyes {
namespace {

std::string errorOf(const std::string& text) { return test::ribError(text); }

// An object of two squares (its own transform inside the block), placed three times (one
// instance outside the image), against the same squares written out at each place.
TEST(Instancing, InstancesDrawTheObjectWhereTheyArePlaced) {
    const std::string object = test::square(0, 4, 0, 4, 5) + "Translate 5 0 0\n" + test::square(0, 2, 0, 6, 6);
    auto placed = [](const std::string& body, double x, double y, const char* color) {
        return "AttributeBegin\nTranslate " + std::to_string(x) + " " + std::to_string(y) + " 0\nColor " + color +
               "\n" + body + "AttributeEnd\n";
    };
    const std::string header = test::orthoHeader(32, 32, "PixelSamples 3 3\n");
    const std::string instanced = header + "ObjectBegin 1\n" + object + "ObjectEnd\nObjectBegin \"tree\"\n" +
                                  test::square(0, 3, 0, 3, 4) + "ObjectEnd\n" + placed("ObjectInstance 1\n", 2.3, 3.6, "1 0 0") +
                                  placed("ObjectInstance 1\n", 19.5, 20.25, "0 1 0") +
                                  placed("ObjectInstance \"tree\"\n", 11.2, 25.1, "0 0 1") +
                                  placed("ObjectInstance 1\n", 100, 100, "1 1 1") + "WorldEnd\n";
    const std::string written = header + placed("AttributeBegin\n" + object + "AttributeEnd\n", 2.3, 3.6, "1 0 0") +
                                placed(object, 19.5, 20.25, "0 1 0") + placed(test::square(0, 3, 0, 3, 4), 11.2, 25.1, "0 0 1") +
                                "WorldEnd\n";
    for (Algorithm a : {Algorithm::SpacetimeOcclusion, Algorithm::Frames, Algorithm::Raytrace}) {
        const test::RenderResult inst = test::renderRib(instanced, test::optionsFor(a));
        const test::RenderResult ref = test::renderRib(written, test::optionsFor(a));
        EXPECT_TRUE(test::identicalPixels(inst, ref)) << algorithmName(a) << ": max difference "
                                                       << test::maxAbsDifference(inst, ref);
        EXPECT_FLOAT_EQ(inst.channel(0, 3, 26, 0), 1.0f);  // inside the red instance's first square
        EXPECT_FLOAT_EQ(inst.channel(0, 25, 8, 1), 1.0f);   // the green one's second square
        EXPECT_FLOAT_EQ(inst.channel(0, 12, 4, 2), 1.0f);   // the blue "tree"
    }
    // The instance outside the image is culled before it is expanded (the ray tracer expands
    // everything up front, as it does procedurals).
    const test::RenderResult inst = test::renderRib(instanced);
    EXPECT_EQ(inst.stats.counters.proceduralsExpanded, 3u);
}

// An instance's own motion: transform keys before ObjectInstance move it, as they move the
// object written out.
TEST(Instancing, AnInstanceMovesWithItsOwnTransform) {
    const std::string header = test::orthoHeader(32, 16, "Option \"streyes\" \"int frames\" [0 3]\n");
    const std::string motion = "MotionBegin [0 3]\nTranslate 2 5 0\nTranslate 20 6 0\nMotionEnd\n";
    const std::string object = test::square(0, 5, 0, 4, 5);
    const test::RenderResult inst =
        test::renderRib(header + "ObjectBegin 7\n" + object + "ObjectEnd\n" + motion + "ObjectInstance 7\nWorldEnd\n");
    const test::RenderResult ref = test::renderRib(header + motion + object + "WorldEnd\n");
    ASSERT_EQ(inst.frames.size(), 4u);
    EXPECT_LT(test::maxAbsDifference(inst, ref), 1e-6f);
    EXPECT_EQ(inst.alpha(0, 3, 8), 1.0f);  // frame 0: x 2..7, y 5..9
    EXPECT_EQ(inst.alpha(3, 3, 8), 0.0f);  // frame 3 has moved on (x 20..25)
}

// Instances are not kept: each bucket their bound reaches expands them for itself and frees the
// children when it is done (memory follows the buckets at work, not the instances). An instance
// across four 16-pixel buckets is expanded four times, one inside a bucket once; the pixels are
// those of the geometry written out, whatever the buckets.
TEST(Instancing, EachBucketExpandsTheInstancesItReaches) {
    const std::string header = test::orthoHeader(64, 32, "PixelSamples 2 2\n");
    const std::string object = test::square(0, 6, 0, 6, 5);
    const std::string places = "Translate 13 13 0\n";  // x 13..19, y 13..19: four buckets
    const std::string inside = "Translate 35 3 0\n";   // x 35..41 (bucket 32..47), y 3..9 (rows 22..28)
    auto render = [&](const std::string& a, const std::string& b, int bucket) {
        RenderOptions o;
        o.bucketSize = bucket;
        return test::renderRib(header + "ObjectBegin 1\n" + object + "ObjectEnd\n" + a + b + "WorldEnd\n", o);
    };
    const test::RenderResult four = render("AttributeBegin\n" + places + "ObjectInstance 1\nAttributeEnd\n",
                                           "AttributeBegin\n" + inside + "ObjectInstance 1\nAttributeEnd\n", 16);
    EXPECT_EQ(four.stats.counters.proceduralsExpanded, 5u);
    const test::RenderResult whole = render("AttributeBegin\n" + places + "ObjectInstance 1\nAttributeEnd\n",
                                            "AttributeBegin\n" + inside + "ObjectInstance 1\nAttributeEnd\n", 64);
    EXPECT_EQ(whole.stats.counters.proceduralsExpanded, 2u);
    const test::RenderResult written = test::renderRib(header + "AttributeBegin\n" + places + object + "AttributeEnd\n" +
                                                       "AttributeBegin\n" + inside + object + "AttributeEnd\nWorldEnd\n");
    EXPECT_TRUE(test::identicalPixels(four, written));
    EXPECT_TRUE(test::identicalPixels(whole, written));
    EXPECT_EQ(four.alpha(0, 16, 16), 1.0f);
    EXPECT_EQ(four.alpha(0, 38, 25), 1.0f);
}

TEST(Instancing, MistakesAreErrorsNamingTheLine) {
    const std::string world = "WorldBegin\n";
    EXPECT_EQ(errorOf(world + "ObjectBegin 1\nSphere 1 -1 1 360\nObjectEnd\nObjectInstance 1\nWorldEnd\n"), "");
    std::string e = errorOf(world + "ObjectBegin 1\nSphere 1 -1 1 360\nObjectEnd\nObjectInstance 2\nWorldEnd\n");
    EXPECT_NE(e.find("bad.rib:5:"), std::string::npos) << e;
    EXPECT_NE(e.find("no object 2 is defined"), std::string::npos) << e;
    e = errorOf(world + "ObjectBegin \"a\"\nSphere 1 -1 1 360\nWorldEnd\n");
    EXPECT_NE(e.find("bad.rib:2:"), std::string::npos) << e;
    EXPECT_NE(e.find("missing ObjectEnd"), std::string::npos) << e;
    e = errorOf(world + "ObjectBegin 1\nObjectBegin 2\n");
    EXPECT_NE(e.find("bad.rib:3:"), std::string::npos) << e;
    e = errorOf(world + "ObjectBegin 1\nLightSource \"pointlight\" 1\nObjectEnd\nWorldEnd\n");
    EXPECT_NE(e.find("bad.rib:3:"), std::string::npos) << e;
    EXPECT_NE(e.find("geometry only"), std::string::npos) << e;
    e = errorOf(world + "ObjectBegin 1\nAttributeBegin\nObjectEnd\nWorldEnd\n");
    EXPECT_NE(e.find("bad.rib:3:"), std::string::npos) << e;
    EXPECT_NE(e.find("AttributeBegin is never closed"), std::string::npos) << e;
    e = errorOf(world + "ObjectBegin 1\nObjectInstance 1\nObjectEnd\nWorldEnd\n");
    EXPECT_NE(e.find("cannot hold itself"), std::string::npos) << e;
    e = errorOf(world + "ObjectBegin [1 2]\n");
    EXPECT_NE(e.find("whole number or a string"), std::string::npos) << e;
    // Outside the world: skipped with a warning, as the peers do (an error until issue 46); an
    // error under --strict.
    EXPECT_EQ(errorOf("ObjectBegin 1\nObjectEnd\nWorldBegin\nWorldEnd\n"), "");
    e = test::ribError("ObjectBegin 1\nObjectEnd\nWorldBegin\nWorldEnd\n", true);
    EXPECT_NE(e.find("bad.rib:1:"), std::string::npos) << e;

    // An empty object warns once, at its ObjectBegin.
    Log log;
    parseRibString(world + "ObjectBegin 3\nObjectEnd\nObjectInstance 3\nObjectInstance 3\nWorldEnd\n", "w.rib", log);
    ASSERT_EQ(log.warnings().size(), 1u);
    EXPECT_NE(log.warnings()[0].find("w.rib:2"), std::string::npos) << log.warnings()[0];
}

}  // namespace
}  // namespace streyes
