// Point-based occlusion and colour bleeding (point_based_buffer.h, point_based_tree.h) against
// closed forms: a disc overhead and a half-open box over a point of a plane give Lambert's form
// factor within the microbuffer's resolution error, counted pixel by pixel (the weight of the
// pixels the outline may cross); a plane of one colour gives that colour times its coverage;
// an empty cloud gives 0 (and under an environment map, the map); a disc under a map mixes the
// two by its form factor; and the render's store gives the same bits whatever the threads.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstring>
#include <fstream>
#include <functional>
#include <iterator>
#include <thread>

#include "shade/point_based_buffer.h"
#include "shade/point_clouds.h"
#include "streyes/error.h"
#include "form_factor_util.h"
#include "test_util.h"

namespace streyes {
namespace {

using Vec = std::array<double, 3>;

// Discs with "_area" and "_radiosity" (the channels bake3d's users write), in name order.
struct CloudMaker {
    std::vector<float> data;
    void disc(const Vec& p, const Vec& n, double radius, double area, const Vec& colour) {
        const float rec[] = {float(p[0]), float(p[1]), float(p[2]), float(n[0]), float(n[1]), float(n[2]), float(radius),
                             float(area), float(colour[0]), float(colour[1]), float(colour[2])};
        data.insert(data.end(), std::begin(rec), std::end(rec));
    }
    // The parallelogram corner + [0,1] eu + [0,1] ev as cells x cells micropolygons, each a disc
    // at its centre with the cell's area and the radius that covers it (half its diagonal), facing n.
    void rect(const Vec& corner, const Vec& eu, const Vec& ev, int cu, int cv, const Vec& n, const Vec& colour) {
        const double du = std::sqrt(eu[0] * eu[0] + eu[1] * eu[1] + eu[2] * eu[2]) / cu;
        const double dv = std::sqrt(ev[0] * ev[0] + ev[1] * ev[1] + ev[2] * ev[2]) / cv;
        for (int j = 0; j < cv; ++j)
            for (int i = 0; i < cu; ++i) {
                Vec p;
                for (int c = 0; c < 3; ++c) p[c] = corner[c] + (i + 0.5) / cu * eu[c] + (j + 0.5) / cv * ev[c];
                disc(p, n, 0.5 * std::sqrt(du * du + dv * dv), du * dv, colour);
            }
    }
    BakedPointCloud cloud() const { return BakedPointCloud({{"_area", 1}, {"_radiosity", 3}}, data); }
};

double formFactor(const Vec& p, const std::vector<Vec>& poly) { return test::lambertFormFactor(p, poly); }

// Does the ray from p along d meet the rectangle corner + [0,1] eu + [0,1] ev?
bool hitsRect(const Vec& p, const Vec& d, const Vec& corner, const Vec& eu, const Vec& ev) {
    const Vec n = {eu[1] * ev[2] - eu[2] * ev[1], eu[2] * ev[0] - eu[0] * ev[2], eu[0] * ev[1] - eu[1] * ev[0]};
    const double dn = d[0] * n[0] + d[1] * n[1] + d[2] * n[2];
    if (dn == 0) return false;
    const double t = ((corner[0] - p[0]) * n[0] + (corner[1] - p[1]) * n[1] + (corner[2] - p[2]) * n[2]) / dn;
    if (t <= 0) return false;
    const Vec h = {p[0] + t * d[0] - corner[0], p[1] + t * d[1] - corner[1], p[2] + t * d[2] - corner[2]};
    const double u = (h[0] * eu[0] + h[1] * eu[1] + h[2] * eu[2]) / (eu[0] * eu[0] + eu[1] * eu[1] + eu[2] * eu[2]);
    const double v = (h[0] * ev[0] + h[1] * ev[1] + h[2] * ev[2]) / (ev[0] * ev[0] + ev[1] * ev[1] + ev[2] * ev[2]);
    return u >= 0 && u <= 1 && v >= 0 && v <= 1;
}

// The microbuffer's resolution error for a shape between `inner` and `outer` (directions from
// the point: inside the shape for sure, and possibly): the weight share of the pixels of the
// hemisphere about +z that are not wholly inside `inner` nor wholly outside `outer`, judged at
// 5 x 5 directions across each pixel. A pixel-centre estimate of the shape's coverage lies
// within this of the exact one (the shape being anything between the two).
double outlineWeight(CubeMicrobuffer& b, const std::function<bool(const Vec&)>& inner,
                     const std::function<bool(const Vec&)>& outer) {
    const int res = b.resolution();
    double all = 0, unsure = 0;
    for (int f = 0; f < 6; ++f)
        for (int iv = 0; iv < res; ++iv)
            for (int iu = 0; iu < res; ++iu) {
                const float* d = b.direction(f, iu, iv);
                if (!(d[2] > 0)) continue;
                const double w = d[2] * b.solidAngle(f, iu, iv);
                all += w;
                bool allIn = true, anyOut = false;
                for (int j = 0; j < 5; ++j)
                    for (int i = 0; i < 5; ++i) {
                        const double u = -1 + (iu + i / 4.0) * 2 / res, v = -1 + (iv + j / 4.0) * 2 / res;
                        Vec dir;
                        const int a = CubeMicrobuffer::axis(f);
                        dir[size_t(a)] = CubeMicrobuffer::side(f);
                        dir[size_t((a + 1) % 3)] = u;
                        dir[size_t((a + 2) % 3)] = v;
                        allIn = allIn && inner(dir);
                        anyOut = anyOut || outer(dir);
                    }
                if (!allIn && anyOut) unsure += w;
            }
    return unsure / all;
}

const Vec kUp = {0, 0, 1};

TEST(PointBased, DiscOverheadIsItsFormFactorWithinTheMicrobufferError) {
    // A disc of radius R at height h over the point, facing it: sin^2 of its half-angle.
    const double R = 0.8, h = 1.0, exact = R * R / (R * R + h * h);
    CloudMaker m;
    m.disc({0, 0, h}, {0, 0, -1}, R, M_PI * R * R, {1, 1, 1});
    const DiscHierarchy tree(m.cloud());
    auto inDisc = [&](const Vec& d) { return d[2] > 0 && (d[0] * d[0] + d[1] * d[1]) * h * h < R * R * d[2] * d[2]; };
    double lastError = 1, lastBound = 1;
    for (int res : {8, 16, 32, 64}) {
        CubeMicrobuffer b;
        PointBasedSettings s;
        s.res = res;
        const float P[3] = {0, 0, 0}, N[3] = {0, 0, 1};
        float occ = -1, colour[3];
        b.integrate(tree, P, N, s, &occ, colour);
        const double bound = outlineWeight(b, inDisc, inDisc);
        EXPECT_LE(std::fabs(occ - exact), bound) << "res " << res << ": " << occ << " against " << exact;
        // The bound is the outline's pixels: ~ L / (2 res) for an outline of angular length
        // L = 2 pi sin(theta) (point_based_buffer.h); it halves as res doubles. Measured: bound
        // 0.186, 0.096, 0.047, 0.024 at res 8 to 64; error 0.0042, 0.0099, 0.0040, 0.0004.
        EXPECT_LT(bound, 2 * M_PI * std::sqrt(exact) / (2 * res)) << res;
        EXPECT_LT(bound, lastBound) << res;
        EXPECT_NEAR(colour[0], occ, 1e-6);  // white: the colour seen is the coverage
        lastBound = bound;
        lastError = std::fabs(occ - exact);
    }
    EXPECT_LT(lastError, 0.01);
}

// The box over the plane z = 0 of half-open-box tests: a roof at z = 1 over x in [-1, 1],
// y in [-2, 2], walls at x = -1 and x = 1 down to the plane; open at y = -2 and y = 2.
struct HalfOpenBox {
    double grow = 0;  // every face this much larger in its plane (and the walls taller)
    Vec roofCorner() const { return {-1 - grow, -2 - grow, 1}; }
    Vec roofU() const { return {2 + 2 * grow, 0, 0}; }
    Vec roofV() const { return {0, 4 + 2 * grow, 0}; }
    Vec wallCorner(int side) const { return {double(side), -2 - grow, 0}; }
    Vec wallU() const { return {0, 4 + 2 * grow, 0}; }
    Vec wallV() const { return {0, 0, 1 + grow}; }
    bool hit(const Vec& p, const Vec& d) const {
        return hitsRect(p, d, roofCorner(), roofU(), roofV()) || hitsRect(p, d, wallCorner(-1), wallU(), wallV()) ||
               hitsRect(p, d, wallCorner(1), wallU(), wallV());
    }
    double formFactorFrom(const Vec& p) const {
        const Vec rc = roofCorner(), ru = roofU(), rv = roofV();
        auto quad = [](const Vec& c, const Vec& u, const Vec& v) {
            return std::vector<Vec>{c, {c[0] + u[0], c[1] + u[1], c[2] + u[2]},
                                    {c[0] + u[0] + v[0], c[1] + u[1] + v[1], c[2] + u[2] + v[2]}, {c[0] + v[0], c[1] + v[1], c[2] + v[2]}};
        };
        return formFactor(p, quad(rc, ru, rv)) + formFactor(p, quad(wallCorner(-1), wallU(), wallV())) +
               formFactor(p, quad(wallCorner(1), wallU(), wallV()));
    }
};

// Discs of cell size 1/20 facing into the box; with `floor`, the plane's own discs too.
BakedPointCloud boxCloud(bool floor) {
    CloudMaker m;
    const HalfOpenBox box;
    m.rect(box.roofCorner(), box.roofU(), box.roofV(), 40, 80, {0, 0, -1}, {1, 1, 1});
    m.rect(box.wallCorner(-1), box.wallU(), box.wallV(), 80, 20, {1, 0, 0}, {1, 1, 1});
    m.rect(box.wallCorner(1), box.wallU(), box.wallV(), 80, 20, {-1, 0, 0}, {1, 1, 1});
    if (floor) m.rect({-1, -2, 0}, {2, 0, 0}, {0, 4, 0}, 40, 80, kUp, {1, 1, 1});
    return m.cloud();
}

const Vec kBoxPoints[] = {{0, 0, 0}, {0.5, 1.2, 0}, {-0.9, -0.5, 0}, {0.2, 1.9, 0}};

TEST(PointBased, HalfOpenBoxIsTheFormFactorWithinTheMicrobufferError) {
    // Every disc drawn exactly (maxsolidangle far below any disc's): the union of the discs lies
    // between the box and the box grown by the discs' overhang (radius - half a cell), so the
    // result lies within the two form factors, widened by the pixels in between.
    const DiscHierarchy tree(boxCloud(false));
    const double overhang = 0.5 * std::sqrt(2.0) / 20 - 0.5 / 20;
    HalfOpenBox box, grown;
    grown.grow = overhang;
    for (int res : {10, 24}) {
        for (const Vec& p : kBoxPoints) {
            CubeMicrobuffer b;
            PointBasedSettings s;
            s.res = res;
            s.maxSolidAngle = 1e-6f;
            const float P[3] = {float(p[0]), float(p[1]), float(p[2])}, N[3] = {0, 0, 1};
            float occ = -1;
            b.integrate(tree, P, N, s, &occ, nullptr);
            const double lo = box.formFactorFrom(p), hi = grown.formFactorFrom(p);
            const double bound = outlineWeight(b, [&](const Vec& d) { return box.hit(p, d); },
                                               [&](const Vec& d) { return grown.hit(p, d); });
            EXPECT_GE(occ, lo - bound) << "res " << res << " at " << p[0] << " " << p[1];
            EXPECT_LE(occ, hi + bound) << "res " << res << " at " << p[0] << " " << p[1];
            EXPECT_GT(lo, 0.4);  // the box covers much of the sky: a dropped face would show
            if (res == 24) {
                EXPECT_LT(bound + hi - lo, 0.12) << "the bound says something";
            }
        }
    }
}

TEST(PointBased, ClustersStayNearTheExactAnswerAndThePlanesOwnDiscsHideNothing) {
    const DiscHierarchy tree(boxCloud(false)), withFloor(boxCloud(true));
    for (const Vec& p : kBoxPoints) {
        CubeMicrobuffer b;
        PointBasedSettings exact, clustered;  // clustered: the defaults, Aqsis's (res 10, 0.03 sr)
        exact.maxSolidAngle = 1e-6f;
        const float P[3] = {float(p[0]), float(p[1]), float(p[2])}, N[3] = {0, 0, 1};
        float a = -1, c = -1, f = -1, fc = -1;
        b.integrate(tree, P, N, exact, &a, nullptr);
        b.integrate(tree, P, N, clustered, &c, nullptr);
        b.integrate(withFloor, P, N, exact, &f, nullptr);
        b.integrate(withFloor, P, N, clustered, &fc, nullptr);
        // Christensen's approximation: a cluster is drawn as one disc of its area.
        EXPECT_NEAR(c, a, 0.03) << p[0] << " " << p[1];
        // The floor's discs are edge on to its points (or behind them): drawn one by one they add
        // nothing; in clusters they move the clusters' discs a little.
        EXPECT_EQ(f, a) << p[0] << " " << p[1];
        EXPECT_NEAR(fc, a, 0.03) << p[0] << " " << p[1];
    }
}

TEST(PointBased, PlaneOfOneColourGivesThatColourTimesItsCoverage) {
    // A plane 40 x 40 at height 1 (coverage: its form factor, 0.9988 at the centre) of one colour.
    CloudMaker m;
    const Vec colour = {0.2, 0.5, 0.9};
    m.rect({-20, -20, 1}, {40, 0, 0}, {0, 40, 0}, 160, 160, {0, 0, -1}, colour);
    const DiscHierarchy tree(m.cloud());
    for (const Vec& p : {Vec{0, 0, 0}, Vec{3, -7, 0}, Vec{15, 15, 0}}) {
        CubeMicrobuffer b;
        PointBasedSettings s;
        const float P[3] = {float(p[0]), float(p[1]), float(p[2])}, N[3] = {0, 0, 1};
        float occ = -1, got[3];
        b.integrate(tree, P, N, s, &occ, got);
        const double ff = formFactor(p, {{-20, -20, 1}, {20, -20, 1}, {20, 20, 1}, {-20, 20, 1}});
        EXPECT_NEAR(occ, ff, 0.03) << p[0] << " " << p[1];
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], colour[size_t(c)] * occ, 1e-5) << c;
    }
}

