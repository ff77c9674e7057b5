#include "geom/subdivision.h"

#include <opensubdiv/bfr/refinerSurfaceFactory.h>
#include <opensubdiv/bfr/surface.h>
#include <opensubdiv/bfr/surfaceFactoryCache.h>
#include <opensubdiv/far/error.h>
#include <opensubdiv/far/primvarRefiner.h>
#include <opensubdiv/far/topologyDescriptor.h>
#include <tbb/parallel_for.h>

#include <array>
#include <cmath>
#include <mutex>
#include <shared_mutex>
#include <string>

namespace streyes {

namespace Bfr = OpenSubdiv::Bfr;
namespace Far = OpenSubdiv::Far;
namespace Sdc = OpenSubdiv::Sdc;

namespace {

using ThreadedCache = Bfr::SurfaceFactoryCacheThreaded<std::shared_mutex, std::shared_lock<std::shared_mutex>,
                                                       std::unique_lock<std::shared_mutex>>;
using SurfaceFactory = Bfr::RefinerSurfaceFactory<ThreadedCache>;
using Surface = Bfr::Surface<double>;
using PointDesc = Surface::PointDescriptor;

// Three doubles as Far's PrimvarRefiner wants them.
struct Point3 {
    double p[3];
    void Clear() { p[0] = p[1] = p[2] = 0; }
    void AddWithWeight(const Point3& s, double w) {
        for (int i = 0; i < 3; ++i) p[i] += w * s.p[i];
    }
};

// Far reports problems through a global callback: collect them for the error message.
thread_local std::string farMessages;
void farError(Far::ErrorType, const char* message) {
    if (!farMessages.empty()) farMessages += "; ";
    farMessages += message;
}

// A dyadic rectangle of an irregular face that lies in one leaf of Bfr's patch tree, and the
// patch points that leaf is a convex combination of.
struct Leaf {
    ParamRect rect;
    bool polynomial = false;  // a bicubic there (a B-spline leaf): its Bezier form is exact
    std::vector<int> support;
};

struct FaceInfo {
    int level1Face = 0;
    Surface surface;
    bool regular = false;
    std::vector<Leaf> leaves;  // irregular faces
};

constexpr int kMaxLeafDepth = 10;  // Bfr's trees are at most 6 deep (its sharp approximation level)

// The weights of all patch points at (u, v): Bfr evaluated with the identity as patch points.
class WeightProbe {
  public:
    explicit WeightProbe(const Surface& s) : s_(s), n_(s.GetNumPatchPoints()) {
        identity_.assign(size_t(n_) * size_t(n_), 0.0);
        for (int i = 0; i < n_; ++i) identity_[size_t(i) * size_t(n_) + size_t(i)] = 1;
        w_.resize(size_t(n_));
    }
    int size() const { return n_; }
    const std::vector<double>& weights(double u, double v) {
        const double uv[2] = {u, v};
        s_.Evaluate(uv, identity_.data(), PointDesc(n_), w_.data());
        return w_;
    }
    void support(double u, double v, std::vector<int>& out) {
        weights(u, v);
        out.clear();
        for (int j = 0; j < n_; ++j)
            if (w_[size_t(j)] != 0) out.push_back(j);
    }

