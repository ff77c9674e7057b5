// Catmull-Clark surfaces through OpenSubdiv, checked against closed forms: the limit of a cube,
// the B-spline surface of a regular mesh, a crease's curve, and bounds that hold what Bfr
// evaluates.
#include "geom/subdivision.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "geom/curved_body.h"
#include "geom/grid.h"
#include "shade/shading.h"
#include "test_util.h"

namespace streyes {
namespace {

// The unit cube [-1/2, 1/2]^3, faces facing out.
SubdivisionMeshDesc cube() {
    SubdivisionMeshDesc d;
    d.faceSizes = {4, 4, 4, 4, 4, 4};
    d.faceVertices = {0, 1, 3, 2, 2, 3, 5, 4, 4, 5, 7, 6, 6, 7, 1, 0, 1, 7, 5, 3, 6, 0, 2, 4};
    d.vertexCount = 8;
    d.P = {{{-.5, -.5, .5}, {.5, -.5, .5}, {-.5, .5, .5}, {.5, .5, .5},
            {-.5, .5, -.5}, {.5, .5, -.5}, {-.5, -.5, -.5}, {.5, -.5, -.5}}};
    return d;
}

struct Surface {
    Camera camera = test::pixelCamera(256);
    Material material;
    std::shared_ptr<const SubdivisionShape> shape;
    std::unique_ptr<SubdivisionMesh> mesh;
    explicit Surface(const SubdivisionMeshDesc& d) {
        shape = std::make_shared<SubdivisionShape>(d);
        auto key = shape->key(d.P[0]);
        mesh = std::make_unique<SubdivisionMesh>(shape, key, key, TimeSpan{0, 0}, &material, &camera,
                                                 shape->colors({}, Color{1, 1, 1}));
    }
    // Every face diced at n x n (more where its edges ask for it).
    std::vector<Grid> dice(int n) const {
        std::vector<Grid> grids(size_t(mesh->faceCount()));
        for (int f = 0; f < mesh->faceCount(); ++f) CurvedBody(mesh.get(), f).dice(n, n, grids[size_t(f)]);
        return grids;
    }
};

TEST(Subdivision, CubeLimitSurfaceMatchesTheClosedForm) {
    Surface s(cube());
    // Refined once, the cube's 6 faces are 24 quads, each with one corner of valence 3.
    EXPECT_EQ(s.mesh->faceCount(), 24);
    EXPECT_EQ(s.shape->irregularFaceCount(), 24);
    float top = -1;
    Vec3f topAt;
    bool corner = false;
    for (const Grid& g : s.dice(6))
        for (const Vec3f& p : g.P[0]) {
            if (p.z > top) top = p.z, topAt = p;
            // The limit of a valence-3 corner: (n^2 v + 4 sum(edge neighbours) + sum(diagonals)) / (n (n+5)).
            corner = corner || length(p - Vec3f{0.25f, 0.25f, 0.25f}) < 1e-6f;
        }
    // The middle of a face lies at 68/81 of the half-width.
    EXPECT_NEAR(top, 0.5 * 68.0 / 81.0, 1e-6);
    EXPECT_NEAR(topAt.x, 0.0f, 1e-6f);
    EXPECT_NEAR(topAt.y, 0.0f, 1e-6f);
    EXPECT_TRUE(corner);
}

TEST(Subdivision, RegularMeshIsTheUniformBSplineSurface) {
    // A torus-shaped quad mesh: every vertex has valence 4, every face is a B-spline patch of
    // the control net, and every level-1 vertex is the B-spline surface at a half-integer
    // parameter: (1 4 1)/6 in each direction at a vertex, (1 23 23 1)/48 at a face middle, and
    // so on.
    const int n = 6, m = 5;
    SubdivisionMeshDesc d;
    auto id = [&](int i, int j) { return ((j + m) % m) * n + (i + n) % n; };
    for (int j = 0; j < m; ++j)
        for (int i = 0; i < n; ++i) {
            d.faceSizes.push_back(4);
            for (int v : {id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)}) d.faceVertices.push_back(v);
        }
    d.vertexCount = n * m;
    d.P.resize(1);
    for (int j = 0; j < m; ++j)
        for (int i = 0; i < n; ++i) {
            const double a = 2 * M_PI * i / n, b = 2 * M_PI * j / m, r = 3 + std::cos(b) + 0.3 * std::sin(3 * a);
            d.P[0].push_back({r * std::cos(a), r * std::sin(a), std::sin(b)});
        }
    Surface s(d);
    EXPECT_EQ(s.shape->irregularFaceCount(), 0);
    for (int f = 0; f < s.mesh->faceCount(); ++f) EXPECT_TRUE(s.mesh->regular(f));
    // The B-spline surface of the net at (i + a, j + b), a and b in {0, 1/2}.
    auto bspline = [&](int i, int j, double a, double b) {
        auto w = [](double t, double out[4]) {
            out[0] = (1 - t) * (1 - t) * (1 - t) / 6;
            out[1] = (3 * t * t * t - 6 * t * t + 4) / 6;
            out[2] = (-3 * t * t * t + 3 * t * t + 3 * t + 1) / 6;
            out[3] = t * t * t / 6;
        };
        double wu[4], wv[4];
        w(a, wu);
        w(b, wv);
        Vec3d p;
        for (int l = 0; l < 4; ++l)
            for (int k = 0; k < 4; ++k) p += d.P[0][size_t(id(i + k - 1, j + l - 1))] * (wu[k] * wv[l]);
        return Vec3f(p);
    };
    std::vector<Vec3f> expected;
    for (int j = 0; j < m; ++j)
        for (int i = 0; i < n; ++i)
            for (double a : {0.0, 0.5})
                for (double b : {0.0, 0.5}) expected.push_back(bspline(i, j, a, b));
    // Every face corner is one of them, and every one of them is a face corner.
    std::vector<bool> seen(expected.size(), false);
    for (int f = 0; f < s.mesh->faceCount(); ++f)
        for (int c = 0; c < 4; ++c) {
            Vec3f P, N;
            s.mesh->evaluatePoint(f, c & 1, c >> 1, 0, &P, &N);
            size_t best = 0;
            for (size_t e = 1; e < expected.size(); ++e)
                if (length(expected[e] - P) < length(expected[best] - P)) best = e;
            EXPECT_NEAR(length(expected[best] - P), 0.0f, 2e-6f) << "face " << f << " corner " << c;
            seen[best] = true;
        }
    EXPECT_EQ(std::count(seen.begin(), seen.end(), true), long(expected.size()));
}

TEST(Subdivision, IrregularFaceBoundsHoldWhatBfrEvaluates) {
    // A cube with one vertex pulled out (valence 3 corners everywhere) and a semi-sharp crease.
    SubdivisionMeshDesc d = cube();
    d.P[0][3] = {1.2, 0.9, 0.8};
    d.creaseEdges = {1, 3};
    d.creaseSharpness = {2.5f};
    Surface s(d);
    std::mt19937 rng(31);
    std::uniform_real_distribution<double> uni(0, 1);
    for (int f = 0; f < s.mesh->faceCount(); ++f) {
        const Bounds3f whole = s.mesh->bound(f, {0, 1, 0, 1}, 0);
        for (int trial = 0; trial < 6; ++trial) {
            const int depth = int(rng() % 4);
            const double w = std::ldexp(1.0, -depth);
            const double u0 = w * double(rng() % (1u << depth)), v0 = w * double(rng() % (1u << depth));
            const ParamRect r{u0, u0 + w, v0, v0 + w};
            const Bounds3f b = s.mesh->bound(f, r, 0);
            EXPECT_TRUE(whole.contains(b.lo) && whole.contains(b.hi));
            for (int k = 0; k < 64; ++k) {
                Vec3f P, N;
                s.mesh->evaluate(f, u0 + w * uni(rng), v0 + w * uni(rng), 0, &P, &N);
                EXPECT_TRUE(b.contains(P)) << "face " << f << " rect " << u0 << "," << v0 << " size " << w;
            }
        }
        // The bound shrinks: a quarter of a face away from its extraordinary corner is bounded
        // by the Bezier hull of its leaf, well inside the whole face's box.
        Bounds3f quarters[4];
        float smallest = 1e30f;
        for (int q = 0; q < 4; ++q) {
            quarters[q] = s.mesh->bound(f, {(q & 1) * 0.5, (q & 1) * 0.5 + 0.5, (q >> 1) * 0.5, (q >> 1) * 0.5 + 0.5}, 0);
            const Vec3f dq = quarters[q].diagonal();
            smallest = std::min(smallest, dq.x + dq.y + dq.z);
        }
        const Vec3f dw = whole.diagonal();
        EXPECT_LT(smallest, 0.75f * (dw.x + dw.y + dw.z)) << "face " << f;
    }
}

// Bfr's tree for a face with one extraordinary corner: a Gregory leaf at that corner, a quarter
// of the face on each side, and regular (bicubic) leaves everywhere else, some of them next to
// finer leaves. Only the Gregory leaf is bounded by the box of its patch points; every other cell
// gets a Bezier form that matches what Bfr evaluates, and bounds that shrink with the piece.
// (Regular leaves next to finer ones used to be taken for irregular: on a leaf's border Bfr
// may evaluate with the neighbouring leaf, whose weights are on other patch points; their
// bounds were the box of all their patch points, up to 40 times the piece's area on screen.)
TEST(Subdivision, OnlyTheExtraordinaryCornerIsWithoutABezierForm) {
    Surface s(cube());
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> uni(0, 1);
    for (int f = 0; f < s.mesh->faceCount(); ++f) {
        int without = 0;
        for (int j = 0; j < 4; ++j)
            for (int i = 0; i < 4; ++i) {
                const ParamRect r{i / 4.0, (i + 1) / 4.0, j / 4.0, (j + 1) / 4.0};
                BezierPatch cp;
                if (!s.mesh->bezier(f, r, 0, &cp)) {
                    ++without;
                    continue;
                }
                for (int k = 0; k < 8; ++k) {
                    const double a = uni(rng), b = uni(rng);
                    Vec3f P, N;
                    s.mesh->evaluate(f, r.u0 + a * 0.25, r.v0 + b * 0.25, 0, &P, &N);
                    Vec3d Q, du, dv;
                    evalBezier(cp, a, b, &Q, &du, &dv);
                    EXPECT_LT(length(Vec3d(P) - Q), 1e-5) << "face " << f << " cell " << i << "," << j;
                }
            }
        EXPECT_EQ(without, 1) << "face " << f;
    }
}

TEST(Subdivision, CreaseMakesTheSharpEdgeItPromises) {
    // The four top edges of the cube, infinitely sharp: the crease is the cubic B-spline of the
    // top square (its limit at an edge's middle is (P0 + 23 P1 + 23 P2 + P3) / 48), the top face
    // stays flat at z = 1/2, and the surface folds there.
    SubdivisionMeshDesc d = cube();
    d.creaseEdges = {0, 1, 1, 3, 3, 2, 2, 0};
    d.creaseSharpness = {10, 10, 10, 10};
    Surface s(d);
    const Vec3f mid{11.0f / 24, 0, 0.5f};
    std::vector<Vec3f> normalsAtMid;
    float top = -1;
    for (const Grid& g : s.dice(5))
        for (size_t i = 0; i < g.P[0].size(); ++i) {
            top = std::max(top, g.P[0][i].z);
            if (length(g.P[0][i] - mid) < 1e-6f) normalsAtMid.push_back(normalize(g.N[0][i]));
        }
    EXPECT_NEAR(top, 0.5f, 1e-6f);
    ASSERT_GE(normalsAtMid.size(), 2u);
    float minDot = 1;
    for (const Vec3f& a : normalsAtMid)
        for (const Vec3f& b : normalsAtMid) minDot = std::min(minDot, std::fabs(dot(a, b)));
    EXPECT_LT(minDot, 0.5f);  // two faces meet at a sharp angle

    // Without the tag the same point of the mesh is smooth and lower.
    Surface smooth(cube());
    float smoothTop = -1;
    for (const Grid& g : smooth.dice(5))
        for (const Vec3f& p : g.P[0]) smoothTop = std::max(smoothTop, p.z);
    EXPECT_LT(smoothTop, 0.45f);
}

TEST(Subdivision, NonQuadFacesHolesAndBoundariesHaveTheRightFaces) {
    // A pyramid: a square base and four triangles. Refined once, a triangle becomes 3 quads.
    SubdivisionMeshDesc d;
    d.faceSizes = {4, 3, 3, 3, 3};
    d.faceVertices = {0, 3, 2, 1, 0, 1, 4, 1, 2, 4, 2, 3, 4, 3, 0, 4};
    d.vertexCount = 5;
    d.P = {{{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}, {0, 0, 1.5}}};
    EXPECT_EQ(Surface(d).mesh->faceCount(), 4 + 4 * 3);
    d.holes = {0};  // no base: the triangles' limit surface still needs the base's points
    EXPECT_EQ(Surface(d).mesh->faceCount(), 4 * 3);
    // An open square sheet of 2 x 2 quads: without interpolateboundary only faces away from the
    // boundary have a limit surface (none here); with it, all four do.
    SubdivisionMeshDesc sheet;
    sheet.faceSizes = {4, 4, 4, 4};
    sheet.faceVertices = {0, 1, 4, 3, 1, 2, 5, 4, 3, 4, 7, 6, 4, 5, 8, 7};
    sheet.vertexCount = 9;
    sheet.P.resize(1);
    for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 3; ++i) sheet.P[0].push_back({double(i), double(j), 0});
    sheet.interpolateBoundary = 1;
    Surface withBoundary(sheet);
    EXPECT_EQ(withBoundary.mesh->faceCount(), 16);
    // The corners of an interpolated boundary stay where they are.
    Vec3f P, N;
    bool cornerFound = false;
    for (int f = 0; f < withBoundary.mesh->faceCount(); ++f)
        for (int c = 0; c < 4; ++c) {
            withBoundary.mesh->evaluatePoint(f, c & 1, c >> 1, 0, &P, &N);
            cornerFound = cornerFound || length(P - Vec3f{2, 2, 0}) < 1e-6f;
        }
    EXPECT_TRUE(cornerFound);
    sheet.interpolateBoundary = 0;
    EXPECT_EQ(SubdivisionShape(sheet).faceCount(), 0);
}

}  // namespace
}  // namespace streyes