TEST(PointBased, EmptyCloudAndDiscsBehindGiveZero) {
    CubeMicrobuffer b;
    PointBasedSettings s;
    const float P[3] = {0, 0, 0}, N[3] = {0, 0, 1};
    float occ = -1, colour[3] = {-1, -1, -1};
    const DiscHierarchy empty{BakedPointCloud({{"_area", 1}, {"_radiosity", 3}}, {})};
    EXPECT_TRUE(empty.empty());
    b.integrate(empty, P, N, s, &occ, colour);
    EXPECT_EQ(occ, 0.0f);
    EXPECT_EQ(colour[0], 0.0f);
    // Discs seen from behind (facing away), and discs below the horizon: nothing.
    CloudMaker m;
    m.rect({-5, -5, 1}, {10, 0, 0}, {0, 10, 0}, 20, 20, kUp, {1, 1, 1});
    m.rect({-5, -5, -1}, {10, 0, 0}, {0, 10, 0}, 20, 20, kUp, {1, 1, 1});
    b.integrate(DiscHierarchy(m.cloud()), P, N, s, &occ, colour);
    EXPECT_EQ(occ, 0.0f);
    // The same discs facing the point: covered.
    CloudMaker facing;
    facing.rect({-5, -5, 1}, {10, 0, 0}, {0, 10, 0}, 20, 20, {0, 0, -1}, {1, 1, 1});
    b.integrate(DiscHierarchy(facing.cloud()), P, N, s, &occ, colour);
    EXPECT_GT(occ, 0.9f);
}