  private:
    const Surface& s_;
    int n_;
    std::vector<double> identity_, w_;
};

double lerpD(double a, double b, double t) { return a + (b - a) * t; }

// The inverse of the 4x4 matrix of cubic Bernstein values at the parameters t: maps the values of
// a cubic at t[0..3] to its Bezier coefficients.
std::array<double, 16> bernsteinFitMatrix(const double t[4]) {
    double a[4][8];
    for (int i = 0; i < 4; ++i) {
        double b[4], d[4];
        bernstein(t[i], b, d);
        for (int j = 0; j < 4; ++j) a[i][j] = b[j], a[i][4 + j] = i == j ? 1 : 0;
    }
    for (int c = 0; c < 4; ++c) {  // Gauss-Jordan with partial pivoting
        int p = c;
        for (int r = c + 1; r < 4; ++r)
            if (std::fabs(a[r][c]) > std::fabs(a[p][c])) p = r;
        for (int k = 0; k < 8; ++k) std::swap(a[c][k], a[p][k]);
        const double inv = 1 / a[c][c];
        for (int k = 0; k < 8; ++k) a[c][k] *= inv;
        for (int r = 0; r < 4; ++r)
            if (r != c) {
                const double f = a[r][c];
                for (int k = 0; k < 8; ++k) a[r][k] -= f * a[c][k];
            }
    }
    std::array<double, 16> m;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) m[size_t(i * 4 + j)] = a[i][4 + j];
    return m;
}

// Whether every patch point's weight is one bicubic polynomial over r: fitted through 4x4 samples
// and compared at four other points. All of them lie strictly inside r: on r's border Bfr may
// evaluate with the neighbouring leaf, whose weights are on other patch points when it lies at
// another level of the tree (positions agree there, weights do not), which made regular leaves
// next to finer ones look irregular.
bool weightsArePolynomial(WeightProbe& probe, const ParamRect& r) {
    const int n = probe.size();
    static constexpr double kT[4] = {0.125, 0.375, 0.625, 0.875};
    static const std::array<double, 16> kInv = bernsteinFitMatrix(kT);
    std::vector<double> samples(size_t(16 * n));
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i) {
            const std::vector<double>& w = probe.weights(lerpD(r.u0, r.u1, kT[i]), lerpD(r.v0, r.v1, kT[j]));
            std::copy(w.begin(), w.end(), samples.begin() + (j * 4 + i) * n);
        }
    // Bezier coefficients of each weight, per direction.
    std::vector<double> rows(size_t(16 * n)), coef(size_t(16 * n));
    for (int l = 0; l < 4; ++l)
        for (int i = 0; i < 4; ++i)
            for (int c = 0; c < n; ++c) {
                double s = 0;
                for (int k = 0; k < 4; ++k) s += kInv[size_t(i * 4 + k)] * samples[size_t((l * 4 + k) * n + c)];
                rows[size_t((l * 4 + i) * n + c)] = s;
            }
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i)
            for (int c = 0; c < n; ++c) {
                double s = 0;
                for (int l = 0; l < 4; ++l) s += kInv[size_t(j * 4 + l)] * rows[size_t((l * 4 + i) * n + c)];
                coef[size_t((j * 4 + i) * n + c)] = s;
            }
    static constexpr double kCheck[4][2] = {{0.2113, 0.7071}, {0.8377, 0.2929}, {0.3821, 0.4142}, {0.6180, 0.9135}};
    for (const auto& q : kCheck) {
        double bu[4], bv[4], d[4];
        bernstein(q[0], bu, d);
        bernstein(q[1], bv, d);
        const std::vector<double>& w = probe.weights(lerpD(r.u0, r.u1, q[0]), lerpD(r.v0, r.v1, q[1]));
        for (int c = 0; c < n; ++c) {
            double fit = 0;
            for (int j = 0; j < 4; ++j)
                for (int i = 0; i < 4; ++i) fit += bu[i] * bv[j] * coef[size_t((j * 4 + i) * n + c)];
            if (std::fabs(fit - w[size_t(c)]) > 1e-9) return false;
        }
    }
    return true;
}

// Splits r into the cells of Bfr's tree: a dyadic cell whose four quadrant centres see the same
// patch points lies in one leaf (leaves are dyadic squares, so a leaf reaching into all four
// quadrants contains the cell; distinct leaves use distinct points).
void findLeaves(WeightProbe& probe, const ParamRect& r, int depth, std::vector<Leaf>& out) {
    std::vector<int> s[4];
    const double um = 0.5 * (r.u0 + r.u1), vm = 0.5 * (r.v0 + r.v1);
    for (int q = 0; q < 4; ++q)
        probe.support(0.5 * ((q & 1 ? um : r.u0) + (q & 1 ? r.u1 : um)), 0.5 * ((q & 2 ? vm : r.v0) + (q & 2 ? r.v1 : vm)),
                      s[q]);
    if (s[1] == s[0] && s[2] == s[0] && s[3] == s[0]) {
        out.push_back({r, weightsArePolynomial(probe, r), s[0]});
        return;
    }
    if (depth >= kMaxLeafDepth) {
        // Not resolved: bound the cell by every patch point, which always holds.
        Leaf all{r, false, {}};
        for (int j = 0; j < probe.size(); ++j) all.support.push_back(j);
        out.push_back(std::move(all));
        return;
    }
    for (int q = 0; q < 4; ++q)
        findLeaves(probe,
                   {q & 1 ? um : r.u0, q & 1 ? r.u1 : um, q & 2 ? vm : r.v0, q & 2 ? r.v1 : vm}, depth + 1, out);
}

