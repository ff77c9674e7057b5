// The trim region of a NuPatch (TrimCurve): its loops of rational B-spline curves in (u, v), as
// polylines. RenderMan's rule: a point is inside the trim curves when a ray from it crosses them
// an odd number of times, and the inside is cut away (the surface keeps the rest).
//
// Trimming removes micropolygons: one whose centre (in u, v) is inside is not rasterized (Grid::hole),
// so a hole's edge is resolved to within half a micropolygon, on both sides of it alike.
#pragma once

#include <cstdint>
#include <vector>

#include "streyes/scene.h"
#include "streyes/vecmath.h"

namespace streyes {

class NurbsTrim {
  public:
    // The loops as polylines of `stepsPerSpan` segments per knot span and degree.
    explicit NurbsTrim(const TrimLoops& loops, int stepsPerSpan = 64);

    bool empty() const { return edges_.empty(); }
    // Whether (u, v) is cut away.
    bool cut(double u, double v) const;
    // Whether all of [u0, u1] x [v0, v1] is cut away: no loop edge's box meets it and its centre
    // is cut (conservative: false where an edge passes near).
    bool covers(double u0, double u1, double v0, double v1) const;
    // For an nu x nv grid over [u0, u1] x [v0, v1]: hole[j * nu + i] = 1 where micropolygon (i, j)'s
    // centre is cut away. False, with `hole` untouched, when the rectangle misses every loop's bound
    // (nothing is cut there). Allocates nothing once its scratch is warm.
    bool mark(double u0, double u1, double v0, double v1, int nu, int nv, std::vector<uint8_t>& hole) const;

  private:
    struct Edge {
        Vec2<double> a, b;
    };
    std::vector<Edge> edges_;
    double ulo_ = 0, uhi_ = 0, vlo_ = 0, vhi_ = 0;  // the loops' bound
};

}  // namespace streyes