// "environmentmap" on the point-based path: what no disc covers sees the map (one RGB a pixel,
// as the shading op looks it up). A cloud of nothing under a constant map gives the map's colour;
// a disc overhead gives its radiosity over its form factor and the map over the rest; the
// occlusion is the same bits with or without colour and map; the environment alone ("environmentcolor")
// is the map times the uncovered share.
std::vector<float> constantEnvironment(const CubeMicrobuffer& b, const Vec& c) {
    std::vector<float> env(size_t(b.pixels()) * 3);
    for (size_t i = 0; i < env.size(); ++i) env[i] = float(c[i % 3]);
    return env;
}

TEST(PointBased, NothingUnderAConstantEnvironmentIsItsColour) {
    const Vec sky = {0.2, 0.5, 0.9};
    const DiscHierarchy empty{BakedPointCloud({{"_area", 1}, {"_radiosity", 3}}, {})};
    CloudMaker far;  // a small disc below the horizon: drawn nowhere in the cone
    far.disc({0, 0, -3}, {0, 0, 1}, 0.1, 0.0314, {1, 1, 1});
    const DiscHierarchy below(far.cloud());
    for (int res : {4, 10, 33}) {
        CubeMicrobuffer b;
        b.setResolution(res);
        const std::vector<float> env = constantEnvironment(b, sky);
        PointBasedSettings s;
        s.res = res;
        for (const DiscHierarchy* tree : {&empty, &below})
            for (const Vec& n : {Vec{0, 0, 1}, Vec{0.6, 0, 0.8}}) {
                const float P[3] = {0, 0, 0}, N[3] = {float(n[0]), float(n[1]), float(n[2])};
                float occ = -1, colour[3] = {-1, -1, -1}, seen[3] = {-1, -1, -1};
                b.integrate(*tree, P, N, s, &occ, colour, env.data());
                EXPECT_EQ(occ, 0.0f);
                for (int c = 0; c < 3; ++c) EXPECT_NEAR(colour[c], sky[size_t(c)], 1e-6) << res << " " << c;
                b.integrate(*tree, P, N, s, &occ, nullptr, env.data(), seen);
                for (int c = 0; c < 3; ++c) EXPECT_NEAR(seen[c], sky[size_t(c)], 1e-6) << res << " " << c;
            }
    }
}

