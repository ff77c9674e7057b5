// Watertightness of closed surfaces under spacetime subdivision (scenes/hard/*_spin*.rib).
//
// A closed convex object (a cube of six bilinear patches, a sphere of latitude-longitude patches)
// spins over 64 frames. Its faces are split to different depths and diced at different rates, so
// shared edges carry T-junctions, and with motion blur each grid is sampled per time slice. The
// answer is analytic because the object is convex at every instant (linear interpolation of the
// transform is a linear map, which keeps a convex polyhedron convex): an eye ray at time t meets
// it when it passes every face plane. The sample oracle (sample_oracle.h) then checks that no
// sample inside the silhouette sees the background (no cracks), none outside sees the object, and
// that every sample inside is hit exactly twice, by a front and a back face (a crack in a front
// face hidden by the back face gives one hit; a double hit on a shared edge three).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "sample_oracle.h"
#include "streyes/rib.h"

namespace streyes {
namespace {

struct Plane {
    Vec3d n;
    double c;  // inside: dot(n, p) <= c
};

// The object of a watertightness scene: its object-space corners and faces, and its motion.
class SpinningObject {
  public:
    explicit SpinningObject(const Scene& scene) : camera_(scene.camera) {
        objectToCamera_ = scene.patches.front().objectToWorld.then(scene.camera.worldToCamera);
        Vec3d centre{0, 0, 0};
        for (const BilinearPatchDesc& p : scene.patches)
            for (const Vec3d& c : p.P[0]) {
                corners_.push_back(c);
                centre = centre + c;
            }
        centre = centre * (1.0 / double(corners_.size()));
        // One plane per patch (they are planar), facing away from the centre.
        for (const BilinearPatchDesc& p : scene.patches) {
            const auto& c = p.P[0];
            Vec3d n = cross(c[3] - c[0], c[2] - c[1]);
            if (length(n) == 0) continue;
            n = normalize(n);
            double d = dot(n, c[0]);
            if (dot(n, centre) > d) n = -n, d = -d;
            planes_.push_back({n, d});
        }
        // Bounding spheres about the centre, so that most rays are decided without the planes.
        inner_ = 1e30;
        for (Plane& pl : planes_) inner_ = std::min(inner_, pl.c - dot(pl.n, centre));
        for (const Vec3d& c : corners_) outer_ = std::max(outer_, length(c - centre));
        centre_ = centre;
    }

    Matrix4 at(double t) const { return objectToCamera_.at(t); }

    // Does the eye ray through raster (x, y) meet the object at time t? Clipped against the
    // object-space planes. `inverse` is the inverse of at(t).
    bool hits(const Matrix4& inverse, double x, double y) const {
        Vec3d o, v;
        eyeRay(inverse, x, y, &o, &v);
        return hitsRay(o, v);
    }

    void eyeRay(const Matrix4& inverse, double x, double y, Vec3d* o, Vec3d* v) const {
        Vec3d d{(x - camera_.bx()) / camera_.ax(), (y - camera_.by()) / camera_.ay(), 1.0};
        *o = inverse.point({0, 0, 0});
        *v = inverse.vector(d);
    }

    // Depth of field: the ray from lens point R (lu, lv) through the point of the focal plane
    // z = d that the pinhole sees at (x, y).
    bool hitsThroughLens(const Matrix4& inverse, double x, double y, double lu, double lv) const {
        const double R = lensRadius_, d = focalDistance_;
        const Vec3d focal{d * (x - camera_.bx()) / camera_.ax(), d * (y - camera_.by()) / camera_.ay(), d};
        const Vec3d lens{R * lu, R * lv, 0};
        return hitsRay(inverse.point(lens), inverse.vector(focal - lens));
    }
    void setLens(double radius, double focalDistance) {
        lensRadius_ = radius;
        focalDistance_ = focalDistance;
    }

    bool hitsRay(Vec3d o, Vec3d v) const {
        const double dist = length(cross(centre_ - o, v)) / length(v);  // of the ray from the centre
        if (dist > outer_) return false;
        if (dist < inner_) return true;
        double t0 = 0, t1 = 1e30;
        for (const Plane& pl : planes_) {
            double den = dot(pl.n, v), num = pl.c - dot(pl.n, o);
            if (den == 0) {
                if (num < 0) return false;
            } else if (den > 0) {
                t1 = std::min(t1, num / den);
            } else {
                t0 = std::max(t0, num / den);
            }
            if (t0 >= t1) return false;
        }
        return true;
    }

