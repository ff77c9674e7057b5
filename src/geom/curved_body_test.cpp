// CurvedBody over patch meshes and quadrics: bounds hold what is diced, neighbouring pieces put
// the same bits on their common edges however deeply each was split and at whatever rate it was
// diced, and closed surfaces dice into watertight meshes.
#include "geom/curved_body.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <random>

#include "geom/grid.h"
#include "geom/nurbs_mesh.h"
#include "geom/patch_mesh.h"
#include "geom/quadric.h"
#include "shade/shading.h"
#include "test_util.h"
#include "geom/subdivision.h"

namespace streyes {
namespace {

struct Fixture {
    Camera camera = test::pixelCamera(128);
    Material material;
    std::vector<std::unique_ptr<SurfaceMesh>> meshes;

    // A patch mesh from a description (camera space = object space), still or moving by `shift`.
    const SurfaceMesh* patchMesh(const PatchMeshDesc& d, Vec3d shift = {}) {
        PatchMeshShape shape(d);
        std::vector<Vec3d> moved = d.P[0];
        for (Vec3d& p : moved) p += shift;
        std::vector<BezierPatch> k1;
        if (shift != Vec3d{}) k1 = shape.patches(moved);
        meshes.push_back(std::make_unique<BezierMesh>(shape.topology(), TimeSpan{0, 1}, &material, &camera,
                                                      shape.patches(d.P[0]), k1,
                                                      shape.colors(d.Cs, Color{1, 1, 1})));
        meshes.back()->setShadingRate(material.shadingRate);
        return meshes.back().get();
    }
    // A cube with one corner pulled out and a semi-sharp crease, moved by `shift` at key 1.
    const SurfaceMesh* subdivisionCube(Vec3d shift = {}) {
        SubdivisionMeshDesc d;
        d.faceSizes = {4, 4, 4, 4, 4, 4};
        d.faceVertices = {0, 1, 3, 2, 2, 3, 5, 4, 4, 5, 7, 6, 6, 7, 1, 0, 1, 7, 5, 3, 6, 0, 2, 4};
        d.vertexCount = 8;
        d.P = {{{-1, -1, 1}, {1, -1, 1}, {-1, 1, 1}, {2.4, 1.8, 1.6}, {-1, 1, -1}, {1, 1, -1}, {-1, -1, -1}, {1, -1, -1}}};
        for (Vec3d& p : d.P[0]) p = p * 25.0 + Vec3d{64, 64, 100};
        d.creaseEdges = {1, 3};
        d.creaseSharpness = {1.5f};
        auto shape = std::make_shared<SubdivisionShape>(d);
        std::vector<Vec3d> moved = d.P[0];
        for (Vec3d& p : moved) p += shift;
        auto k0 = shape->key(d.P[0]), k1 = shift == Vec3d{} ? k0 : shape->key(moved);
        meshes.push_back(std::make_unique<SubdivisionMesh>(shape, k0, k1, TimeSpan{0, 1}, &material, &camera,
                                                           shape->colors({}, Color{1, 1, 1})));
        meshes.back()->setShadingRate(material.shadingRate);
        return meshes.back().get();
    }
    // A NuPatch: a surface of revolution about z of a rational profile (rho, z, w), its rational
    // quadratic circle in u, placed by m0 at key 0 and m1 at key 1 (the same: still).
    const SurfaceMesh* nurbsRevolution(const std::vector<std::array<double, 3>>& profile, int vorder,
                                       std::vector<double> vknot, const Matrix4& m0, const Matrix4& m1) {
        const double h = std::sqrt(0.5), cx[9] = {1, 1, 0, -1, -1, -1, 0, 1, 1}, cy[9] = {0, 1, 1, 1, 0, -1, -1, -1, 0},
                     cw[9] = {1, h, 1, h, 1, h, 1, h, 1};
        auto shape = std::make_shared<NurbsShape>();
        shape->nu = 9, shape->uorder = 3, shape->nv = int(profile.size()), shape->vorder = vorder;
        shape->uknot = {0, 0, 0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1, 1, 1};
        shape->vknot = std::move(vknot);
        shape->vmin = shape->vknot[size_t(vorder - 1)], shape->vmax = shape->vknot[profile.size()];
        std::vector<Vec3d> k0, k1;
        for (const auto& [rho, z, w] : profile)
            for (int i = 0; i < 9; ++i) {
                shape->w.push_back(w * cw[i]);
                k0.push_back(m0.point({rho * cx[i], rho * cy[i], z}));
                k1.push_back(m1.point({rho * cx[i], rho * cy[i], z}));
            }
        meshes.push_back(std::make_unique<NurbsMesh>(shape, k0, k1, TimeSpan{0, 1}, &material, &camera,
                                                     std::array<Color, 4>{}));
        meshes.back()->setShadingRate(material.shadingRate);
        return meshes.back().get();
    }
    const SurfaceMesh* nurbsSphere(double r, const Matrix4& m0, const Matrix4& m1) {
        const double h = std::sqrt(0.5);
        return nurbsRevolution({{0, -r, 1}, {r, -r, h}, {r, 0, 1}, {r, r, h}, {0, r, 1}}, 3, {0, 0, 0, 0.5, 0.5, 1, 1, 1},
                               m0, m1);
    }
    const SurfaceMesh* quadric(QuadricKind kind, QuadricMesh::Params p, const Matrix4& m0, const Matrix4& m1) {
        const QuadricMesh::Params params[2] = {p, p};
        const Matrix4 m[2] = {m0, m1};
        meshes.push_back(
            std::make_unique<QuadricMesh>(kind, params, m, TimeSpan{0, 1}, &material, &camera, std::array<Color, 4>{}));
        meshes.back()->setShadingRate(material.shadingRate);
        return meshes.back().get();
    }
};

// A wavy B-spline patch mesh of nu x nv control points over [0, 60]^2 at depth 20.
PatchMeshDesc wavyMesh(int nu, int nv, bool uPeriodic = false, bool vPeriodic = false) {
    PatchMeshDesc d;
    d.nu = nu, d.nv = nv, d.uPeriodic = uPeriodic, d.vPeriodic = vPeriodic;
    basisFromName("b-spline", &d.uBasis);
    basisFromName("b-spline", &d.vBasis);
    d.P.resize(1);
    for (int j = 0; j < nv; ++j)
        for (int i = 0; i < nu; ++i)
            d.P[0].push_back({10 + 40.0 * i / (nu - 1), 10 + 40.0 * j / (nv - 1), 20 + 6 * std::sin(i * 1.3 + j * 0.7)});
    return d;
}

// A closed torus-shaped B-spline mesh: periodic in u and in v.
PatchMeshDesc torusMesh(int nu, int nv) {
    PatchMeshDesc d = wavyMesh(nu, nv, true, true);
    d.P[0].clear();
    for (int j = 0; j < nv; ++j)
        for (int i = 0; i < nu; ++i) {
            const double a = 2 * M_PI * i / nu, b = 2 * M_PI * j / nv;
            const double r = 30 + 12 * std::cos(b);
            d.P[0].push_back({64 + r * std::cos(a), 64 + r * std::sin(a), 60 + 12 * std::sin(b) + 2 * std::cos(3 * a)});
        }
    return d;
}

// The vertices along one side of a diced grid (0: row 0, 1: column nu, 2: row nv, 3: column 0),
// in increasing parameter, with repeated vertices removed.
std::vector<Vec3f> sideOf(const Grid& g, int side, int k = 0) {
    std::vector<Vec3f> out;
    const int n = side == 0 || side == 2 ? g.nu : g.nv;
    for (int m = 0; m <= n; ++m) {
        const int i = side == 0 || side == 2 ? m : (side == 1 ? g.nu : 0);
        const int j = side == 1 || side == 3 ? m : (side == 2 ? g.nv : 0);
        const Vec3f p = g.P[k][size_t(g.index(i, j))];
        if (out.empty() || out.back() != p) out.push_back(p);
    }
    return out;
}

CurvedBody& asCurved(BodyPtr& b) { return static_cast<CurvedBody&>(*b); }

TEST(CurvedBody, DicedBSplineMeshLiesOnTheBSplineSurface) {
    // Every interior grid vertex of every patch, and every patch corner, against the uniform
    // cubic B-spline formula over the mesh's control points.
    Fixture fx;
    const PatchMeshDesc d = wavyMesh(6, 5);
    const SurfaceMesh* mesh = fx.patchMesh(d);
    ASSERT_EQ(mesh->faceCount(), 3 * 2);
    auto basis = [](double t, double w[4]) {
        w[0] = (1 - t) * (1 - t) * (1 - t) / 6;
        w[1] = (3 * t * t * t - 6 * t * t + 4) / 6;
        w[2] = (-3 * t * t * t + 3 * t * t + 3 * t + 1) / 6;
        w[3] = t * t * t / 6;
    };
    auto direct = [&](int pi, int pj, double u, double v) {
        double wu[4], wv[4];
        basis(u, wu);
        basis(v, wv);
        Vec3d p;
        for (int l = 0; l < 4; ++l)
            for (int k = 0; k < 4; ++k) p += d.P[0][size_t((pj + l) * d.nu + pi + k)] * (wu[k] * wv[l]);
        return Vec3f(p);
    };
    for (int f = 0; f < mesh->faceCount(); ++f) {
        const int pi = f % 3, pj = f / 3;
        Grid g;
        CurvedBody(mesh, f).dice(7, 5, g);
        for (int j = 0; j <= g.nv; ++j)
            for (int i = 0; i <= g.nu; ++i) {
                const bool corner = (i == 0 || i == g.nu) && (j == 0 || j == g.nv);
                if (!corner && (i == 0 || j == 0 || i == g.nu || j == g.nv)) continue;  // side lattices
                const Vec3f want = direct(pi, pj, double(i) / g.nu, double(j) / g.nv);
                EXPECT_NEAR(length(g.P[0][size_t(g.index(i, j))] - want), 0.0f, 2e-4f) << "face " << f;
            }
    }
}

TEST(CurvedBody, SplitPiecesShareTheirCommonEdgeBitForBit) {
    Fixture fx;
    const SurfaceMesh* mesh = fx.patchMesh(wavyMesh(4, 4));
    CurvedBody root(mesh, 0);
    BodyPtr halves[2], quarters[2];
    root.split(SplitAxis::U, halves);
    asCurved(halves[0]).split(SplitAxis::V, quarters);
    Grid right, low, high;
    halves[1]->dice(3, 3, right);
    quarters[0]->dice(5, 2, low);
    quarters[1]->dice(2, 7, high);
    // The line u = 1/2: column 0 of the right half, column nu of both left quarters.
    std::vector<Vec3f> left = sideOf(low, 1), upper = sideOf(high, 1);
    ASSERT_EQ(left.back(), upper.front());
    left.insert(left.end(), upper.begin() + 1, upper.end());
    EXPECT_EQ(left, sideOf(right, 3));
    EXPECT_GE(left.size(), 5u);  // the line's lattice, not just the corners
}

TEST(CurvedBody, NeighbouringPatchesShareTheirEdgeBitForBit) {
    Fixture fx;
    const SurfaceMesh* mesh = fx.patchMesh(wavyMesh(5, 4));  // 2 x 1 patches
    ASSERT_EQ(mesh->faceCount(), 2);
    CurvedBody a(mesh, 0), b(mesh, 1);
    BodyPtr h[2], q[2];
    a.split(SplitAxis::V, h);
    asCurved(h[1]).split(SplitAxis::V, q);
    Grid g0, g1, g2, gb;
    h[0]->dice(4, 1, g0);
    q[0]->dice(1, 3, g1);
    q[1]->dice(6, 6, g2);
    b.dice(2, 9, gb);
    std::vector<Vec3f> edge = sideOf(g0, 1);
    for (const Grid* g : {&g1, &g2}) {
        std::vector<Vec3f> s = sideOf(*g, 1);
        ASSERT_EQ(edge.back(), s.front());
        edge.insert(edge.end(), s.begin() + 1, s.end());
    }
    EXPECT_EQ(edge, sideOf(gb, 3));
}

// Dices a random split tree of every face and checks that the grids close up: every boundary
// segment of every grid is met by the same segment of another grid, or by a chain of segments
// on it (a piece split where its neighbour's edge has no lattice point puts its corner on that
// edge's chord).
void expectWatertight(const SurfaceMesh& mesh, uint32_t seed, int keys) {
    std::mt19937 rng(seed);
    std::vector<Grid> grids;
    std::function<void(const Body&, int)> visit = [&](const Body& b, int depth) {
        if (depth < 5 && std::uniform_real_distribution<>(0, 1)(rng) < 0.7) {
            BodyPtr h[2];
            b.split(rng() % 2 ? SplitAxis::U : SplitAxis::V, h);
            visit(*h[0], depth + 1);
            visit(*h[1], depth + 1);
            return;
        }
        grids.emplace_back();
        b.dice(int(1 + rng() % 6), int(1 + rng() % 6), grids.back());
    };
    for (int f = 0; f < mesh.faceCount(); ++f) visit(CurvedBody(&mesh, f), 0);

    for (int k = 0; k < keys; ++k) {
        auto key = [](Vec3f a, Vec3f b) {
            auto less = [](Vec3f p, Vec3f q) { return std::tie(p.x, p.y, p.z) < std::tie(q.x, q.y, q.z); };
            return less(a, b) ? std::make_pair(std::array<float, 3>{a.x, a.y, a.z}, std::array<float, 3>{b.x, b.y, b.z})
                              : std::make_pair(std::array<float, 3>{b.x, b.y, b.z}, std::array<float, 3>{a.x, a.y, a.z});
        };
        std::map<std::pair<std::array<float, 3>, std::array<float, 3>>, int> count;
        for (const Grid& g : grids)
            for (int s = 0; s < 4; ++s) {
                const std::vector<Vec3f> v = sideOf(g, s, k);
                for (size_t i = 0; i + 1 < v.size(); ++i) ++count[key(v[i], v[i + 1])];
            }
        auto asVec = [](const std::array<float, 3>& a) { return Vec3f{a[0], a[1], a[2]}; };
        std::vector<std::pair<Vec3f, Vec3f>> odd;
        for (const auto& [e, n] : count) {
            EXPECT_LE(n, 2) << "a segment is shared by more than two grids";
            if (n % 2) odd.emplace_back(asVec(e.first), asVec(e.second));
        }
        // Each odd segment is a chord of a coarser neighbour covered by a chain of the finer side's
        // segments, or one of those segments, lying on such a chord.
        auto onSegment = [](Vec3f a, Vec3f b, Vec3f p) {
            const Vec3f d = b - a;
            const float len = length(d), t = dot(p - a, d) / (len * len);
            return t >= -1e-4f && t <= 1 + 1e-4f && length(a + d * t - p) <= 1e-4f * len + 1e-5f;
        };
        // Two grids that share a whole segment share it bit for bit, so a segment that is only
        // nearly matched (by one segment of about its length) is a crack.
        for (const auto& [a, b] : odd) {
            const float len = length(b - a);
            float covered = 0;
            int pieces = 0;
            bool onChord = false;
            for (const auto& [c, e] : odd) {
                if ((c == a && e == b) || (c == b && e == a)) continue;
                if (onSegment(a, b, c) && onSegment(a, b, e)) covered += length(e - c), ++pieces;
                onChord = onChord || (onSegment(c, e, a) && onSegment(c, e, b) && length(e - c) > 1.5f * len);
            }
            EXPECT_TRUE(onChord || (pieces >= 2 && std::fabs(covered - len) <= 1e-3f * len))
                << "a crack along a segment of length " << len << " (covered " << covered << " by " << pieces << ")";
        }
    }
}

// Coarse shading rates make long lattice steps, so that random splits often cut sides where the
// neighbour has no lattice point (the corner then goes on the neighbour's chord).
TEST(CurvedBody, ClosedPatchMeshDicesIntoAWatertightMesh) {
    Fixture fx;
    fx.material.shadingRate = 30;
    const SurfaceMesh* still = fx.patchMesh(torusMesh(6, 5));
    const SurfaceMesh* moving = fx.patchMesh(torusMesh(6, 5), {7, -3, 2});
    EXPECT_EQ(still->faceCount(), 30);
    for (uint32_t seed : {1u, 2u, 3u}) {
        expectWatertight(*still, seed, 1);
        expectWatertight(*moving, seed, 2);
    }
}

TEST(CurvedBody, ClosedQuadricsDiceIntoWatertightMeshes) {
    Fixture fx;
    fx.material.shadingRate = 30;
    const Matrix4 m0 = Matrix4::translate({64, 64, 100}) , m1 = Matrix4::rotate(30, {1, 1, 0}) * m0;
    for (uint32_t seed : {4u, 5u}) {
        expectWatertight(*fx.quadric(QuadricKind::Sphere, {40, -40, 40, 360}, m0, m0), seed, 1);
        expectWatertight(*fx.quadric(QuadricKind::Sphere, {40, -40, 40, 360}, m0, m1), seed, 2);
        expectWatertight(*fx.quadric(QuadricKind::Torus, {35, 12, 0, 360, 360}, m0, m1), seed, 2);
    }
}

// NuPatches: a sphere (a seam and two poles, collapsed sides) and a torus (two seams), and a
// cubic vase profile of non-uniform knots (a seam, open ends).
TEST(CurvedBody, ClosedNurbsSurfacesDiceIntoWatertightMeshes) {
    Fixture fx;
    fx.material.shadingRate = 30;
    const Matrix4 m0 = Matrix4::translate({64, 64, 100}), m1 = Matrix4::rotate(30, {1, 1, 0}) * m0;
    const double h = std::sqrt(0.5);
    std::vector<std::array<double, 3>> torus;
    const double cx[9] = {1, 1, 0, -1, -1, -1, 0, 1, 1}, cy[9] = {0, 1, 1, 1, 0, -1, -1, -1, 0};
    for (int j = 0; j < 9; ++j) torus.push_back({35 + 12 * cx[j], 12 * cy[j], j % 2 ? h : 1});
    const std::vector<double> circle{0, 0, 0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1, 1, 1};
    for (uint32_t seed : {4u, 5u}) {
        expectWatertight(*fx.nurbsSphere(40, m0, m0), seed, 1);
        expectWatertight(*fx.nurbsSphere(40, m0, m1), seed, 2);
        expectWatertight(*fx.nurbsRevolution(torus, 3, circle, m0, m1), seed, 2);
    }
}

TEST(CurvedBody, ClosedSubdivisionSurfaceDicesIntoAWatertightMesh) {
    Fixture fx;
    fx.material.shadingRate = 30;
    for (uint32_t seed : {6u, 7u}) {
        expectWatertight(*fx.subdivisionCube(), seed, 1);
        expectWatertight(*fx.subdivisionCube({5, 2, -4}), seed, 2);
    }
}

TEST(CurvedBody, BoundsHoldTheDicedSurfaceAtEveryTime) {
    Fixture fx;
    const Matrix4 m0 = Matrix4::translate({64, 64, 100}), m1 = Matrix4::rotate(40, {0, 1, 1}) * Matrix4::translate({60, 70, 90});
    std::vector<const SurfaceMesh*> meshes = {
        fx.patchMesh(wavyMesh(6, 5), {4, 9, -3}),
        fx.subdivisionCube({6, -5, 3}),
        fx.quadric(QuadricKind::Sphere, {30, -20, 25, 300}, m0, m1),
        fx.quadric(QuadricKind::Cylinder, {20, -10, 30, 270}, m0, m1),
        fx.quadric(QuadricKind::Cone, {30, 20, 360}, m0, m1),
        fx.quadric(QuadricKind::Disk, {5, 25, 200}, m0, m1),
        fx.quadric(QuadricKind::Paraboloid, {20, 5, 30, 360}, m0, m1),
        fx.quadric(QuadricKind::Hyperboloid, {10, -20, -10, -5, 25, 15, 330}, m0, m1),
        fx.quadric(QuadricKind::Torus, {30, 10, -45, 200, 250}, m0, m1),
        fx.nurbsSphere(30, m0, m1),
        fx.nurbsRevolution({{20, -20, 1}, {35, -10, 0.4}, {10, 5, 2.5}, {12, 20, 1}, {25, 30, 0.7}}, 4,
                           {-1, -1, -1, -1, 0.2, 3, 3, 3, 3}, m0, m1),
    };
    std::mt19937 rng(23);
    for (const SurfaceMesh* mesh : meshes) {
        for (int trial = 0; trial < 6; ++trial) {
            BodyPtr b = std::make_unique<CurvedBody>(mesh, int(rng() % unsigned(mesh->faceCount())));
            for (int s = 0; s < int(rng() % 5); ++s) {
                BodyPtr h[2];
                b->split(SplitAxis(rng() % 3), h);
                b = std::move(h[rng() % 2]);
            }
            const LBBox3f lb = b->bound();
            Grid g;
            b->dice(7, 7, g);
            for (int k = 0; k < (g.moving ? 2 : 1); ++k)
                for (const Vec3f& p : g.P[k]) EXPECT_TRUE((k == 0 ? lb.b0 : lb.b1).contains(p)) << "trial " << trial;
            if (g.moving) {  // the linear motion between stays inside the interpolated box
                const Bounds3f mid = lb.at(0.5f);
                for (size_t i = 0; i < g.P[0].size(); ++i) {
                    const Vec3f p = lerp(g.P[0][i], g.P[1][i], 0.5f);
                    EXPECT_LE(length(vmax(vmin(p, mid.hi), mid.lo) - p), 1e-4f);
                }
            }
        }
    }
}

TEST(CurvedBody, QuadricsFollowRenderMansParameterisation) {
    Fixture fx;
    const Matrix4 id;
    Vec3f P, N;
    fx.quadric(QuadricKind::Sphere, {2, -2, 2, 360}, id, id)->evaluate(0, 0.25, 0.5, 0, &P, &N);
    EXPECT_NEAR(length(P - Vec3f{0, 2, 0}), 0, 1e-6f);  // theta 90 degrees on the equator
    fx.quadric(QuadricKind::Sphere, {2, -2, 2, 360}, id, id)->evaluate(0, 0.7, 1, 0, &P, &N);
    EXPECT_EQ(P.x, 0.0f);  // the pole is one point
    EXPECT_EQ(P.z, 2.0f);
    fx.quadric(QuadricKind::Cone, {3, 1, 360}, id, id)->evaluate(0, 0, 0.5, 0, &P, &N);
    EXPECT_NEAR(length(P - Vec3f{0.5f, 0, 1.5f}), 0, 1e-6f);
    fx.quadric(QuadricKind::Disk, {1, 2, 180}, id, id)->evaluate(0, 1, 0, 0, &P, &N);
    EXPECT_NEAR(length(P - Vec3f{-2, 0, 1}), 0, 1e-6f);
    fx.quadric(QuadricKind::Paraboloid, {2, 0, 4, 360}, id, id)->evaluate(0, 0, 0.25, 0, &P, &N);
    EXPECT_NEAR(length(P - Vec3f{1, 0, 1}), 0, 1e-6f);  // r = rmax sqrt(z / zmax)
    fx.quadric(QuadricKind::Hyperboloid, {1, 0, -1, 0, 1, 1, 360}, id, id)->evaluate(0, 0.25, 0.5, 0, &P, &N);
    EXPECT_NEAR(length(P - Vec3f{-0.5f, 0.5f, 0}), 0, 1e-6f);
    fx.quadric(QuadricKind::Torus, {3, 1, 0, 360, 360}, id, id)->evaluate(0, 0, 0.25, 0, &P, &N);
    EXPECT_NEAR(length(P - Vec3f{3, 0, 1}), 0, 1e-6f);
    fx.quadric(QuadricKind::Cylinder, {1, -1, 1, 360}, id, id)->evaluate(0, 0.5, 1, 0, &P, &N);
    EXPECT_NEAR(length(P - Vec3f{-1, 0, 1}), 0, 1e-6f);
    EXPECT_NEAR(std::fabs(normalize(N).x), 1, 1e-6f);  // the cylinder's normal is radial
}

}  // namespace
}  // namespace streyes
