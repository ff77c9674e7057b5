#include "geom/curves.h"

#include <cmath>

namespace streyes {

namespace {

// A unit vector perpendicular to a and b, or to a alone where a and b are parallel (a curve
// running straight at the eye): the ribbon then keeps some width rather than none.
Vec3d sideDirection(Vec3d a, Vec3d b) {
    Vec3d s = cross(a, b);
    if (dot(s, s) > 1e-24 * dot(a, a) * dot(b, b) && dot(s, s) > 0) return normalize(s);
    s = cross(a, Vec3d(1, 0, 0));
    if (dot(s, s) < 1e-6 * dot(a, a)) s = cross(a, Vec3d(0, 1, 0));
    return dot(s, s) > 0 ? normalize(s) : Vec3d(1, 0, 0);
}

// The first of the differences that is not zero: a segment's end tangent where control points repeat.
Vec3d firstNonZero(std::initializer_list<Vec3d> ds) {
    for (const Vec3d& d : ds)
        if (dot(d, d) > 0) return d;
    return {0, 0, 0};
}

}  // namespace

CurveRibbons::CurveRibbons(const CurvesDesc& d)
    : desc_(d), cubic_(d.cubic), step_(d.cubic ? d.basis.step : 1), toBezier_(basisToBezier(d.basis)) {
    // Vertices: the two sides (v = 0, v = 1) of every joint. Edges: every joint's cross-section,
    // then each segment's two long sides.
    std::vector<SurfaceTopology::Face> faces;
    int joints = 0, vertices = 0;
    for (size_t c = 0; c < d.nvertices.size(); ++c) {
        const int segs = d.segments(c), nj = d.varying(c);
        vertexOffset_.push_back(vertices);
        jointOffset_.push_back(joints);
        for (int s = 0; s < segs; ++s) segments_.push_back({int(c), s * step_, joints + s, joints + (s + 1) % nj});
        for (int j = 0; j < nj; ++j) curveOfJoint_.push_back(int(c));
        joints += nj;
        vertices += d.nvertices[c];
    }
    const int n = int(segments_.size());
    for (int f = 0; f < n; ++f) {
        const Segment& s = segments_[size_t(f)];
        SurfaceTopology::Face face;
        face.corner = {2 * s.joint0, 2 * s.joint1, 2 * s.joint0 + 1, 2 * s.joint1 + 1};
        face.side = {joints + f, s.joint1, joints + n + f, s.joint0};
        faces.push_back(face);
    }
    topology_ = SurfaceTopology::build(std::move(faces), 2 * joints, joints + 2 * n);
}

// Uniform: the curve's; varying: the joint's; vertex: the curve there (the basis at the joint's
// segment end); constant: the one value.
template <typename V>
V CurveRibbons::atJoint(ParamClass cls, const std::vector<V>& values, int joint) const {
    const int c = curveOfJoint_[size_t(joint)];
    switch (cls) {
    case ParamClass::Constant: return values[0];
    case ParamClass::Uniform: return values[size_t(c)];
    case ParamClass::Vertex: {
        const int n = desc_.nvertices[size_t(c)], local = joint - jointOffset_[size_t(c)];
        const V* v = &values[size_t(vertexOffset_[size_t(c)])];
        if (!cubic_) return v[local % n];
        const int segs = desc_.segments(size_t(c));
        const bool end = local == segs;  // the far end of a nonperiodic curve
        const int first = (end ? segs - 1 : local) * step_;
        const std::array<double, 16>& m = desc_.basis.m;
        V r = v[0] * 0.0;
        for (int k = 0; k < 4; ++k) {
            const double w = end ? m[size_t(k)] + m[size_t(4 + k)] + m[size_t(8 + k)] + m[size_t(12 + k)] : m[size_t(12 + k)];
            r = r + v[(first + k) % n] * w;
        }
        return r;
    }
    default: return values[size_t(joint)];  // varying, facevarying
    }
}

std::vector<BezierPatch> CurveRibbons::patches(const std::vector<Vec3d>& P, const Matrix4& toCamera,
                                               bool perspective) const {
    const CurvesDesc& d = desc_;
    // Widths scale with the transform (by its mean scale); normals go by its inverse transpose.
    const double det = toCamera(0, 0) * (toCamera(1, 1) * toCamera(2, 2) - toCamera(1, 2) * toCamera(2, 1)) -
                       toCamera(0, 1) * (toCamera(1, 0) * toCamera(2, 2) - toCamera(1, 2) * toCamera(2, 0)) +
                       toCamera(0, 2) * (toCamera(1, 0) * toCamera(2, 1) - toCamera(1, 1) * toCamera(2, 0));
    const double widthScale = std::cbrt(std::fabs(det));
    Matrix4 inverse;
    const bool oriented = !d.N.empty() && invert(toCamera, &inverse);

    // Each segment's centre line in Bezier form.
    std::vector<std::array<Vec3d, 4>> centre(segments_.size());
    for (size_t f = 0; f < segments_.size(); ++f) {
        const Segment& s = segments_[f];
        const int n = d.nvertices[size_t(s.curve)];
        const Vec3d* cp = &P[size_t(vertexOffset_[size_t(s.curve)])];
        std::array<Vec3d, 4>& q = centre[f];
        if (!cubic_) {
            const Vec3d a = cp[s.first % n], b = cp[(s.first + 1) % n];
            q = {a, lerp(a, b, 1.0 / 3), lerp(a, b, 2.0 / 3), b};
            continue;
        }
        for (int i = 0; i < 4; ++i) {
            Vec3d r{0, 0, 0};
            for (int k = 0; k < 4; ++k) r = r + cp[(s.first + k) % n] * toBezier_[size_t(i * 4 + k)];
            q[size_t(i)] = r;
        }
    }
    // Joints: one point (the start of the segment leaving it, else the end of the one arriving),
    // the mean of the unit tangents arriving and leaving, the side direction and the width.
    const size_t joints = curveOfJoint_.size();
    std::vector<Vec3d> point(joints), tangent(joints, Vec3d(0, 0, 0)), side(joints), normal(joints);
    std::vector<double> width(joints);
    std::vector<bool> placed(joints, false);
    for (size_t f = 0; f < segments_.size(); ++f) {
        const Segment& s = segments_[f];
        const std::array<Vec3d, 4>& q = centre[f];
        point[size_t(s.joint0)] = q[0];
        placed[size_t(s.joint0)] = true;
        if (!placed[size_t(s.joint1)]) point[size_t(s.joint1)] = q[3];
        tangent[size_t(s.joint0)] += normalize(firstNonZero({q[1] - q[0], q[2] - q[0], q[3] - q[0]}));
        tangent[size_t(s.joint1)] += normalize(firstNonZero({q[3] - q[2], q[3] - q[1], q[3] - q[0]}));
    }
    for (size_t j = 0; j < joints; ++j) {
        width[j] = std::max(0.0, atJoint(d.widthClass, d.width, int(j))) * widthScale;
        if (oriented) {
            const Vec3d n = atJoint(d.normalClass, d.N, int(j));
            const Vec3d nc{inverse(0, 0) * n.x + inverse(0, 1) * n.y + inverse(0, 2) * n.z,
                           inverse(1, 0) * n.x + inverse(1, 1) * n.y + inverse(1, 2) * n.z,
                           inverse(2, 0) * n.x + inverse(2, 1) * n.y + inverse(2, 2) * n.z};
            normal[j] = nc;
            side[j] = sideDirection(tangent[j], nc);
        } else {
            side[j] = sideDirection(tangent[j], perspective ? point[j] : Vec3d(0, 0, 1));
        }
    }
    std::vector<BezierPatch> out(segments_.size());
    for (size_t f = 0; f < segments_.size(); ++f) {
        const Segment& s = segments_[f];
        std::array<Vec3d, 4> q = centre[f];
        const size_t a = size_t(s.joint0), b = size_t(s.joint1);
        q[0] = point[a];
        q[3] = point[b];
        // The half-width offset at u = 0, 1/3, 2/3, 1: the joints' at the ends, and across the
        // curve's own tangent (and the line of sight, or the normal blended from the joints') at
        // u = 1/3 and 2/3, with the width linear in u. The cubic through these four is exact for
        // a straight ribbon, and keeps a bent segment's width where a blend of the ends' directions
        // would narrow it.
        Vec3d h[4];
        h[0] = side[a] * (0.5 * width[a]);
        h[3] = side[b] * (0.5 * width[b]);
        for (int i = 1; i <= 2; ++i) {
            const double u = i / 3.0, v = 1 - u;
            const Vec3d c = q[0] * (v * v * v) + q[1] * (3 * u * v * v) + q[2] * (3 * u * u * v) + q[3] * (u * u * u);
            Vec3d t = (q[1] - q[0]) * (v * v) + (q[2] - q[1]) * (2 * u * v) + (q[3] - q[2]) * (u * u);
            if (!(dot(t, t) > 0)) t = lerp(tangent[a], tangent[b], u);
            Vec3d dir = sideDirection(t, oriented ? lerp(normal[a], normal[b], u) : perspective ? c : Vec3d(0, 0, 1));
            if (dot(dir, side[a] + side[b]) < 0) dir = -dir;  // the same side as the joints'
            h[i] = dir * (0.5 * lerp(width[a], width[b], u));
        }
        const Vec3d o[4] = {h[0], (h[0] * -5.0 + h[1] * 18.0 - h[2] * 9.0 + h[3] * 2.0) / 6.0,
                            (h[0] * 2.0 - h[1] * 9.0 + h[2] * 18.0 - h[3] * 5.0) / 6.0, h[3]};
        for (int i = 0; i < 4; ++i) {
            const Vec3d lo = q[size_t(i)] - o[i], hi = q[size_t(i)] + o[i];
            for (int r = 0; r < 4; ++r) out[f][size_t(r * 4 + i)] = Vec3f(r == 0 ? lo : r == 3 ? hi : lerp(lo, hi, r / 3.0));
        }
    }
    return out;
}

std::vector<std::array<Color, 4>> CurveRibbons::colors(Color color) const {
    std::vector<std::array<Color, 4>> out(segments_.size());
    const ColorPrimvar& cs = desc_.Cs;
    for (size_t f = 0; f < segments_.size(); ++f) {
        if (!cs.given()) {
            out[f].fill(color);
            continue;
        }
        const Color a = atJoint(cs.cls, cs.values, segments_[f].joint0);
        const Color b = atJoint(cs.cls, cs.values, segments_[f].joint1);
        out[f] = {a, b, a, b};
    }
    return out;
}

}  // namespace streyes