  private:
    Camera camera_;
    MotionTransform objectToCamera_;
    std::vector<Vec3d> corners_;
    std::vector<Plane> planes_;
    Vec3d centre_;
    double inner_ = 0, outer_ = 0;
    double lensRadius_ = 0, focalDistance_ = 1;
};

// Rendered without occlusion culling, every surface over a sample is sampled: the hit count
// sees cracks and double hits. With culling (the default), back faces are culled where front
// faces cover them: the pixels must still show no crack.
void expectWatertight(const std::string& scenePath) {
    Log log;
    Scene scene = parseRibFile(test::sourcePath(scenePath), log);
    SpinningObject object(scene);
    double cachedTime = -1e30;
    Matrix4 inverse;
    auto layers = [&](double x, double y, double t) {
        if (t != cachedTime) {
            invert(object.at(t), &inverse);
            cachedTime = t;
        }
        return object.hits(inverse, x, y) ? 2 : 0;  // a front and a back face
    };
    RenderOptions everyLayer;
    everyLayer.algorithm = Algorithm::Spacetime;
    test::RenderResult r = test::renderFile(test::sourcePath(scenePath), everyLayer);
    ASSERT_EQ(r.frames.size(), 64u);
    test::OracleReport rep = test::checkSamples(scene, r, layers);
    EXPECT_GT(rep.pixelsCovered, 40000);  // the checks are not vacuous
    EXPECT_GT(rep.pixelsUncovered, 100000);
    test::expectMatchesOracle(rep);

    RenderOptions culled;
    ASSERT_TRUE(usesOcclusion(culled.algorithm));
    test::OracleReport withCulling = test::recheckPixels(rep, test::renderFile(test::sourcePath(scenePath), culled));
    EXPECT_EQ(withCulling.crackedPixels, 0);
    EXPECT_EQ(withCulling.strayPixels, 0);
    EXPECT_LT(withCulling.hits, rep.hits);  // back faces were culled
}

TEST(Watertight, SpinningCube) { expectWatertight("scenes/hard/cube_spin.rib"); }
TEST(Watertight, SpinningCubeFastOneSlice) { expectWatertight("scenes/hard/cube_spin_fast.rib"); }
TEST(Watertight, SpinningSphere) { expectWatertight("scenes/hard/sphere_spin.rib"); }

// With depth of field every sample sees the cube through its own lens point: vertices shifted per
// vertex keep shared edges shared, so still no cracks and no double hits, against rays from the
// lens points computed here. Focused in front of the cube so its silhouette blurs by some pixels.
TEST(Watertight, SpinningCubeThroughALens) {
    Log log;
    Scene scene = parseRibFile(test::sourcePath("scenes/hard/cube_spin.rib"), log);
    scene.camera.fstop = 2;
    scene.camera.focalLength = 1;
    scene.camera.focalDistance = 4;
    SpinningObject object(scene);
    object.setLens(1.0 / 4, 4);
    double cachedTime = -1e30;
    Matrix4 inverse;
    auto layers = [&](double x, double y, double t, double lu, double lv) {
        if (t != cachedTime) {
            invert(object.at(t), &inverse);
            cachedTime = t;
        }
        return object.hitsThroughLens(inverse, x, y, lu, lv) ? 2 : 0;
    };
    RenderOptions o;
    o.algorithm = Algorithm::Spacetime;
    o.hasFrames = true;
    o.firstFrame = 1;
    o.lastFrame = 8;
    test::RenderResult r = test::renderScene(scene, o);
    ASSERT_EQ(r.frames.size(), 8u);
    test::OracleReport rep = test::checkSamples(scene, r, layers);
    EXPECT_GT(rep.pixelsCovered, 2000);  // the checks are not vacuous
    EXPECT_GT(rep.pixelsUncovered, 10000);
    test::expectMatchesOracle(rep);
    // The blur is there: a pinhole render differs.
    Scene pinhole = scene;
    pinhole.camera.fstop = std::numeric_limits<double>::infinity();
    EXPECT_FALSE(test::identicalPixels(r, test::renderScene(pinhole, o)));
}

}  // namespace
}  // namespace streyes