TEST(PointBased, DiscOverheadUnderAnEnvironmentMixesByItsFormFactor) {
    // A disc of radius R at height h of radiosity r under a constant sky e: r F + e (1 - F),
    // F = R^2 / (R^2 + h^2), within the microbuffer's error |r - e| times the outline's weight.
    const double R = 0.8, h = 1.0, F = R * R / (R * R + h * h);
    const Vec disc = {0.9, 0.6, 0.1}, sky = {0.2, 0.5, 0.9};
    CloudMaker m;
    m.disc({0, 0, h}, {0, 0, -1}, R, M_PI * R * R, disc);
    const DiscHierarchy tree(m.cloud());
    auto inDisc = [&](const Vec& d) { return d[2] > 0 && (d[0] * d[0] + d[1] * d[1]) * h * h < R * R * d[2] * d[2]; };
    for (int res : {8, 16, 32}) {
        CubeMicrobuffer b;
        b.setResolution(res);
        const std::vector<float> env = constantEnvironment(b, sky);
        PointBasedSettings s;
        s.res = res;
        const float P[3] = {0, 0, 0}, N[3] = {0, 0, 1};
        float occ = -1, occPlain = -1, colour[3], plain[3], seen[3];
        b.integrate(tree, P, N, s, &occ, colour, env.data());
        b.integrate(tree, P, N, s, &occPlain, plain);
        const double bound = outlineWeight(b, inDisc, inDisc);
        float occOnly = -1;
        b.integrate(tree, P, N, s, &occOnly, nullptr, env.data(), seen);
        // One drawing, three integrals: the occlusion is the same bits whatever else is asked.
        EXPECT_EQ(occ, occPlain) << res;
        EXPECT_EQ(occ, occOnly) << res;
        for (int c = 0; c < 3; ++c) {
            const double want = disc[size_t(c)] * F + sky[size_t(c)] * (1 - F);
            EXPECT_LE(std::fabs(colour[c] - want), bound * std::fabs(disc[size_t(c)] - sky[size_t(c)]) + 1e-6)
                << "res " << res << " channel " << c << ": " << colour[c] << " against " << want;
            // The map fills exactly what the discs leave: colour = discs' + sky (1 - occlusion).
            EXPECT_NEAR(colour[c], plain[c] + sky[size_t(c)] * (1 - occ), 1e-6) << res << " " << c;
            EXPECT_NEAR(seen[c], sky[size_t(c)] * (1 - occ), 1e-6) << res << " " << c;
        }
        EXPECT_GT(std::fabs(colour[0] - plain[0]), 0.05f);  // the map is there
    }
}

