// Hard cases in geometry (scenes/hard/): degenerate bodies, the eye plane, the split limit.
// Each renders a scene and checks what its header promises, sample by sample where the answer is
// analytic (sample_oracle.h).
#include <gtest/gtest.h>

#include <cmath>

#include "sample_oracle.h"
#include "streyes/rib.h"

namespace streyes {
namespace {

using test::OracleReport;
using test::RenderResult;

Scene loadScene(const std::string& path) {
    Log log;
    return parseRibFile(test::sourcePath(path), log);
}

// Layers over a point, or "either way, up to two" (negative) within `radius` pixels of a fold:
// where a patch's Jacobian vanishes (for a planar bilinear patch, J(u, v) = A + B u + C v, a
// line in (u, v)). Micropolygons that straddle a fold are twisted, and cover the folded
// surface only to within their own size.
class AwayFromFolds {
  public:
    AwayFromFolds(const Scene& scene, double radius) : scene_(scene), layers_(scene), radius_(radius) {}
    int operator()(double x, double y, double t) {
        if (foldPoints_.empty() || t != time_) update(t);
        for (const Vec3d& p : foldPoints_)
            if (std::hypot(p.x - x, p.y - y) < radius_) return -2;
        return layers_(x, y, t);
    }

  private:
    void update(double t) {
        time_ = t;
        foldPoints_.clear();
        auto cross2 = [](Vec3d a, Vec3d b) { return a.x * b.y - a.y * b.x; };
        for (const BilinearPatchDesc& p : test::bilinearPatches(scene_)) {
            const std::array<Vec3d, 4> c = test::cameraCorners(scene_, p, t);
            const Vec3d e = c[1] - c[0], f = c[2] - c[0], g = c[0] - c[1] - c[2] + c[3];
            const double A = cross2(e, f), B = cross2(e, g), C = cross2(g, f);
            for (int i = 0; i <= 256; ++i) {
                const double s = i / 256.0;
                double u = s, v = s;
                if (std::fabs(C) >= std::fabs(B) && C != 0) v = -(A + B * u) / C;
                else if (B != 0) u = -(A + C * v) / B;
                else continue;
                if (u < 0 || u > 1 || v < 0 || v > 1) continue;
                foldPoints_.push_back(lerp(lerp(c[0], c[1], u), lerp(c[2], c[3], u), v));
            }
        }
        foldPoints_.push_back({1e30, 1e30, 0});  // never empty
    }
    const Scene& scene_;
    test::PatchLayers layers_;
    double radius_, time_ = 0;
    std::vector<Vec3d> foldPoints_;
};

// Nothing in the image is NaN or infinite (Z may be +inf where nothing was hit).
void expectFinite(const RenderResult& r) {
    for (const FrameImage& f : r.frames) {
        for (float v : f.rgba) ASSERT_TRUE(std::isfinite(v));
        for (float z : f.z) ASSERT_FALSE(std::isnan(z));
    }
}

void expectNoLimitsHit(const RenderResult& r) {
    EXPECT_EQ(r.stats.counters.culledSplitLimit, 0u);
    EXPECT_EQ(r.stats.counters.culledEyeLimit, 0u);
    EXPECT_TRUE(r.warnings.empty()) << r.warnings.front();
}

// ---- Degenerate bodies ------------------------------------------------------------------------

TEST(Degenerate, ZeroAreaPatchesCoverNothing) {
    // Only the green background is ever hit (the oracle gives zero-area patches no layer): once
    // per sample, and no pixel shows red.
    test::CheckedCase c = test::checkHardCase("zero_area.rib");
    EXPECT_EQ(c.oracle.pixelsCovered, 48 * 48);
    for (int y = 0; y < 48; ++y)
        for (int x = 0; x < 48; ++x) {
            ASSERT_EQ(c.render.channel(0, x, y, 0), 0.0f) << x << "," << y;
            ASSERT_EQ(c.render.channel(0, x, y, 1), 1.0f) << x << "," << y;
        }
    EXPECT_LT(c.render.stats.counters.splits(), 100u);  // nothing is split without end
}

TEST(Degenerate, PoleAndCollapsedEdgesAreWatertight) {
    EXPECT_GT(test::checkHardCase("pole_fan.rib").oracle.pixelsCovered, 700);
}

TEST(Degenerate, NeedlesCoverExactlyTheSamplesInsideThem) {
    test::CheckedCase c = test::checkHardCase("needles.rib", 1e-5);
    // Each needle (30 px long, 1e-4 wide) is one column of micropolygons: nothing to split.
    EXPECT_EQ(c.render.stats.counters.splits(), 0u);
    // 1.2 square pixels at 64 samples per pixel: about 77 samples inside, many of them clear.
    EXPECT_GT(c.oracle.samplesCovered, 30u);
    EXPECT_LT(c.oracle.samplesCovered, 130u);
}

// Exact away from the fold; within one micropolygon of it, either way.
auto foldAware = [](const Scene& s) { return AwayFromFolds(s, 1.0); };

TEST(Degenerate, BowTieCoversItsTwoTrianglesOnce) {
    EXPECT_GT(test::checkHardCase("bowtie.rib", foldAware).oracle.pixelsCovered, 250);
}

TEST(Degenerate, QuadTurningInsideOutDuringTheShutter) {
    test::CheckedCase c = test::checkHardCase("inside_out.rib");
    EXPECT_GT(c.oracle.samplesCovered, 2000u);
    // Pixel columns near the centre are covered for most of the exposure, the outer ones briefly:
    // the time-averaged coverage of column x is the fraction of t in [0, 1] with
    // |x + 0.5 - 24| < 16 |1 - 2t|, within the stratification error.
    for (int x : {8, 16, 23, 30, 38}) {
        const double d = std::fabs(x + 0.5 - 24) / 16;
        EXPECT_NEAR(c.render.alpha(0, x, 12), 1 - d, 0.1) << x;
    }
}

TEST(Degenerate, QuadFoldingOverItselfDuringTheShutter) {
    EXPECT_GT(test::checkHardCase("fold.rib", foldAware).oracle.samplesCovered, 6000u);
}

}  // namespace
}  // namespace streyes