Far::TopologyRefiner* createRefiner(const Far::TopologyDescriptor& d, const Sdc::Options& options) {
    using Factory = Far::TopologyRefinerFactory<Far::TopologyDescriptor>;
    return Factory::Create(d, Factory::Options(Sdc::SCHEME_CATMARK, options));
}

// Evaluates a surface at the 16 points u, v in {0, 1/3, 2/3, 1} of r: its Bezier form there.
BezierPatch bezierOf(const Surface& s, const double* patchPoints, const ParamRect& r) {
    Vec3d samples[16];
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i) {
            const double uv[2] = {lerpD(r.u0, r.u1, i / 3.0), lerpD(r.v0, r.v1, j / 3.0)};
            double p[3];
            s.Evaluate(uv, patchPoints, PointDesc(3), p);
            samples[j * 4 + i] = {p[0], p[1], p[2]};
        }
    return fitBezier(samples);
}

bool overlaps(const ParamRect& a, const ParamRect& b) {
    return a.u0 < b.u1 && b.u0 < a.u1 && a.v0 < b.v1 && b.v0 < a.v1;
}
bool contains(const ParamRect& outer, const ParamRect& r) {
    return outer.u0 <= r.u0 && r.u1 <= outer.u1 && outer.v0 <= r.v0 && r.v1 <= outer.v1;
}
// r in the coordinates of `outer`.
ParamRect relative(const ParamRect& outer, const ParamRect& r) {
    const double du = outer.u1 - outer.u0, dv = outer.v1 - outer.v0;
    return {(r.u0 - outer.u0) / du, (r.u1 - outer.u0) / du, (r.v0 - outer.v0) / dv, (r.v1 - outer.v0) / dv};
}

}  // namespace

// ---- Topology ---------------------------------------------------------------------------------------
struct SubdivisionShape::Impl {
    Sdc::Options options;
    std::unique_ptr<Far::TopologyRefiner> base;    // the mesh, refined uniformly to level 1
    std::unique_ptr<Far::TopologyRefiner> level1;  // level 1 as the base of a new refiner, for Bfr
    std::unique_ptr<SurfaceFactory> factory;
    std::vector<FaceInfo> faces;                   // the level-1 faces with a limit surface
    std::vector<int> parentFace;                   // level-1 face -> base face
    std::shared_ptr<const SurfaceTopology> topology;
    int irregular = 0;
    bool faceVarying = false;  // the base refiner carries channel 0: one value per face vertex
};

struct SubdivisionKey::Data {
    std::vector<BezierPatch> bezier;                   // regular faces
    std::vector<std::vector<double>> patchPoints;      // irregular faces: Bfr's patch points, x y z
    std::vector<std::vector<BezierPatch>> leafBezier;  // irregular faces: per leaf (polynomial ones)
    std::vector<std::vector<Bounds3f>> leafBox;        // irregular faces: per leaf
};

SubdivisionKey::SubdivisionKey(std::unique_ptr<Data> data) : data_(std::move(data)) {}
SubdivisionKey::~SubdivisionKey() = default;

