// A forest of Weber–Penn trees (Procedural "DynamicLoad" ["forest" "model=weberpenn ..."]): every
// tree is one of the presets asked for, the cells' bounds (from each preset's foot bound, without
// growing a tree) hold the trees' own bounds whatever the seed and the wind, and rendered, nothing
// outgrows its bound and a frame alone is the frame in a block.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <sstream>

#include "procedural/forest.h"
#include "procedural/weber_penn.h"
#include "streyes/rib.h"
#include "test_util.h"

namespace streyes {
namespace {

bool holds(const Bounds3d& outer, const Bounds3d& inner) {
    return outer.lo.x <= inner.lo.x && outer.lo.y <= inner.lo.y && outer.lo.z <= inner.lo.z &&
           outer.hi.x >= inner.hi.x && outer.hi.y >= inner.hi.y && outer.hi.z >= inner.hi.z;
}

TEST(ForestWeberPenn, TheFootBoundHoldsEveryTreeOfThePreset) {
    for (const std::string& name : weberPennPresetNames()) {
        const Bounds3d foot = weberPennFootBound(*weberPennPreset(name));
        for (uint64_t seed = 1; seed <= 60; ++seed)
            for (double wind : {0.0, 2.0}) {
                WeberPennParams p = *weberPennPreset(name);
                p.seed = seed, p.windSpeed = 2 * wind, p.windGust = wind;
                EXPECT_TRUE(holds(foot, weberPennBound(p))) << name << " seed " << seed << " wind " << wind;
            }
    }
}

TEST(ForestWeberPenn, EveryTreeIsOneOfThePresetsAskedFor) {
    const char* block = "count=40 seed=3 area=200,200 cell=8 model=weberpenn presets=quaking_aspen,ca_black_oak";
    ExpandContext ctx;
    ctx.detail = 1e12;
    ProceduralOutput cells;
    makeForestGenerator(block, {})->expand(ctx, cells);
    ASSERT_GE(cells.procedurals.size(), 2u);  // cells of 8 trees, on a grid over the area
    std::map<std::string, int> kinds;
    for (const auto& cell : cells.procedurals) {
        ProceduralOutput trees;
        cell.generator->expand(ctx, trees);
        for (const auto& t : trees.procedurals) {
            ++kinds[t.generator->describe()];
            // The tree stands inside its cell's bound (the cell's bound is in the forest's space,
            // the tree's in its own: placed by its transform).
            EXPECT_TRUE(holds(cell.desc.bound, t.desc.objectToWorld.at(0).box(t.desc.bound)));
        }
    }
    int total = 0;
    for (const auto& [kind, n] : kinds) total += n;
    EXPECT_EQ(total, 40);
    ASSERT_EQ(kinds.size(), 2u);
    EXPECT_GT(kinds["DynamicLoad tree (weberpenn quaking_aspen)"], 8);
    EXPECT_GT(kinds["DynamicLoad tree (weberpenn ca_black_oak)"], 8);
}

TEST(ForestWeberPenn, AnUnknownPresetIsAnError) {
    EXPECT_THROW(parseForestParams("model=weberpenn presets=quaking_aspen,palm", {}), InputError);
    EXPECT_THROW(parseForestParams("model=lsystem", {}), InputError);
    EXPECT_TRUE(parseForestParams("count=3", {}).weberPennPresets.empty());
    EXPECT_EQ(parseForestParams("model=weberpenn", {}).weberPennPresets, weberPennPresetNames());
}

// Four quaking aspens (about 13 m) on 40 x 20 m seen from 32 m; the declared bound from the
// preset's foot bound around the area.
std::string grove(const std::string& extra) {
    // Each tree is turned about its foot: its foot bound's box turned by up to 45 degrees.
    Bounds3d foot = weberPennFootBound(*weberPennPreset("quaking_aspen"));
    foot.lo.x *= std::sqrt(2.0), foot.hi.x *= std::sqrt(2.0), foot.lo.z *= std::sqrt(2.0), foot.hi.z *= std::sqrt(2.0);
    std::ostringstream rib;
    rib << "Format 64 48 1\nProjection \"perspective\" \"fov\" [50]\nPixelSamples 2 2\nShutter 0 0.5\n"
        << "Rotate 10 1 0 0\nTranslate 0 -8 32\nWorldBegin\n"
        << "LightSource \"distantlight\" 1 \"from\" [-1 2 -1] \"to\" [0 0 0]\nLightSource \"ambientlight\" 2 \"intensity\" [0.3]\n"
        << "Surface \"matte\"\nProcedural \"DynamicLoad\" [\"forest\" \"count=4 seed=5 area=40,20 cell=2 model=weberpenn "
        << "presets=quaking_aspen " << extra << "\"] [" << foot.lo.x - 20 << " " << foot.hi.x + 20 << " " << foot.lo.y << " "
        << foot.hi.y << " " << foot.lo.z - 10 << " " << foot.hi.z + 10 << "]\nWorldEnd\n";
    return rib.str();
}

TEST(ForestWeberPenn, AFrameAloneIsTheFrameInABlockAndNothingOutgrowsItsBound) {
    RenderOptions o;
    o.hasShot = true;
    o.shotFirst = 1;
    o.shotLast = 3;
    for (const char* wind : {"wind=0", "wind=0.5 keystep=1"}) {
        SCOPED_TRACE(wind);
        const test::ShotAndFrame r = test::renderShotAndFrame(grove(wind), o, 1, 3, 2);
        ASSERT_EQ(r.shot.frames.size(), 3u);
        EXPECT_TRUE(r.samePixels(2));
        EXPECT_TRUE(r.shot.warnings.empty()) << r.shot.warnings.front();
        // Four trees of about 13 m at 45 m: a good part of the frame, not all of it.
        const double alpha = test::alphaSum(r.alone, 2);
        EXPECT_GT(alpha, 0.1 * 64 * 48);
        EXPECT_LT(alpha, 0.9 * 64 * 48);
    }
}

}  // namespace
}  // namespace streyes
