// "Cs" on bicubic patches (Patch "bicubic", PatchMesh "bicubic"): vertex colours follow the
// patch's basis as P does, varying ones are bilinear between the corners of the patch grid (RI
// Spec 3.2, section 5.1; Aqsis 1.8.4 renders both the same way). A flat Bezier patch whose x
// control points are 0 0 32 32 along u has x = 32 (3u^2 - 2u^3), which is not linear in u: a
// vertex colour linear in the control points' x reads x / 32 at every point (the Bezier basis
// reproduces linear functions), where the bilinear blend of the corners would read u (up to 0.1
// away); a varying colour reads u.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "test_util.h"

namespace streyes {
namespace {

// A 32 x 16 orthographic view one unit a pixel, samples at the centres of 4 x 4 strata.
std::string header() {
    return test::orthoHeader(32, 16, "PixelSamples 4 4\nHider \"hidden\" \"jitter\" 0\n");
}

double xControl(int i) { return i < 2 ? 0.0 : 32.0; }

// The 16 control points, row by row (u fastest), and a vertex colour of each from f(x, row).
std::string controls(const std::string& what, double (*f)(double x, int c)) {
    std::string s;
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i) {
            if (what == "P") s += std::to_string(xControl(i)) + " " + std::to_string(16.0 * j / 3) + " 5  ";
            else
                for (int c = 0; c < 3; ++c) s += std::to_string(f(xControl(i), c)) + " ";
        }
    return "[" + s + "]";
}

double linearInX(double x, int c) { return c == 0 ? x / 32 : c == 1 ? 0.25 : 1 - x / 32; }
double constantColour(double, int c) { return 0.3 * (c + 1); }

// u where 32 (3u^2 - 2u^3) = x (it rises monotonically over [0, 1]).
double uAt(double x) {
    double lo = 0, hi = 1;
    for (int k = 0; k < 60; ++k) {
        const double u = (lo + hi) / 2;
        (32 * (3 * u * u - 2 * u * u * u) < x ? lo : hi) = u;
    }
    return (lo + hi) / 2;
}

TEST(BicubicColour, VertexColourFollowsTheBasis) {
    for (const std::string request : {"Patch \"bicubic\"", "PatchMesh \"bicubic\" 4 \"nonperiodic\" 4 \"nonperiodic\""})
        for (const Algorithm a : {Algorithm::SpacetimeOcclusion, Algorithm::Raytrace}) {
            SCOPED_TRACE(request + " " + algorithmName(a));
            const test::RenderResult r = test::renderRib(header() + request + " \"P\" " + controls("P", nullptr) +
                                                         " \"vertex color Cs\" " + controls("Cs", linearInX) + "\nWorldEnd\n",
                                                         test::optionsFor(a));
            EXPECT_TRUE(r.warnings.empty()) << (r.warnings.empty() ? "" : r.warnings.front());
            // REYES shades the grid's vertices (exact there) and interpolates linearly in position,
            // which a colour linear in x is; the ray tracer shades each hit at the (u, v) its
            // micropolygon interpolates, off by x's curvature over a micropolygon (x'' <= 192,
            // a thirtieth of u wide: up to 0.025 pixel, 8e-4 in colour), and along the patch's
            // sides, whose vertices follow the neighbours' lattices, by the parameter rectangle
            // its micropolygons take there (a rectangle, where the side's vertices are not on one:
            // measured up to 4.1e-3 in the pixels next to the sides). The corners' bilinear blend
            // (u) would be up to 0.1 away.
            const double tol = a == Algorithm::Raytrace ? 5e-3 : 1e-4;
            for (int y : {0, 1, 8, 14, 15})
                for (int x : {0, 1, 5, 10, 15, 16, 17, 22, 27, 30, 31}) {
                    const double X = x + 0.5;
                    EXPECT_NEAR(r.channel(0, x, y, 0), X / 32, tol) << "pixel " << x << " " << y;
                    EXPECT_NEAR(r.channel(0, x, y, 1), 0.25, 1e-6) << "pixel " << x << " " << y;
                    EXPECT_NEAR(r.channel(0, x, y, 2), 1 - X / 32, tol) << "pixel " << x << " " << y;
                }
            const test::RenderResult c = test::renderRib(header() + request + " \"P\" " + controls("P", nullptr) +
                                                         " \"vertex color Cs\" " + controls("Cs", constantColour) +
                                                         "\nWorldEnd\n",
                                                         test::optionsFor(a));
            for (int y : {2, 9})
                for (int x : {0, 7, 19, 31})
                    for (int ch = 0; ch < 3; ++ch)
                        EXPECT_NEAR(c.channel(0, x, y, ch), 0.3 * (ch + 1), 1e-6) << "pixel " << x << " " << y;
        }
}

// A varying colour is bilinear in (u, v) between the patch's corners: 0 at u = 0, 1 at u = 1.
// Away from the edges, where u(x) bends fastest and a pixel's mean leaves its centre's value.
TEST(BicubicColour, VaryingColourIsBilinearBetweenTheCorners) {
    for (const Algorithm a : {Algorithm::SpacetimeOcclusion, Algorithm::Raytrace}) {
        SCOPED_TRACE(algorithmName(a));
        const test::RenderResult r = test::renderRib(header() + "Patch \"bicubic\" \"P\" " + controls("P", nullptr) +
                                                     " \"varying color Cs\" [0 0 0  1 0 0  0 0 0  1 0 0]\nWorldEnd\n",
                                                     test::optionsFor(a));
        for (int x : {6, 11, 16, 21, 26}) EXPECT_NEAR(r.channel(0, x, 8, 0), uAt(x + 0.5), 3e-3) << "pixel " << x;
    }
}

}  // namespace
}  // namespace streyes