SubdivisionShape::SubdivisionShape(const SubdivisionMeshDesc& desc) : impl_(std::make_unique<Impl>()) {
    Impl& m = *impl_;
    using BI = Sdc::Options::VtxBoundaryInterpolation;
    m.options.SetVtxBoundaryInterpolation(desc.interpolateBoundary == 1   ? BI::VTX_BOUNDARY_EDGE_AND_CORNER
                                          : desc.interpolateBoundary == 2 ? BI::VTX_BOUNDARY_EDGE_ONLY
                                                                          : BI::VTX_BOUNDARY_NONE);
    Far::SetErrorCallback(farError);
    farMessages.clear();
    auto fail = [&](const std::string& what) {
        throw InputError(desc.loc, "SubdivisionMesh: " + what + (farMessages.empty() ? "" : " (" + farMessages + ")"));
    };

    Far::TopologyDescriptor d;
    d.numVertices = desc.vertexCount;
    d.numFaces = int(desc.faceSizes.size());
    d.numVertsPerFace = desc.faceSizes.data();
    d.vertIndicesPerFace = desc.faceVertices.data();
    d.numCreases = int(desc.creaseSharpness.size());
    d.creaseVertexIndexPairs = desc.creaseEdges.data();
    d.creaseWeights = desc.creaseSharpness.data();
    d.numCorners = int(desc.corners.size());
    d.cornerVertexIndices = desc.corners.data();
    d.cornerWeights = desc.cornerSharpness.data();
    d.numHoles = int(desc.holes.size());
    d.holeIndices = desc.holes.data();
    // Facevarying values (one per face vertex, as given): a channel refined linearly, so that each
    // level-1 face's corners hold the bilinear interpolation RenderMan gives them.
    bool faceVarying = desc.Cs.given() && desc.Cs.cls == ParamClass::FaceVarying;
    for (const Param& v : desc.primvars.params) faceVarying = faceVarying || v.cls == ParamClass::FaceVarying;
    std::vector<int> fvarIndices;
    Far::TopologyDescriptor::FVarChannel channel;
    if (faceVarying) {
        fvarIndices.resize(desc.faceVertices.size());
        for (size_t i = 0; i < fvarIndices.size(); ++i) fvarIndices[i] = int(i);
        channel.numValues = int(fvarIndices.size());
        channel.valueIndices = fvarIndices.data();
        d.numFVarChannels = 1;
        d.fvarChannels = &channel;
        m.options.SetFVarLinearInterpolation(Sdc::Options::FVAR_LINEAR_ALL);
        m.faceVarying = true;
    }
    m.base.reset(createRefiner(d, m.options));
    if (!m.base) fail("OpenSubdiv rejected the topology");
    Far::TopologyRefiner::UniformOptions uniform(1);
    uniform.fullTopologyInLastLevel = true;
    m.base->RefineUniform(uniform);

    // Level 1 as a mesh of its own: its faces, edge and vertex sharpness and holes.
    const Far::TopologyLevel& L = m.base->GetLevel(1);
    std::vector<int> sizes(size_t(L.GetNumFaces()), 4), verts, creases, cornerVerts, holes;
    std::vector<float> creaseWeights, cornerWeights;
    for (int f = 0; f < L.GetNumFaces(); ++f) {
        Far::ConstIndexArray fv = L.GetFaceVertices(f);
        sizes[size_t(f)] = fv.size();
        for (int i = 0; i < fv.size(); ++i) verts.push_back(fv[i]);
        if (L.IsFaceHole(f)) holes.push_back(f);
    }
    for (int e = 0; e < L.GetNumEdges(); ++e)
        if (L.GetEdgeSharpness(e) > 0) {
            Far::ConstIndexArray ev = L.GetEdgeVertices(e);
            creases.push_back(ev[0]);
            creases.push_back(ev[1]);
            creaseWeights.push_back(L.GetEdgeSharpness(e));
        }
    for (int v = 0; v < L.GetNumVertices(); ++v)
        if (L.GetVertexSharpness(v) > 0) {
            cornerVerts.push_back(v);
            cornerWeights.push_back(L.GetVertexSharpness(v));
        }
    Far::TopologyDescriptor d1;
    d1.numVertices = L.GetNumVertices();
    d1.numFaces = L.GetNumFaces();
    d1.numVertsPerFace = sizes.data();
    d1.vertIndicesPerFace = verts.data();
    d1.numCreases = int(creaseWeights.size());
    d1.creaseVertexIndexPairs = creases.data();
    d1.creaseWeights = creaseWeights.data();
    d1.numCorners = int(cornerWeights.size());
    d1.cornerVertexIndices = cornerVerts.data();
    d1.cornerWeights = cornerWeights.data();
    d1.numHoles = int(holes.size());
    d1.holeIndices = holes.data();
    m.level1.reset(createRefiner(d1, m.options));
    if (!m.level1) fail("OpenSubdiv could not rebuild the refined mesh");

    m.parentFace.assign(size_t(L.GetNumFaces()), 0);
    const Far::TopologyLevel& L0 = m.base->GetLevel(0);
    for (int f = 0; f < L0.GetNumFaces(); ++f) {
        Far::ConstIndexArray children = L0.GetFaceChildFaces(f);
        for (int i = 0; i < children.size(); ++i) m.parentFace[size_t(children[i])] = f;
    }

    // One Bfr surface per face with a limit surface, made in parallel through the threaded cache.
    m.factory = std::make_unique<SurfaceFactory>(*m.level1);
    for (int f = 0; f < L.GetNumFaces(); ++f)
        if (sizes[size_t(f)] == 4 && m.factory->FaceHasLimitSurface(f)) m.faces.push_back(FaceInfo{f, {}, false, {}});
    tbb::parallel_for(size_t(0), m.faces.size(), [&](size_t i) {
        FaceInfo& fi = m.faces[i];
        m.factory->InitVertexSurface(fi.level1Face, &fi.surface);
        fi.regular = fi.surface.IsValid() && fi.surface.IsRegular();
        if (fi.surface.IsValid() && !fi.regular) {
            WeightProbe probe(fi.surface);
            findLeaves(probe, {0, 1, 0, 1}, 0, fi.leaves);
        }
    });
    std::vector<FaceInfo> valid;
    for (FaceInfo& fi : m.faces)
        if (fi.surface.IsValid()) valid.push_back(std::move(fi));
    m.faces = std::move(valid);

    // Corners in patch order: Bfr's quad parameterisation puts face vertex i at (0,0), (1,0),
    // (1,1), (0,1).
    // Sides in patch order run fv0-fv1, fv1-fv2, fv3-fv2, fv0-fv3: Far's face edges 0 to 3, the
    // last two backwards; each is reversed when it runs against Far's edge.
    std::vector<SurfaceTopology::Face> faces;
    for (const FaceInfo& fi : m.faces) {
        Far::ConstIndexArray fv = L.GetFaceVertices(fi.level1Face);
        Far::ConstIndexArray fe = L.GetFaceEdges(fi.level1Face);
        SurfaceTopology::Face f;
        f.corner = {fv[0], fv[1], fv[3], fv[2]};
        const int from[4] = {fv[0], fv[1], fv[3], fv[0]};
        for (int k = 0; k < 4; ++k) {
            f.side[size_t(k)] = fe[k];
            f.reversed[size_t(k)] = L.GetEdgeVertices(fe[k])[0] != from[k];
        }
        faces.push_back(f);
        m.irregular += fi.regular ? 0 : 1;
    }
    m.topology = SurfaceTopology::build(std::move(faces), L.GetNumVertices(), L.GetNumEdges());
}