namespace streyes {
namespace {

// ---- The eye plane --------------------------------------------------------------------------------

TEST(EyePlane, WallMovingThroughTheEyePlaneDuringTheShutter) {
    const std::string path = "scenes/hard/eye_plane_moving.rib";
    Scene scene = loadScene(path);
    RenderResult r = test::renderFile(test::sourcePath(path));
    expectFinite(r);
    expectNoLimitsHit(r);
    EXPECT_GT(r.stats.counters.eyeSplits, 0u);
    EXPECT_LT(r.stats.counters.eyeSplits, 20000u);
    // The wall is at z(t) = -2 + 8t and fills the view whenever it lies beyond the near plane, so
    // a pixel's alpha is exactly the share of its samples taken after z reaches 0.1 (t = 0.2625),
    // and its Z the wall's depth at the earliest of them.
    const ResolvedSettings s = resolveSettings(scene, RenderOptions{});
    const int S = s.pattern.count();
    std::vector<SamplePosition> pos(static_cast<size_t>(S));
    const PatternTable table(s.pattern);
    int partly = 0;
    for (int y = 0; y < s.height; ++y)
        for (int x = 0; x < s.width; ++x) {
            table.pixelSamples(x, y, 0, pos.data());
            int seen = 0;
            double nearest = std::numeric_limits<double>::infinity();
            for (const SamplePosition& p : pos) {
                const double z = -2 + 8 * double(p.tf);
                ASSERT_GT(std::fabs(z - 0.1), 1e-5) << "a sample exactly at the near plane";
                if (z >= 0.1) ++seen, nearest = std::min(nearest, z);
            }
            EXPECT_EQ(r.alpha(0, x, y), float(seen) / float(S)) << x << "," << y;
            EXPECT_NEAR(r.z(0, x, y), nearest, 1e-4) << x << "," << y;
            partly += seen > 0 && seen < S;
        }
    EXPECT_EQ(partly, s.width * s.height);  // every pixel has samples on both sides of t = 0.2625
}

TEST(EyePlane, CameraInsideAClosedBox) {
    // Every sample sees exactly one face...
    test::CheckedCase c = test::checkHardCase("camera_inside_box.rib", [](const Scene&) {
        return [](double, double, double) { return 1; };
    });
    const Scene& scene = c.scene;
    const RenderResult& r = c.render;
    EXPECT_EQ(c.oracle.pixelsCovered, 32 * 32);
    EXPECT_GT(r.stats.counters.eyeSplits, 0u);  // the side faces reach behind the camera
    EXPECT_LT(r.stats.counters.eyeSplits, 20000u);
    // ... the one its eye ray (x, y, 1) leaves the box through: the axis of its largest component.
    // Colours from scenes/gen/hard.py, in the order of the faces.
    const Color colours[5] = {{1, 0.2f, 0.2f}, {0.2f, 1, 0.2f}, {0.2f, 0.2f, 1}, {1, 1, 0.2f}, {0.2f, 1, 1}};
    const Camera cam(scene.camera);
    auto faceOf = [&](double x, double y) {
        const double dx = (x - cam.bx()) / cam.ax(), dy = (y - cam.by()) / cam.ay();
        if (std::fabs(dx) <= 1 && std::fabs(dy) <= 1) return 0;
        if (std::fabs(dx) >= std::fabs(dy)) return dx > 0 ? 1 : 2;
        return dy > 0 ? 3 : 4;
    };
    const ResolvedSettings s = resolveSettings(scene, RenderOptions{});
    std::vector<SamplePosition> pos(static_cast<size_t>(s.pattern.count()));
    const PatternTable table(s.pattern);
    int checked = 0;
    for (int y = 0; y < s.height; ++y)
        for (int x = 0; x < s.width; ++x) {
            table.pixelSamples(x, y, 0, pos.data());
            const int face = faceOf(pos[0].x, pos[0].y);
            bool same = true;
            for (const SamplePosition& p : pos) same = same && faceOf(p.x, p.y) == face;
            if (!same) continue;
            ++checked;
            for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(r.channel(0, x, y, ch), colours[face][ch], 1e-6) << x << "," << y;
        }
    EXPECT_GT(checked, 800);
}

// ---- Recursion and overflow ---------------------------------------------------------------------

// The scene with only its last patch (the small square the hard cases put in front).
Scene lastPatchOnly(Scene scene) {
    scene.patches.erase(scene.patches.begin(), scene.patches.end() - 1);
    return scene;
}

TEST(SplitLimit, BodyThatNeverGetsSmallStopsWithOneWarning) {
    const std::string path = "scenes/hard/split_limit.rib";
    Scene scene = loadScene(path);
    RenderResult r = test::renderFile(test::sourcePath(path));
    expectFinite(r);
    EXPECT_GT(r.stats.counters.culledSplitLimit, 0u);
    ASSERT_EQ(r.warnings.size(), 1u);
    EXPECT_NE(r.warnings[0].find("split_limit.rib:15: warning: a body is still too large to dice after 60 splits"),
              std::string::npos)
        << r.warnings[0];
    // Bounded work: at most two pieces of each split overlap a bucket.
    EXPECT_LT(r.stats.counters.splits(), 4u * 60u * r.stats.counters.buckets + 100u);
    // Only the square is ever hit; the huge patch shows nowhere.
    Scene square = lastPatchOnly(scene);
    OracleReport rep = test::checkSamples(square, r, test::PatchLayers(square));
    EXPECT_GT(rep.pixelsCovered, 150);
    test::expectMatchesOracle(rep);
}

TEST(SplitLimit, PiecesThatNeverGetSmallStopAtTheSplitBudget) {
    // The depth limit alone would allow 2^60 pieces here; a small budget keeps the test quick.
    RenderOptions o;
    o.maxSplitsPerPrimitive = 1 << 14;
    RenderResult r = test::renderFile(test::sourcePath("scenes/hard/split_budget.rib"), o);
    expectFinite(r);
    const RenderCounters& n = r.stats.counters;
    EXPECT_GT(n.culledSplitLimit, 0u);
    EXPECT_LE(n.splits(), (uint64_t(o.maxSplitsPerPrimitive) + 100) * n.buckets);
    bool warned = false;
    for (const std::string& w : r.warnings)
        warned = warned || w.find("split_budget.rib:17: warning: geometry needed more than 16384 splits in one bucket") !=
                               std::string::npos;
    EXPECT_TRUE(warned) << ::testing::PrintToString(r.warnings);
    // The red square in front of it, x in [20.5, 27.5], y in [8.5, 15.5], is whole.
    for (int y = 9; y < 15; ++y)
        for (int x = 21; x < 27; ++x) {
            EXPECT_EQ(r.alpha(0, x, y), 1.0f) << x << "," << y;
            EXPECT_EQ(r.channel(0, x, y, 0), 1.0f) << x << "," << y;
            EXPECT_EQ(r.channel(0, x, y, 1), 0.0f) << x << "," << y;
        }
}

TEST(Overflow, CoordinatesBeyondFloatAreSkippedWithAWarning) {
    const std::string path = "scenes/hard/overflow.rib";
    Scene scene = loadScene(path);
    RenderResult r = test::renderFile(test::sourcePath(path));
    expectFinite(r);
    // Both overflowing patches are skipped; the warning is said once, naming the first.
    ASSERT_EQ(r.warnings.size(), 1u) << ::testing::PrintToString(r.warnings);
    EXPECT_NE(r.warnings[0].find("overflow.rib:15: warning: primitive reaches beyond 1e37 in camera space"),
              std::string::npos)
        << r.warnings[0];
    EXPECT_EQ(r.stats.counters.rootBodies, 1u);  // only the square is left
    Scene square = lastPatchOnly(scene);
    OracleReport rep = test::checkSamples(square, r, test::PatchLayers(square));
    EXPECT_GT(rep.pixelsCovered, 150);
    test::expectMatchesOracle(rep);
}

// A mesh whose every face overflows in camera space: one warning, not one per face (the log of a
// bad million-face mesh must not grow without bound).
TEST(Overflow, ABadMeshWarnsOnceNotPerFace) {
    std::string points, faces, counts;
    for (int i = 0; i < 200; ++i) {
        counts += "4 ";
        faces += std::to_string(4 * i) + " " + std::to_string(4 * i + 1) + " " + std::to_string(4 * i + 2) + " " +
                 std::to_string(4 * i + 3) + " ";
        const double x = i % 20, y = i / 20;
        points += std::to_string(x) + " " + std::to_string(y) + " 5  " + std::to_string(x + 1) + " " +
                  std::to_string(y) + " 5  " + std::to_string(x + 1) + " " + std::to_string(y + 1) + " 5  " +
                  std::to_string(x) + " " + std::to_string(y + 1) + " 5  ";
    }
    const std::string rib = test::orthoHeader(32, 32) + "AttributeBegin\nTranslate 1e300 0 0\nPointsPolygons [" +
                            counts + "] [" + faces + "] \"P\" [" + points + "]\nAttributeEnd\n" +
                            "Patch \"bilinear\" \"P\" [0 0 5  1 0 5  0 1 5  1 1 5]\nSphere 2 -2 2 360\nWorldEnd\n";
    RenderResult r = test::renderRib(rib);
    ASSERT_EQ(r.warnings.size(), 1u) << ::testing::PrintToString(r.warnings);
    EXPECT_NE(r.warnings[0].find("primitive reaches beyond 1e37 in camera space"), std::string::npos) << r.warnings[0];
    EXPECT_EQ(r.stats.counters.rootBodies, 2u);  // the patch and the sphere's one face
}

}  // namespace
}  // namespace streyes
