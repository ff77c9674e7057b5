#include "shade/grid_shader.h"

#include <algorithm>
#include <cmath>

#include "bodies/material.h"
#include "shade/shading.h"

namespace streyes {

namespace {
// An opacity in [0, 1] per channel; NaN is opaque (a shader's bad value must not hide what is behind).
Color clampOpacity(Color o) {
    auto c = [](float v) { return v >= 0 ? (v <= 1 ? v : 1.0f) : (v < 0 ? 0.0f : 1.0f); };
    return {c(o.x), c(o.y), c(o.z)};
}
}  // namespace

GridShader::GridShader(const SceneShaders* shaders, const Camera& camera, const LightSet& lights)
    : shaders_(shaders), camera_(camera), lights_(lights) {}

GridShader::~GridShader() = default;

void GridShader::takeCounters(RenderCounters& out) {
    out.pointsShadedBuiltin += builtinPoints_;
    builtinPoints_ = 0;
    out.shadingBatchRuns += batchRuns_;
    out.shadingBatchedGrids += batchedGrids_;
    batchRuns_ = batchedGrids_ = 0;
    if (!vm_) return;
    const sl::ShadeStats& s = vm_->stats();
    out.pointsShadedSurface += s.points;
    out.lightShaderRuns += s.lightRuns;
    out.shadingSanitised += s.sanitised;
    out.shadingIndicesClamped += s.indicesClamped;
    out.shadingLoopsStopped += s.loopsStopped;
    vm_->resetStats();
}

Color GridShader::shadeHit(const Material& m, Color cs, Vec3f p, Vec3f n, double time, float u, float v,
                          uint64_t primitiveId, Color* shadowed, int slots, Color* opacity,
                          const float* primvarCorners) {
    hit_.shadowSlots = slots;
    hit_.resize(0, 0, false);
    hit_.material = &m;
    hit_.primitiveId = primitiveId;
    hit_.primvarCorners = primvarCorners;
    hit_.t0 = hit_.t1 = time;
    hit_.u0 = hit_.u1 = u;
    hit_.v0 = hit_.v1 = v;
    hit_.P[0][0] = p;
    hit_.N[0][0] = m.flipNormals ? -n : n;  // Orientation, as for diced grids
    hit_.Cs[0] = cs;
    if (m.surface || m.atmosphere) prepare(m, hit_, 0, time);
    shadeSurface(hit_, 0, time);  // a hit on the traced surface: not displaced again
    for (int k = 0; k < slots; ++k) shadowed[k] = hit_.Cl[0][size_t(k)];
    if (opacity) *opacity = hit_.Oi[0].empty() ? Color{1, 1, 1} : hit_.Oi[0][0];
    return hit_.Ci[0][0];
}

void GridShader::shade(Grid& grid) {
    for (int k = 0; k < (grid.moving ? 2 : 1); ++k) shadeSlot(grid, k, k == 0 ? grid.t0 : grid.t1);
}

void GridShader::shade(Grid& grid, const uint8_t* need) {
    const Material& m = *grid.material;
    if (m.surface || m.displacement || m.atmosphere || depthLayers_ || aovs_ || !need) {
        shade(grid);
        return;
    }
    for (int k = 0; k < (grid.moving ? 2 : 1); ++k) shadeSurface(grid, k, k == 0 ? grid.t0 : grid.t1, need);
}

Color GridShader::runVolume(const Material& m, const sl::ShaderInstance& shader, const MotionTransform* shaderToWorld,
                            Vec3f from, Vec3f to, double time, Color ci, Color* oi) {
    hit_.shadowSlots = 0;
    hit_.resize(0, 0, false);
    hit_.material = &m;
    hit_.primitiveId = 0;
    hit_.primvarCorners = nullptr;
    hit_.t0 = hit_.t1 = time;
    hit_.u0 = hit_.u1 = hit_.v0 = hit_.v1 = 0;
    hit_.P[0][0] = to;
    hit_.N[0][0] = normalize(to - from);
    hit_.Cs[0] = m.Cs;
    prepare(m, hit_, 0, time);
    volumeI_ = to - from;
    volumeE_ = from;
    volumeCi_ = ci;
    volumeOi_ = *oi;
    sgrid_.set(sl::Global::I, sl::ValueRef::aos(&volumeI_));
    sgrid_.set(sl::Global::E, sl::ValueRef::uniform(volumeE_));
    sgrid_.set(sl::Global::Ci, sl::ValueRef::aos(&volumeCi_));
    sgrid_.set(sl::Global::Oi, sl::ValueRef::aos(&volumeOi_));
    useShaderSpace(shaderToWorld, nullptr, time);
    vm_->run(shader, sgrid_, {});
    const sl::ValueRef rc = vm_->result(sl::Global::Ci), ro = vm_->result(sl::Global::Oi);
    if (ro.valid()) *oi = ro.vec(0);
    return rc.valid() ? rc.vec(0) : ci;
}

void GridShader::displaceOnly(Grid& grid) {
    const Material& m = *grid.material;
    if (!m.displacement) return;
    for (int k = 0; k < (grid.moving ? 2 : 1); ++k) {
        const double time = k == 0 ? grid.t0 : grid.t1;
        prepare(m, grid, k, time);
        displace(m, grid, k, time);
    }
}

void GridShader::shadeSlot(Grid& grid, int k, double time) {
    const Material& m = *grid.material;
    if (m.displacement || m.surface || m.atmosphere) prepare(m, grid, k, time);  // once for all three
    if (m.displacement) displace(m, grid, k, time);
    shadeSurface(grid, k, time);
    if (depthLayers_) {
        const size_t n = size_t(grid.vertexCount());
        std::vector<Color>& oi = grid.Oi[k];
        const bool given = oi.size() == n;  // else opaque
        oi.resize(n);
        for (size_t i = 0; i < n; ++i) {
            const Color o = given ? oi[i] : Color{1, 1, 1};
            const bool opaque = o.x >= 1 && o.y >= 1 && o.z >= 1;
            oi[i] = opaque ? Color{0.5f, 0.5f, 0.5f} : Color{0, 0, 0};
            grid.Ci[k][i] = Color{0, 0, 0};
        }
    }
}

// A shader's "shader" space at `time`: the CTM where it was declared; its "object" space: the
// CTM of the primitive it shades (RI Spec 3.2, section 4.1), in the render camera's space as the
// primitive's points are. A material that does not know its primitive's transform
// (Material::objectSpaceKnown: its shaders never name "object"), or no material: the shader's.
void GridShader::useShaderSpace(const MotionTransform* shaderToWorld, const Material* m, double time) {
    const Matrix4 shaderToCamera = shaderToWorld ? shaderToWorld->at(time) * world_ : world_;
    sgrid_.setSpace(sl::Space::Shader, shaderToCamera);
    sgrid_.setSpace(sl::Space::Object,
                    m && m->objectSpaceKnown ? m->objectToWorld.at(time) * worldToCamera_ : shaderToCamera);
}

// I for the grid's positions: from the eye at the origin, or from the eye plane z = 0 along +z
// under an orthographic camera.
void GridShader::setIncident(const Grid& grid, int k) {
    if (camera_.perspective()) {
        sgrid_.set(sl::Global::I, sl::ValueRef::aos(grid.P[k].data()));
        return;
    }
    const int n = grid.vertexCount();
    orthoI_.resize(size_t(n));
    for (int i = 0; i < n; ++i) orthoI_[size_t(i)] = {0, 0, grid.P[k][size_t(i)].z};
    sgrid_.set(sl::Global::I, sl::ValueRef::aos(orthoI_.data()));
}

// The displacement shader (or each layer of a layered one, in the last layer's "shader" space)
// moves P (and sets N) over the grid; they replace the diced ones.
void GridShader::displace(const Material& m, Grid& grid, int k, double time) {
    useShaderSpace(m.attributes ? &m.attributes->displacement.shaderToWorld : nullptr, &m, time);
    if (m.displacementLayers) network_.run(*vm_, *m.displacementLayers, sgrid_, {});
    else vm_->run(*m.displacement, sgrid_, {});
    auto result = [&](sl::Global g) { return m.displacementLayers ? network_.result(*vm_, g) : vm_->result(g); };
    const sl::ValueRef P = result(sl::Global::P), N = result(sl::Global::N);
    const int n = grid.vertexCount();
    // Read both before writing: a result the shader did not touch is the grid's own array.
    base_.resize(size_t(n) * 2);
    // The largest move (camera space, squared) against the displacement bound, and the largest
    // distance from the eye (what float rounding of a point is relative to).
    float moved = 0, far = 0;
    for (int i = 0; i < n; ++i) {
        base_[size_t(i)] = P.valid() ? P.vec(i) : grid.P[k][size_t(i)];
        base_[size_t(n + i)] = N.valid() ? N.vec(i) : grid.N[k][size_t(i)];
        const Vec3f was = grid.P[k][size_t(i)], d = base_[size_t(i)] - was;
        moved = std::max(moved, dot(d, d));
        far = std::max(far, dot(was, was));
    }
    if (shaders_) shaders_->displacementReach().note(m, std::sqrt(moved), std::sqrt(far));
    std::copy(base_.begin(), base_.begin() + n, grid.P[k].begin());
    std::copy(base_.begin() + n, base_.begin() + 2 * n, grid.N[k].begin());
    setIncident(grid, k);  // the shading grid's views are the grid's arrays: only I is derived
}

void GridShader::shadeSurface(Grid& grid, int k, double time, const uint8_t* need) {
    const Material& m = *grid.material;
    if (aovs_ && grid.aovCount == aovs_->count) clearShaderOutputs(grid, k);
    const size_t n = size_t(grid.vertexCount());
    if (!m.surface) {
        if (depthOnly_) std::fill(grid.Ci[k].begin(), grid.Ci[k].end(), Color{0, 0, 0});
        else shadeGridSlot(grid, k, time, lights_, !camera_.perspective(), lightScratch_, need);
        builtinPoints_ += need ? uint64_t(std::count_if(need, need + n, [](uint8_t x) { return x != 0; }))
                               : uint64_t(grid.vertexCount());
        if (!(m.Os.x >= 1 && m.Os.y >= 1 && m.Os.z >= 1)) grid.Oi[k].assign(n, clampOpacity(m.Os));
        else grid.Oi[k].clear();
    } else {
        runSurface(m, grid, k, time);
        // The shader's Oi (Os where it writes none): kept only when some point is see-through.
        const sl::ValueRef oi = surfaceResult(m, sl::Global::Oi);
        grid.Oi[k].clear();
        if (oi.valid())
            for (size_t i = 0; i < n; ++i) {
                const Color o = oi.vec(int(i));
                if (!(o.x >= 1 && o.y >= 1 && o.z >= 1)) {  // NaN counts as see-through here, made opaque below
                    grid.Oi[k].resize(n);
                    for (size_t j = 0; j < n; ++j) grid.Oi[k][j] = clampOpacity(oi.vec(int(j)));
                    break;
                }
            }
    }
    if (m.atmosphere && !depthOnly_) runAtmosphere(m, grid, k, time);
}

// The volume shader takes the surface's Ci and gives what reaches the eye. The parts of the lights
// that cast shadows go through it by superposition too: Cl' = atm(Ci + Cl) - atm(Ci), exact for
// atmospheres affine in Ci (fog, depthcue).
void GridShader::runAtmosphere(const Material& m, Grid& grid, int k, double time) {
    useShaderSpace(m.attributes ? &m.attributes->atmosphere.shaderToWorld : nullptr, &m, time);
    const int n = grid.vertexCount();
    const int slots = grid.shadowSlots;
    base_.assign(grid.Ci[k].begin(), grid.Ci[k].end());  // the surface's colour, kept for the slots
    sgrid_.set(sl::Global::Ci, sl::ValueRef::aos(base_.data()));
    vm_->run(*m.atmosphere, sgrid_, {});
    sl::ValueRef ci = vm_->result(sl::Global::Ci);
    for (int i = 0; i < n; ++i) grid.Ci[k][size_t(i)] = ci.vec(i);
    if (slots == 0) return;
    std::vector<Color>& lit = withLight_;
    lit.resize(size_t(n));
    sgrid_.set(sl::Global::Ci, sl::ValueRef::aos(lit.data()));
    Color* cl = grid.Cl[k].data();
    for (int s = 0; s < slots; ++s) {
        for (int i = 0; i < n; ++i) lit[size_t(i)] = base_[size_t(i)] + cl[size_t(i) * size_t(slots) + size_t(s)];
        vm_->run(*m.atmosphere, sgrid_, {});
        ci = vm_->result(sl::Global::Ci);
        for (int i = 0; i < n; ++i)
            cl[size_t(i) * size_t(slots) + size_t(s)] = ci.vec(i) - grid.Ci[k][size_t(i)];
    }
}

// The shading grid's inputs for slot k: views of the grid's arrays, u and v over the piece.
void GridShader::prepare(const Material& m, const Grid& grid, int k, double time) {
    if (!vm_) {
        vm_ = std::make_unique<sl::ShadingVM>();
        vm_->setTextureSource(shaders_ ? shaders_->textures() : nullptr);
        vm_->setLog(shaders_ ? &shaders_->log() : nullptr);
        vm_->setSpecularExponent(shaders_ ? shaders_->specularExponent() : 8.0f);
        vm_->setRaySource(rays_);
        vm_->setPointClouds(shaders_ ? shaders_->pointClouds() : nullptr);
    }
    queries_ = shaders_ ? shaders_->queries(m.attributes) : SceneQueries();
    sgrid_.state = &queries_;
    const int n = grid.vertexCount();
    sgrid_.setShape(grid.nu, grid.nv);
    sgrid_.parts = nullptr;  // one grid (shadeBatch sets its parts after this)
    sgrid_.partCount = 0;
    u_.resize(size_t(n));
    v_.resize(size_t(n));
    const float du = grid.nu > 0 ? (grid.u1 - grid.u0) / float(grid.nu) : 0.0f;
    const float dv = grid.nv > 0 ? (grid.v1 - grid.v0) / float(grid.nv) : 0.0f;
    const bool placed = grid.paramU.size() == size_t(n) && grid.paramV.size() == size_t(n);
    for (int j = 0; j <= grid.nv; ++j)
        for (int i = 0; i <= grid.nu; ++i) {
            // The borders exactly, as the dicers place them: neighbours agree on shared vertices.
            const size_t at = size_t(grid.index(i, j));
            if (placed) {  // where the dicer put the vertex (a curved body's sides)
                const float fu = grid.paramU[at], fv = grid.paramV[at];
                u_[at] = fu >= 1 ? grid.u1 : grid.u0 + fu * (grid.u1 - grid.u0);
                v_[at] = fv >= 1 ? grid.v1 : grid.v0 + fv * (grid.v1 - grid.v0);
                continue;
            }
            u_[at] = i == grid.nu ? grid.u1 : grid.u0 + float(i) * du;
            v_[at] = j == grid.nv ? grid.v1 : grid.v0 + float(j) * dv;
        }
    static const Vec3f kEye{0, 0, 0};
    using sl::Global;
    using sl::ValueRef;
    sgrid_.set(Global::P, ValueRef::aos(grid.P[k].data()));
    sgrid_.set(Global::N, ValueRef::aos(grid.N[k].data()));
    sgrid_.set(Global::Ng, ValueRef::aos(grid.N[k].data()));
    setIncident(grid, k);
    sgrid_.set(Global::E, ValueRef::uniform(kEye));
    sgrid_.set(Global::Cs, ValueRef::aos(grid.Cs.data()));
    sgrid_.set(Global::Ci, ValueRef{});  // outputs: only an atmosphere reads them as inputs
    sgrid_.set(Global::Oi, ValueRef::uniform(m.Os));
    sgrid_.set(Global::Os, ValueRef::uniform(m.Os));
    sgrid_.set(Global::u, ValueRef::soa(u_.data()));
    sgrid_.set(Global::v, ValueRef::soa(v_.data()));
    sgrid_.set(Global::s, ValueRef::soa(u_.data()));
    sgrid_.set(Global::t, ValueRef::soa(v_.data()));
    du_ = du;
    dv_ = dv;
    time_ = float(time);
    sgrid_.time = time;
    sgrid_.set(Global::du, ValueRef::uniform(&du_));
    sgrid_.set(Global::dv, ValueRef::uniform(&dv_));
    sgrid_.set(Global::time, ValueRef::uniform(&time_));
    // Primitives are in the render camera's space (a merged sequence bakes each frame's camera
    // into them): their variables go through it. "world" is the frame's own.
    worldToCamera_ = camera_.worldToCamera().at(time);
    world_ = shaders_ ? shaders_->worldToCameraAt(time) : worldToCamera_;
    sgrid_.setSpace(sl::Space::World, world_);
    // Named coordinate systems (CoordinateSystem): object to world, then this "world".
    sgrid_.coordinateSystems = nullptr;
    if (shaders_ && !shaders_->coordinateSystems().empty()) {
        const std::vector<sl::NamedSpace>& named = shaders_->coordinateSystems();
        namedSpaces_.resize(named.size());
        for (size_t i = 0; i < named.size(); ++i) {
            namedSpaces_[i].name = named[i].name;
            namedSpaces_[i].toCurrent = named[i].toCurrent * world_;
        }
        sgrid_.coordinateSystems = &namedSpaces_;
    }
    bindPrimvars(m, grid, n, time);
    sgrid_.flipNormals = m.flipNormals;  // calculatenormal turns as N does (Orientation, mirroring)
    sgrid_.seed = unsigned(grid.primitiveId ^ (grid.primitiveId >> 32));
    sgrid_.nearClip = camera_.nearClip();
    sgrid_.farClip = camera_.farClip();
    // Message passing: this primitive's shaders, each with its own "shader" space.
    sl::PeerShaders peers;
    auto peer = [&](sl::Peer which, const sl::ShaderInstance* s, const MotionTransform* shaderToWorld) {
        peers[size_t(which)].shader = s;
        peers[size_t(which)].toCurrent = shaderToWorld ? shaderToWorld->at(time) * world_ : world_;
    };
    const Attributes* a = m.attributes;
    peer(sl::Peer::Surface, m.surface.get(), a ? &a->surface.shaderToWorld : nullptr);
    peer(sl::Peer::Displacement, m.displacement.get(), a ? &a->displacement.shaderToWorld : nullptr);
    peer(sl::Peer::Atmosphere, m.atmosphere.get(), a ? &a->atmosphere.shaderToWorld : nullptr);
    peers[size_t(sl::Peer::Incident)] = peers[size_t(sl::Peer::Atmosphere)];  // rays from the eye cross it
    vm_->setPeers(peers);
}

void GridShader::bindPrimvars(const Material& m, const Grid& grid, int n, double time) {
    sgrid_.primvars = nullptr;
    if (m.primvars.params.empty()) return;
    // Sizes first: the views point into primvarData_.
    size_t total = 0;
    for (const Param& p : m.primvars.params)
        if (p.type != ParamType::String)
            total += size_t(p.componentsPerItem()) * (p.cls == ParamClass::Constant ? 1 : size_t(n));
    primvarData_.resize(total);
    const float* block = grid.primvarCorners ? grid.primvarCorners : m.primvarCorners.data();
    size_t cornerAt = 0;
    size_t at = 0, bound = 0;  // entries of primvars_ are reused from grid to grid (no allocation once warm)
    for (const Param& p : m.primvars.params) {
        if (primvars_.size() <= bound) primvars_.emplace_back();
        sl::Primvar& v = primvars_[bound];
        v.name = p.name;
        v.loc = p.loc;
        if (p.type == ParamType::String) {
            v.type = sl::BaseType::String;
            v.strings = p.strings;
            ++bound;
            continue;
        }
        const int w = p.componentsPerItem();  // 1, 3 (color) or 2 ("st")
        float* d = &primvarData_[at];
        float* comp[3] = {nullptr, nullptr, nullptr};
        if (p.cls == ParamClass::Constant) {
            for (int c = 0; c < w; ++c) d[c] = float(p.nums[size_t(c)]), comp[c] = d + c;
            v.value = sl::ValueRef{{comp[0], comp[1], comp[2]}, 0};
            at += size_t(w);
        } else if (p.cls == ParamClass::Uniform) {  // a mesh face's own value: uniform over the grid
            const float* corners = block + cornerAt;
            cornerAt += 4 * size_t(w);
            for (int c = 0; c < w; ++c) d[c] = corners[c], comp[c] = d + c;
            v.value = sl::ValueRef{{comp[0], comp[1], comp[2]}, 0};
            at += size_t(w) * size_t(n);
        } else if (m.primvarBezier && p.cls == ParamClass::Vertex) {
            // A bicubic patch's vertex variable: its 16 Bezier control values, bicubic in (u, v).
            const float* controls = block + cornerAt;
            cornerAt += 16 * size_t(w);
            for (int c = 0; c < w; ++c) comp[c] = d + size_t(c) * size_t(n);
            for (int i = 0; i < n; ++i) {
                const float u = u_[size_t(i)], vv = v_[size_t(i)];
                const float su = 1 - u, sv = 1 - vv;
                const float bu[4] = {su * su * su, 3 * u * su * su, 3 * u * u * su, u * u * u};
                const float bv[4] = {sv * sv * sv, 3 * vv * sv * sv, 3 * vv * vv * sv, vv * vv * vv};
                for (int c = 0; c < w; ++c) {
                    float sum = 0;
                    for (int r = 0; r < 4; ++r) {
                        const float* row = controls + size_t(r * 4 * w + c);
                        sum += bv[r] * (bu[0] * row[0] + bu[1] * row[w] + bu[2] * row[2 * w] + bu[3] * row[3 * w]);
                    }
                    comp[c][i] = sum;
                }
            }
            v.value = sl::ValueRef{{comp[0], comp[1], comp[2]}, 1};
            at += size_t(w) * size_t(n);
        } else {
            // Four corners in RenderMan order (the body's, or the material's), bilinear in the body's (u, v).
            const float* corners = block + cornerAt;
            cornerAt += 4 * size_t(w);
            for (int c = 0; c < w; ++c) {
                const float k[4] = {corners[c], corners[w + c], corners[2 * w + c], corners[3 * w + c]};
                comp[c] = d + size_t(c) * size_t(n);
                for (int i = 0; i < n; ++i) {
                    const float u = u_[size_t(i)], vv = v_[size_t(i)];
                    comp[c][i] = (k[0] + (k[1] - k[0]) * u) + ((k[2] + (k[3] - k[2]) * u) - (k[0] + (k[1] - k[0]) * u)) * vv;
                }
            }
            v.value = sl::ValueRef{{comp[0], comp[1], comp[2]}, 1};
            at += size_t(w) * size_t(n);
        }
        // Points, vectors and normals: from the primitive's object space to current space.
        if (p.type == ParamType::Point || p.type == ParamType::Vector || p.type == ParamType::Normal) {
            const Matrix4 toCurrent = m.objectToWorld.at(time) * worldToCamera_;
            Matrix4 inverse;
            if (!invert(toCurrent, &inverse)) inverse = Matrix4();
            const int count = v.value.stride ? n : 1;
            for (int i = 0; i < count; ++i) {
                const Vec3d a{comp[0][i], comp[1][i], comp[2][i]};
                Vec3d b;
                if (p.type == ParamType::Point) b = toCurrent.point(a);
                else if (p.type == ParamType::Vector) b = toCurrent.vector(a);
                else  // normals by the inverse transpose
                    b = {inverse(0, 0) * a.x + inverse(0, 1) * a.y + inverse(0, 2) * a.z,
                         inverse(1, 0) * a.x + inverse(1, 1) * a.y + inverse(1, 2) * a.z,
                         inverse(2, 0) * a.x + inverse(2, 1) * a.y + inverse(2, 2) * a.z};
                comp[0][i] = float(b.x), comp[1][i] = float(b.y), comp[2][i] = float(b.z);
            }
            // "N" is the shading normal; the rest bind by name.
            if (p.name == "N" && p.type == ParamType::Normal) {
                sgrid_.set(sl::Global::N, v.value);
                continue;
            }
        }
        if (p.name == "Cs" && p.type == ParamType::Color) {  // a bicubic mesh's vertex colour (addPatchMesh)
            sgrid_.set(sl::Global::Cs, v.value);
            continue;
        }
        if (p.name == "Os" && p.type == ParamType::Color) {  // the opacity a shader starts from
            sgrid_.set(sl::Global::Os, v.value);
            sgrid_.set(sl::Global::Oi, v.value);
            continue;
        }
        const sl::ValueRef one{{comp[0], nullptr, nullptr}, v.value.stride};
        if (p.name == "st") {
            sgrid_.set(sl::Global::s, one);
            sgrid_.set(sl::Global::t, sl::ValueRef{{comp[1], nullptr, nullptr}, v.value.stride});
            continue;
        }
        if (p.name == "s" && w == 1) sgrid_.set(sl::Global::s, one);
        if (p.name == "t" && w == 1) sgrid_.set(sl::Global::t, one);
        v.type = p.type == ParamType::Color    ? sl::BaseType::Color
                 : p.type == ParamType::Point  ? sl::BaseType::Point
                 : p.type == ParamType::Vector ? sl::BaseType::Vector
                 : p.type == ParamType::Normal ? sl::BaseType::Normal
                                               : sl::BaseType::Float;
        v.strings.clear();
        ++bound;
    }
    primvars_.resize(bound);
    sgrid_.primvars = &primvars_;
}

// A light as the interpreter runs it: once, or an area light once at each of its points (each
// weighted 1 / their number, its surface's normal as N).
void GridShader::addLight(const sl::ShaderInstance* s, int li, double time, std::vector<sl::LightRef>& out) const {
    if (!lights_.isArea(li)) {
        out.emplace_back(s, lights_.lightToCamera(li, time));
        return;
    }
    const int n = lights_.areaSamples(li);
    for (int j = 0; j < n; ++j)
        out.emplace_back(s, lights_.areaSampleToCamera(li, j, time), lights_.areaNormal(li, j, time), 1.0f / float(n));
}

void GridShader::runSurface(const Material& m, Grid& grid, int k, double time) {
    useShaderSpace(m.attributes ? &m.attributes->surface.shaderToWorld : nullptr, &m, time);
    // The material's lights, those that cast shadows apart.
    unshadowed_.clear();
    int shadowed = 0;
    for (int li : m.lights) {
        const sl::ShaderInstance* s = shaders_ && !depthOnly_ ? shaders_->light(size_t(li)) : nullptr;
        if (!s) continue;
        if (grid.shadowSlots > 0 && lights_.shadowSlotOf(li) >= 0) {
            ++shadowed;
            continue;
        }
        addLight(s, li, time, unshadowed_);
    }
    const int n = grid.vertexCount();
    runSurfaceShaders(m, unshadowed_);
    if (aovs_ && grid.aovCount == aovs_->count) copyShaderOutputs(grid, k);
    const sl::ValueRef ci = surfaceResult(m, sl::Global::Ci);
    std::vector<Color>& Ci = grid.Ci[k];
    for (int i = 0; i < n; ++i) Ci[size_t(i)] = ci.valid() ? ci.vec(i) : Color{0, 0, 0};
    if (grid.shadowSlots > 0) {
        Color* cl = grid.Cl[k].data();
        std::fill(cl, cl + size_t(n) * size_t(grid.shadowSlots), Color{0, 0, 0});
        if (shadowed > 0) {
            base_.assign(Ci.begin(), Ci.end());
            for (int li : m.lights) {
                const int slot = lights_.shadowSlotOf(li);
                const sl::ShaderInstance* s = shaders_->light(size_t(li));
                if (slot < 0 || !s) continue;
                withOne_.assign(unshadowed_.begin(), unshadowed_.end());
                addLight(s, li, time, withOne_);
                runSurfaceShaders(m, withOne_);
                const sl::ValueRef c = surfaceResult(m, sl::Global::Ci);
                for (int i = 0; i < n; ++i)
                    cl[size_t(i) * size_t(grid.shadowSlots) + size_t(slot)] = c.vec(i) - base_[size_t(i)];
            }
        }
    }
}

void GridShader::runSurfaceShaders(const Material& m, const std::vector<sl::LightRef>& lights) {
    if (m.layers) network_.run(*vm_, *m.layers, sgrid_, lights);
    else vm_->run(*m.surface, sgrid_, lights);
}

// A shader output no shader writes reads 0 (the grid's arrays are reused from grid to grid).
void GridShader::clearShaderOutputs(Grid& grid, int k) const {
    const size_t A = size_t(aovs_->count), n = size_t(grid.vertexCount());
    float* out = grid.aov[k].data();
    for (size_t vi = 0; vi < aovs_->vars.size(); ++vi) {
        if (aovs_->vars[vi].var != AovVar::Shader) continue;
        const size_t o = size_t(aovs_->offset[vi]), w = size_t(aovs_->vars[vi].width);
        for (size_t i = 0; i < n; ++i) std::fill(out + i * A + o, out + i * A + o + w, 0.0f);
    }
}

// The surface shader's output parameters the layout names, from its run without the lights that
// cast shadows (those are run again one at a time: an output that depends on them misses their part).
void GridShader::copyShaderOutputs(Grid& grid, int k) const {
    const size_t A = size_t(aovs_->count);
    const int n = grid.vertexCount();
    float* out = grid.aov[k].data();
    for (size_t vi = 0; vi < aovs_->vars.size(); ++vi) {
        const AovEntry& e = aovs_->vars[vi];
        if (e.var != AovVar::Shader) continue;
        const sl::ValueRef v = vm_->output(e.name);
        if (!v.valid()) continue;
        const size_t o = size_t(aovs_->offset[vi]);
        for (int i = 0; i < n; ++i)
            for (int c = 0; c < e.width; ++c) out[size_t(i) * A + o + size_t(c)] = v.comp[c] ? v.at(c, i) : 0.0f;
    }
}

}  // namespace streyes