SubdivisionShape::~SubdivisionShape() = default;

int SubdivisionShape::faceCount() const { return int(impl_->faces.size()); }
int SubdivisionShape::irregularFaceCount() const { return impl_->irregular; }
const std::shared_ptr<const SurfaceTopology>& SubdivisionShape::topology() const { return impl_->topology; }

namespace {
// Refines per-vertex values of the base mesh to level 1 (smoothly, or linearly for varying ones).
std::vector<double> refineToLevel1(const Far::TopologyRefiner& base, const std::vector<Vec3d>& values, bool varying) {
    std::vector<Point3> src(values.size()), dst(size_t(base.GetLevel(1).GetNumVertices()));
    for (size_t i = 0; i < values.size(); ++i) src[i] = {{values[i].x, values[i].y, values[i].z}};
    Far::PrimvarRefinerReal<double> refiner(base);
    Point3* out = dst.data();
    if (varying) refiner.InterpolateVarying(1, src.data(), out);
    else refiner.Interpolate(1, src.data(), out);
    std::vector<double> flat(dst.size() * 3);
    for (size_t i = 0; i < dst.size(); ++i)
        for (int c = 0; c < 3; ++c) flat[i * 3 + size_t(c)] = dst[i].p[c];
    return flat;
}
}  // namespace