// The render's store: a cloud file read once, its hierarchy shared; the same bits whatever the
// number of threads asking; a missing or truncated cloud is an error the caller warns about.
TEST(PointBased, StoreGivesTheSameBitsWhateverTheThreads) {
    test::TempDir dir("pointbased");
    const std::string file = dir.path() + "/box.ptc";
    std::string error;
    ASSERT_TRUE(boxCloud(true).write(file, &error)) << error;
    constexpr int n = 512;
    std::vector<float> px(n), py(n), pz(n, 0.0f), nx(n, 0.0f), ny(n, 0.0f), nz(n, 1.0f);
    for (int i = 0; i < n; ++i) px[size_t(i)] = -0.99f + 1.98f * float(i % 32) / 31, py[size_t(i)] = -1.99f + 3.98f * float(i / 32) / 15;
    auto run = [&](int threads, bool indirect) {
        Log log;
        PointClouds clouds(log);
        std::vector<float> out(size_t(n) * 4, -1.0f);
        std::vector<std::thread> pool;
        const int per = n / threads;
        for (int t = 0; t < threads; ++t)
            pool.emplace_back([&, t] {
                const size_t at = size_t(t * per);
                sl::PointBasedQuery q;
                q.n = per;
                q.indirect = indirect;
                const float* P[3] = {px.data() + at, py.data() + at, pz.data() + at};
                const float* N[3] = {nx.data() + at, ny.data() + at, nz.data() + at};
                for (int c = 0; c < 3; ++c) q.P[c] = P[c], q.N[c] = N[c];
                float* o[4] = {out.data() + at, out.data() + n + at, out.data() + 2 * n + at, out.data() + 3 * n + at};
                q.out = o;
                std::string e;
                EXPECT_TRUE(clouds.pointBased(file, q, &e)) << e;
            });
        for (std::thread& th : pool) th.join();
        return out;
    };
    const std::vector<float> one = run(1, true), four = run(4, true), occlusionOnly = run(4, false);
    ASSERT_EQ(std::memcmp(one.data(), four.data(), sizeof(float) * one.size()), 0);
    ASSERT_EQ(std::memcmp(one.data(), occlusionOnly.data(), sizeof(float) * n), 0);
    for (int i = 0; i < n; ++i) {
        EXPECT_GT(one[size_t(i)], 0.3f) << i;  // under the box
        EXPECT_EQ(one[size_t(n + i)], one[size_t(i)]) << i;  // white
    }

    Log log;
    PointClouds clouds(log);
    sl::PointBasedQuery q;
    float o0 = 0, *o[4] = {&o0, &o0, &o0, &o0};
    const float zero = 0, up = 1;
    q.n = 1;
    for (int c = 0; c < 3; ++c) q.P[c] = &zero, q.N[c] = c == 2 ? &up : &zero;
    q.out = o;
    std::string e;
    EXPECT_FALSE(clouds.pointBased(dir.path() + "/missing.ptc", q, &e));
    EXPECT_NE(e.find("missing.ptc"), std::string::npos) << e;
    const std::string bytes = [&] {
        std::ifstream f(file, std::ios::binary);
        return std::string((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
    }();
    {
        std::ofstream f(dir.path() + "/short.ptc", std::ios::binary);
        f.write(bytes.data(), std::streamsize(bytes.size() - 5));
    }
    e.clear();
    EXPECT_FALSE(clouds.pointBased(dir.path() + "/short.ptc", q, &e));
    EXPECT_NE(e.find("truncated"), std::string::npos) << e;
    // A cloud without "_radiosity": occlusion yes, indirect diffuse no.
    ASSERT_TRUE(BakedPointCloud({}, {0, 0, 1, 0, 0, -1, 0.5f}).write(dir.path() + "/plain.ptc", &error)) << error;
    EXPECT_TRUE(clouds.pointBased(dir.path() + "/plain.ptc", q, &e)) << e;
    EXPECT_GT(o0, 0.0f);
    q.indirect = true;
    EXPECT_FALSE(clouds.pointBased(dir.path() + "/plain.ptc", q, &e));
    EXPECT_NE(e.find("_radiosity"), std::string::npos) << e;
}

}  // namespace
}  // namespace streyes
