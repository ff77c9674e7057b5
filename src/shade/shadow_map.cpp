#include "shade/shadow_map.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "shade/vm/texture_source.h"

namespace streyes {

namespace {

struct Hom {
    double x, y, z, w;
};

// p * M without the divide.
Hom homogeneous(const Matrix4& m, const Vec3d& p) {
    return {p.x * m(0, 0) + p.y * m(1, 0) + p.z * m(2, 0) + m(3, 0),
            p.x * m(0, 1) + p.y * m(1, 1) + p.z * m(2, 1) + m(3, 1),
            p.x * m(0, 2) + p.y * m(1, 2) + p.z * m(2, 2) + m(3, 2),
            p.x * m(0, 3) + p.y * m(1, 3) + p.z * m(2, 3) + m(3, 3)};
}

double det3(const double a[3], const double b[3], const double c[3]) {
    return a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) + a[2] * (b[0] * c[1] - b[1] * c[0]);
}

// a + b x + c y + d x y
struct Bilinear {
    double a = 0, b = 0, c = 0, d = 0;
    double at(double x, double y) const { return a + b * x + c * y + d * x * y; }
};

uint64_t mix(uint64_t z) {
    z += 0x9e3779b97f4a7c15ull;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

uint64_t bitsOf(double v) {
    const float f = float(v);
    uint32_t u;
    std::memcpy(&u, &f, sizeof u);
    return u;
}

}  // namespace

bool DepthMap::sameAs(const DepthMap& o) const {
    if (bool(previous) != bool(o.previous)) return false;
    if (previous && previous != o.previous && !previous->sameAs(*o.previous)) return false;
    return width == o.width && height == o.height && worldToCamera == o.worldToCamera &&
           worldToScreen == o.worldToScreen && z.size() == o.z.size() &&
           (z.empty() || std::memcmp(z.data(), o.z.data(), z.size() * sizeof(float)) == 0);
}

Matrix4 screenProjection(bool perspective, double ax, double bx, double ay, double by, int width, int height) {
    Matrix4 m;
    m.m.fill(0);
    const double W = width, H = height;
    m(0, 0) = 2 * ax / W;
    m(1, 1) = -2 * ay / H;
    if (perspective) {  // x' = (2ax/W) x + (2bx/W - 1) z, w = z: screen x = x'/z; z' = 1
        m(2, 0) = 2 * bx / W - 1;
        m(2, 1) = 1 - 2 * by / H;
        m(3, 2) = 1;
        m(2, 3) = 1;
    } else {
        m(3, 0) = 2 * bx / W - 1;
        m(3, 1) = 1 - 2 * by / H;
        m(2, 2) = 1;
        m(3, 3) = 1;
    }
    return m;
}

bool ShadowLookup::set(const DepthMap& map, const Matrix4& currentToWorld, std::string* error) {
    Matrix4 cameraToWorld;
    if (!invert(map.worldToCamera, &cameraToWorld)) {
        *error = "its world-to-camera matrix is singular";
        return false;
    }
    Matrix4 screenToWorld;
    if (!invert(map.worldToScreen, &screenToWorld)) {
        *error = "its world-to-screen matrix is singular";
        return false;
    }
    map_ = &map;
    toCamera_ = currentToWorld * map.worldToCamera;
    toScreen_ = currentToWorld * map.worldToScreen;
    cameraToScreen_ = cameraToWorld * map.worldToScreen;
    return true;
}

float ShadowLookup::occlusion(const Vec3d& p, const Vec3d& dpdu, const Vec3d& dpdv, const ShadowFilter& f) const {
    const DepthMap& map = *map_;
    const double W = map.width, H = map.height;
    // Texel coordinates (the depth pass's raster: x right, y down, pixel i over [i, i + 1)).
    auto texel = [&](const Vec3d& q, double* x, double* y) {
        const Hom h = homogeneous(toScreen_, q);
        if (!(h.w > 0)) return false;  // behind the light's camera
        *x = (h.x / h.w + 1) * 0.5 * W;
        *y = (1 - h.y / h.w) * 0.5 * H;
        return std::isfinite(*x) && std::isfinite(*y);
    };
    double tx, ty;
    if (!texel(p, &tx, &ty)) return 0;
    const Vec3d pc = toCamera_.point(p);
    const double zc = pc.z;

    // The footprint: the micropolygon's extent along u and v in texels, scaled, plus the blur.
    double fx = 0, fy = 0;
    for (const Vec3d& d : {dpdu, dpdv}) {
        double x, y;
        if ((d.x != 0 || d.y != 0 || d.z != 0) && texel(p + d, &x, &y))
            fx += std::fabs(x - tx), fy += std::fabs(y - ty);
    }
    const double hx = std::max(0.5, 0.5 * f.swidth * fx + 0.5 * f.sblur * W);
    const double hy = std::max(0.5, 0.5 * f.twidth * fy + 0.5 * f.tblur * H);
    const double x0 = tx - hx, x1 = tx + hx, y0 = ty - hy, y1 = ty + hy;
    if (x1 <= 0 || y1 <= 0 || x0 >= W || y0 >= H) return 0;  // wholly outside the map: unshadowed

    // The receiver's depth at a texel: where the texel's ray meets p's tangent plane. The ray of
    // screen point (sx, sy) is the camera points q with (q C).x = sx (q C).w and (q C).y = sy (q C).w;
    // with n . q = n . pc, Cramer's rule gives q.z = N / D, N and D bilinear in (sx, sy).
    const Vec3d n = cross(toCamera_.vector(dpdu), toCamera_.vector(dpdv));
    const double nn = dot(n, n);
    bool plane = nn > 0 && std::isfinite(nn);
    Bilinear N, D;
    if (plane) {
        const Matrix4& C = cameraToScreen_;
        const double np[3] = {n.x, n.y, n.z}, rhsPlane = dot(n, pc);
        double vN[4], vD[4];
        for (int k = 0; k < 4; ++k) {
            const double sx = k & 1, sy = k >> 1;
            const double r1[3] = {C(0, 0) - sx * C(0, 3), C(1, 0) - sx * C(1, 3), C(2, 0) - sx * C(2, 3)};
            const double r2[3] = {C(0, 1) - sy * C(0, 3), C(1, 1) - sy * C(1, 3), C(2, 1) - sy * C(2, 3)};
            const double b1 = -(C(3, 0) - sx * C(3, 3)), b2 = -(C(3, 1) - sy * C(3, 3));
            // Columns are the unknowns x, y, z: replace the z column by the right-hand side.
            const double c0[3] = {r1[0], r2[0], np[0]}, c1[3] = {r1[1], r2[1], np[1]}, c2[3] = {r1[2], r2[2], np[2]};
            const double rhs[3] = {b1, b2, rhsPlane};
            vD[k] = det3(c0, c1, c2);
            vN[k] = det3(c0, c1, rhs);
        }
        N = {vN[0], vN[1] - vN[0], vN[2] - vN[0], vN[3] - vN[1] - vN[2] + vN[0]};
        D = {vD[0], vD[1] - vD[0], vD[2] - vD[0], vD[3] - vD[1] - vD[2] + vD[0]};
    }
    // The receiver's depth at texel position (x, y), less what the texel's own samples may lie
    // nearer than its centre by (half a texel of the receiver's slope each way, there: under a
    // perspective light the slope grows across a wide footprint), the bias and rounding.
    auto behind = [&](double x, double y) {
        if (!plane) return zc - double(f.bias) - 1e-5 * std::fabs(zc);
        const double sx = 2 * x / W - 1, sy = 1 - 2 * y / H;
        const double d = D.at(sx, sy), num = N.at(sx, sy);
        const double z = num / d;
        // A ray nearly along the plane, or meeting it behind the camera: the point's own depth.
        if (!(std::isfinite(z) && (z > 0 || zc <= 0))) return zc - double(f.bias) - 1e-5 * std::fabs(zc);
        // dz/dx and dz/dy of N / D (sx = 2x / W - 1, sy = 1 - 2y / H).
        const double dzx = ((N.b + N.d * sy) * d - num * (D.b + D.d * sy)) / (d * d) * (2 / W);
        const double dzy = ((N.c + N.d * sx) * d - num * (D.c + D.d * sx)) / (d * d) * (-2 / H);
        return z - double(f.bias) - 0.5 * (std::fabs(dzx) + std::fabs(dzy)) - 1e-5 * std::fabs(z);
    };
    const int w = map.width, h = map.height;
    auto occluded = [&](int i, int j) {
        if (i < 0 || j < 0 || i >= w || j >= h) return false;
        const float zm = map.z[size_t(j) * size_t(w) + size_t(i)];
        return double(zm) < behind(i + 0.5, j + 0.5);
    };

    const int i0 = int(std::floor(x0)), i1 = int(std::ceil(x1)) - 1, j0 = int(std::floor(y0)),
              j1 = int(std::ceil(y1)) - 1;
    const double texels = double(i1 - i0 + 1) * double(j1 - j0 + 1);
    if (texels <= kExactTexels) {
        double blocked = 0;
        for (int j = j0; j <= j1; ++j) {
            const double wy = std::min(y1, double(j + 1)) - std::max(y0, double(j));
            for (int i = i0; i <= i1; ++i)
                if (occluded(i, j)) blocked += wy * (std::min(x1, double(i + 1)) - std::max(x0, double(i)));
        }
        return float(blocked / ((x1 - x0) * (y1 - y0)));
    }
    // Stratified taps, jittered by a hash of the point.
    const int m = std::max(1, int(std::ceil(std::sqrt(double(std::max(1, f.samples))))));
    uint64_t seed = mix(bitsOf(p.x) ^ mix(bitsOf(p.y) ^ mix(bitsOf(p.z))));
    int blocked = 0;
    for (int b = 0; b < m; ++b)
        for (int a = 0; a < m; ++a) {
            seed = mix(seed);
            const double ja = double(seed & 0xffffff) / double(1 << 24),
                         jb = double((seed >> 24) & 0xffffff) / double(1 << 24);
            const double x = x0 + (a + ja) / m * (x1 - x0), y = y0 + (b + jb) / m * (y1 - y0);
            blocked += occluded(int(std::floor(x)), int(std::floor(y)));
        }
    return float(double(blocked) / double(m * m));
}

void ShadowLookup::lookup(const sl::DirectionQuery& q, const ShadowFilter& f, float* out) const {
    for (int i = 0; i < q.n; ++i) {
        if (q.active && !q.active[i]) continue;
        const Vec3d p{q.R[0][i], q.R[1][i], q.R[2][i]};
        Vec3d du{0, 0, 0}, dv{0, 0, 0};
        if (q.dRdu[0]) du = {q.dRdu[0][i], q.dRdu[1][i], q.dRdu[2][i]};
        if (q.dRdv[0]) dv = {q.dRdv[0][i], q.dRdv[1][i], q.dRdv[2][i]};
        out[i] = occlusion(p, du, dv, f);
    }
}

}  // namespace streyes