std::shared_ptr<const SubdivisionKey> SubdivisionShape::key(const std::vector<Vec3d>& P) const {
    const Impl& m = *impl_;
    const std::vector<double> level1 = refineToLevel1(*m.base, P, false);
    auto data = std::make_unique<SubdivisionKey::Data>();
    SubdivisionKey::Data& d = *data;
    const size_t n = m.faces.size();
    d.bezier.resize(n);
    d.patchPoints.resize(n);
    d.leafBezier.resize(n);
    d.leafBox.resize(n);
    tbb::parallel_for(size_t(0), n, [&](size_t f) {
        const FaceInfo& fi = m.faces[f];
        std::vector<double> pp(size_t(fi.surface.GetNumPatchPoints()) * 3);
        fi.surface.PreparePatchPoints(level1.data(), PointDesc(3), pp.data(), PointDesc(3));
        if (fi.regular) {
            d.bezier[f] = bezierOf(fi.surface, pp.data(), {0, 1, 0, 1});
            return;
        }
        for (const Leaf& leaf : fi.leaves) {
            Bounds3f box;
            if (leaf.polynomial) {
                d.leafBezier[f].push_back(bezierOf(fi.surface, pp.data(), leaf.rect));
                box = bezierBound(d.leafBezier[f].back());
            } else {
                d.leafBezier[f].push_back({});
                for (int j : leaf.support) box.extend(Vec3f(float(pp[size_t(j) * 3]), float(pp[size_t(j) * 3 + 1]),
                                                            float(pp[size_t(j) * 3 + 2])));
            }
            d.leafBox[f].push_back(padded(box));
        }
        d.patchPoints[f] = std::move(pp);
    });
    return std::make_shared<SubdivisionKey>(std::move(data));
}

std::vector<std::array<Color, 4>> SubdivisionShape::colors(const ColorPrimvar& Cs, Color color) const {
    const Impl& m = *impl_;
    std::vector<std::array<Color, 4>> out(m.faces.size());
    for (auto& c : out) c.fill(color);
    if (!Cs.given()) return out;
    if (Cs.cls == ParamClass::Constant) {
        for (auto& c : out) c.fill(Cs.values[0]);
        return out;
    }
    if (Cs.cls == ParamClass::Uniform) {
        for (size_t f = 0; f < out.size(); ++f) out[f].fill(Cs.values[size_t(m.parentFace[size_t(m.faces[f].level1Face)])]);
        return out;
    }
    const Far::TopologyLevel& L = m.base->GetLevel(1);
    const int order[4] = {0, 1, 3, 2};
    if (Cs.cls == ParamClass::FaceVarying) {
        if (!m.faceVarying) return out;  // the shape was built without its channel: none was given
        std::vector<Point3> src(Cs.values.size()), dst(size_t(L.GetNumFVarValues(0)));
        for (size_t i = 0; i < src.size(); ++i) src[i] = {{Cs.values[i].x, Cs.values[i].y, Cs.values[i].z}};
        Far::PrimvarRefinerReal<double> refiner(*m.base);
        Point3* to = dst.data();
        refiner.InterpolateFaceVarying(1, src.data(), to, 0);
        for (size_t f = 0; f < out.size(); ++f) {
            Far::ConstIndexArray fvv = L.GetFaceFVarValues(m.faces[f].level1Face, 0);
            for (int c = 0; c < 4; ++c) {
                const Point3& v = dst[size_t(fvv[order[c]])];
                out[f][size_t(c)] = Color(float(v.p[0]), float(v.p[1]), float(v.p[2]));
            }
        }
        return out;
    }
    std::vector<Vec3d> values(Cs.values.begin(), Cs.values.end());
    const bool varying = Cs.cls != ParamClass::Vertex;
    const std::vector<double> level1 = refineToLevel1(*m.base, values, varying);
    for (size_t f = 0; f < out.size(); ++f) {
        const FaceInfo& fi = m.faces[f];
        Far::ConstIndexArray fv = L.GetFaceVertices(fi.level1Face);
        if (varying) {
            for (int c = 0; c < 4; ++c) {
                const double* v = &level1[size_t(fv[order[c]]) * 3];
                out[f][size_t(c)] = Color(float(v[0]), float(v[1]), float(v[2]));
            }
        } else {
            // Vertex colours are smooth like positions: their limit at the face's corners.
            std::vector<double> pp(size_t(fi.surface.GetNumPatchPoints()) * 3);
            fi.surface.PreparePatchPoints(level1.data(), PointDesc(3), pp.data(), PointDesc(3));
            for (int c = 0; c < 4; ++c) {
                double u, v, p[3];
                cornerParam(c, &u, &v);
                const double uv[2] = {u, v};
                fi.surface.Evaluate(uv, pp.data(), PointDesc(3), p);
                out[f][size_t(c)] = Color(float(p[0]), float(p[1]), float(p[2]));
            }
        }
    }
    return out;
}

// ---- One motion segment -----------------------------------------------------------------------------
SubdivisionMesh::SubdivisionMesh(std::shared_ptr<const SubdivisionShape> shape,
                                 std::shared_ptr<const SubdivisionKey> key0, std::shared_ptr<const SubdivisionKey> key1,
                                 TimeSpan keys, const Material* material, const Camera* camera,
                                 std::vector<std::array<Color, 4>> colors)
    : SurfaceMesh(shape->topology(), keys, material, camera), shape_(std::move(shape)), key0_(std::move(key0)),
      key1_(std::move(key1)) {
    moving_ = keys.t1 > keys.t0 && key1_ != key0_;
    colors_ = std::move(colors);
}

bool SubdivisionMesh::regular(int f) const { return shape_->impl().faces[size_t(f)].regular; }

bool SubdivisionMesh::faceMoving(int f) const {
    if (!moving()) return false;
    const SubdivisionKey::Data &a = key0_->data(), &b = key1_->data();
    return a.bezier[size_t(f)] != b.bezier[size_t(f)] || a.patchPoints[size_t(f)] != b.patchPoints[size_t(f)];
}

void SubdivisionMesh::derivatives(int f, double u, double v, int k, Vec3d* P, Vec3d* dPdu, Vec3d* dPdv) const {
    const SubdivisionKey::Data& d = key(k);
    const std::vector<double>& pp = d.patchPoints[size_t(f)];
    if (pp.empty()) {
        evalBezier(d.bezier[size_t(f)], u, v, P, dPdu, dPdv);
        return;
    }
    const double uv[2] = {u, v};
    double p[3], du[3], dv[3];
    shape_->impl().faces[size_t(f)].surface.Evaluate(uv, pp.data(), PointDesc(3), p, du, dv);
    *P = {p[0], p[1], p[2]};
    *dPdu = {du[0], du[1], du[2]};
    *dPdv = {dv[0], dv[1], dv[2]};
}

Bounds3f SubdivisionMesh::bound(int f, const ParamRect& r, int k) const {
    const SubdivisionKey::Data& d = key(k);
    if (d.patchPoints[size_t(f)].empty())
        return paddedBound(bezierSubPatch(d.bezier[size_t(f)], r.u0, r.u1, r.v0, r.v1).data(), 16);
    const std::vector<Leaf>& leaves = shape_->impl().faces[size_t(f)].leaves;
    Bounds3f b;
    for (size_t i = 0; i < leaves.size(); ++i) {
        if (!overlaps(leaves[i].rect, r)) continue;
        if (leaves[i].polynomial) {
            const ParamRect q = relative(leaves[i].rect, r);
            b.extend(paddedBound(bezierSubPatch(d.leafBezier[size_t(f)][i], std::max(0.0, q.u0), std::min(1.0, q.u1),
                                                std::max(0.0, q.v0), std::min(1.0, q.v1))
                                     .data(),
                                 16));
        } else {
            b.extend(d.leafBox[size_t(f)][i]);
        }
    }
    return b;
}

bool SubdivisionMesh::bezier(int f, const ParamRect& r, int k, BezierPatch* cp) const {
    const SubdivisionKey::Data& d = key(k);
    if (d.patchPoints[size_t(f)].empty()) {
        *cp = bezierSubPatch(d.bezier[size_t(f)], r.u0, r.u1, r.v0, r.v1);
        return true;
    }
    const std::vector<Leaf>& leaves = shape_->impl().faces[size_t(f)].leaves;
    for (size_t i = 0; i < leaves.size(); ++i) {
        if (!leaves[i].polynomial || !contains(leaves[i].rect, r)) continue;
        const ParamRect q = relative(leaves[i].rect, r);
        *cp = bezierSubPatch(d.leafBezier[size_t(f)][i], q.u0, q.u1, q.v0, q.v1);
        return true;
    }
    return false;
}

}  // namespace streyes
