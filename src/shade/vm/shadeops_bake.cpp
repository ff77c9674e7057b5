// bake3d(), texture3d() and bake(): one PointCloudSource call per call site and grid, over the
// points that run. Positions and normals go to the source in world space (Aqsis's default
// "coordsystem"), so a cloud baked from one camera is read from another. Without a source
// bake3d and bake write nothing and texture3d finds nothing (each returns 0).
#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

#include "shade/vm/ops.h"
#include "shade/vm/vm.h"

namespace streyes::sl::ops {

namespace {

thread_local std::vector<float> records, cloudIn, cloudOut;

struct Xform {
    float m[16];  // row vectors: p' = p M
    V3 point(V3 p) const {
        const float x = p.x * m[0] + p.y * m[4] + p.z * m[8] + m[12];
        const float y = p.x * m[1] + p.y * m[5] + p.z * m[9] + m[13];
        const float z = p.x * m[2] + p.y * m[6] + p.z * m[10] + m[14];
        const float w = p.x * m[3] + p.y * m[7] + p.z * m[11] + m[15];
        return w != 1.0f && w != 0.0f ? V3{x / w, y / w, z / w} : V3{x, y, z};
    }
    // A normal by the inverse transpose: this is the inverse.
    V3 normal(V3 n) const {
        return {n.x * m[0] + n.y * m[1] + n.z * m[2], n.x * m[4] + n.y * m[5] + n.z * m[6],
                n.x * m[8] + n.y * m[9] + n.z * m[10]};
    }
};

// Current space to `space` (toSpace) and back (fromSpace, for normals).
void spaces(Exec& x, const std::string& space, Xform* toSpace, Xform* fromSpace) {
    for (int c = 0; c < 16; ++c) toSpace->m[c] = fromSpace->m[c] = c % 5 == 0 ? 1.0f : 0.0f;
    if (space == "current") return;
    x.vm.currentToSpace(space, toSpace->m);
    x.vm.spaceToCurrent(space, fromSpace->m);
}

// The floats of value register r at point i into out (a float, a triple or a matrix).
void loadValue(const RegView& v, int i, float* out) {
    for (int c = 0; c < v.comps; ++c) out[c] = v.at(c, i);
}

int cloudComps(const SlType& t) { return t.isFloat() ? 1 : t.isMatrix() ? 16 : 3; }

// The micropolygon corners of point i's grid neighbours (u then v), clamped to the grid.
int neighbour(const ShadingGrid& g, int i, int du, int dv) {
    const int row = g.nu + 1;
    const int u = std::min(std::max(i % row + du, 0), g.nu), v = std::min(std::max(i / row + dv, 0), g.nv);
    return v * row + u;
}

}  // namespace

// bake3d(file, displaychannels, P, N, pairs...): extra = file, channels, P, N, then (name, value)
// pairs. a0 = 1 where a point was written.
void bake3d(Exec& x, const Instr& in) {
    const RegView d = x.view(in.a[0]);
    std::fill(d.comp(0), d.comp(0) + d.w, 0.0f);
    if (x.active == 0) return;
    PointCloudSource* source = x.vm.pointClouds();
    // Points shaded for a ray's hit are not the surface's own points (no micropolygon, seen from
    // elsewhere): only what the camera's grids shade is baked.
    if (!source || x.grid.rayDepth > 0) return;
    const int32_t* r = x.extra(in.a[1]);
    const int count = in.a[2];
    const std::string& file = x.str(r[0]);
    const RegView P = x.view(r[2]), N = x.view(r[3]);
    const int lane = [&] {
        for (int i = 0; i < x.n; ++i)
            if (x.mask[i]) return i;
        return 0;
    }();
    bool interpolate = false;
    int radiusReg = -1, scaleReg = -1;
    std::string space = "world";
    std::vector<CloudChannel> channels;
    std::vector<int> values;
    for (int k = 4; k + 1 < count; k += 2) {
        const std::string& name = x.str(r[k]);
        const Register& v = x.reg(r[k + 1]);
        if (name == "interpolate" && v.type.isFloat()) interpolate = x.view(r[k + 1]).at(0, lane) != 0;
        else if (name == "radius" && v.type.isFloat()) radiusReg = r[k + 1];
        else if (name == "radiusscale" && v.type.isFloat()) scaleReg = r[k + 1];
        else if (name == "coordsystem" && v.type.isString()) space = x.str(r[k + 1]);
        else if (v.type.isString()) x.vm.warnOnce(x, in, "bake3d-string", "bake3d cannot bake string \"" + name + "\": left out");
        else {
            channels.push_back({name, cloudComps(v.type)});
            values.push_back(r[k + 1]);
        }
    }
    Xform toSpace, fromSpace;
    spaces(x, space, &toSpace, &fromSpace);
    const int stride = 7 + [&] {
        int s = 0;
        for (const CloudChannel& c : channels) s += c.comps;
        return s;
    }();
    const ShadingGrid& g = x.grid;
    const bool shaped = g.nu > 0 && g.nv > 0 && P.varying;
    const int pointsOut = x.n;  // (uniform values make equal records: one is kept)
    records.resize(size_t(pointsOut) * size_t(stride));
    std::vector<float> tmp(static_cast<size_t>(stride), 0.0f);
    int written = 0;
    auto gather = [&](int i, float* out) {
        const V3 p = load3(P, i), nn = load3(N, i);
        out[0] = p.x, out[1] = p.y, out[2] = p.z, out[3] = nn.x, out[4] = nn.y, out[5] = nn.z, out[6] = 0;
        float* o = out + 7;
        for (size_t c = 0; c < values.size(); ++c) {
            loadValue(x.view(values[c]), i, o);
            o += channels[c].comps;
        }
    };
    for (int i = 0; i < pointsOut; ++i) {
        if (!x.mask[i]) continue;
        float* rec = records.data() + size_t(written) * size_t(stride);
        float radius = 0;
        if (interpolate && shaped) {
            // Aqsis's "interpolate": a micropolygon's centre (the mean of its four corners, and of
            // their values), standing for the micropolygon; points on the far borders own none.
            const int row = g.nu + 1;
            if (i % row == g.nu || i / row == g.nv) continue;
            gather(i, rec);
            const int corners[3] = {i + 1, i + row, i + row + 1};
            V3 c[4] = {{rec[0], rec[1], rec[2]}};
            for (int k = 0; k < 3; ++k) {
                gather(corners[k], tmp.data());
                for (int f = 0; f < stride; ++f) rec[f] += tmp[size_t(f)];
                c[k + 1] = {tmp[0], tmp[1], tmp[2]};
            }
            for (int f = 0; f < stride; ++f) rec[f] *= 0.25f;
            const V3 mid{rec[0], rec[1], rec[2]};
            float r2 = 0;
            for (const V3& q : c) r2 = std::max(r2, dot3(sub3(mid, q), sub3(mid, q)));
            radius = std::sqrt(r2);
        } else {
            gather(i, rec);
            if (shaped) {
                // Half the longer diagonal of the micropolygon the point's u and v steps span.
                const V3 p = load3(P, i);
                const int iu = neighbour(g, i, 1, 0), iv = neighbour(g, i, 0, 1);
                V3 e1 = sub3(load3(P, iu), p), e2 = sub3(load3(P, iv), p);
                if (iu == i) e1 = sub3(p, load3(P, neighbour(g, i, -1, 0)));
                if (iv == i) e2 = sub3(p, load3(P, neighbour(g, i, 0, -1)));
                radius = 0.5f * std::sqrt(std::max(dot3(add3(e1, e2), add3(e1, e2)), dot3(sub3(e1, e2), sub3(e1, e2))));
            }
        }
        if (radiusReg >= 0) radius = x.view(radiusReg).at(0, i);
        if (scaleReg >= 0) radius *= x.view(scaleReg).at(0, i);
        const V3 p = toSpace.point({rec[0], rec[1], rec[2]}), nn = fromSpace.normal({rec[3], rec[4], rec[5]});
        rec[0] = p.x, rec[1] = p.y, rec[2] = p.z, rec[3] = nn.x, rec[4] = nn.y, rec[5] = nn.z, rec[6] = radius;
        bool finite = true;
        for (int f = 0; f < stride; ++f) finite = finite && std::isfinite(rec[f]);
        if (!finite) continue;  // a NaN never reaches a file
        ++written;
        d.comp(0)[d.varying ? i : 0] = 1.0f;
    }
    if (written == 0) return;
    BakeRecords b;
    b.channels = &channels;
    b.records = records.data();
    b.count = written;
    source->bake3d(file, b);
}

// texture3d(file, P, N, pairs...): extra = file, P, N, then (name, variable copy) pairs; a0 = 1
// where the lookup found the cloud.
void texture3d(Exec& x, const Instr& in) {
    const RegView d = x.view(in.a[0]);
    std::fill(d.comp(0), d.comp(0) + d.w, 0.0f);
    if (x.active == 0) return;
    PointCloudSource* source = x.vm.pointClouds();
    const int32_t* r = x.extra(in.a[1]);
    const int count = in.a[2];
    const std::string& file = x.str(r[0]);
    std::string space = "world";
    std::vector<CloudChannel> channels;
    std::vector<int> outs;
    for (int k = 3; k + 1 < count; k += 2) {
        const std::string& name = x.str(r[k]);
        const Register& v = x.reg(r[k + 1]);
        if (name == "coordsystem" && v.type.isString()) space = x.str(r[k + 1]);
        else if (name == "filterradius" || name == "filterscale" || name == "maxdepth") continue;  // brick maps'
        else if (v.type.isString()) x.vm.warnOnce(x, in, "texture3d-string", "texture3d cannot read string \"" + name + "\"");
        else {
            channels.push_back({name, cloudComps(v.type)});
            outs.push_back(r[k + 1]);
        }
    }
    if (!source || channels.empty()) return;
    Xform toSpace, fromSpace;
    spaces(x, space, &toSpace, &fromSpace);
    const int n = x.n;
    const RegView P = x.view(r[1]), N = x.view(r[2]);
    cloudIn.resize(size_t(n) * 6);
    int total = 0;
    for (const CloudChannel& c : channels) total += c.comps;
    cloudOut.assign(size_t(n) * size_t(total), 0.0f);
    for (int i = 0; i < n; ++i) {
        const V3 p = toSpace.point(load3(P, i)), nn = fromSpace.normal(load3(N, i));
        const float v[6] = {p.x, p.y, p.z, nn.x, nn.y, nn.z};
        for (int c = 0; c < 6; ++c) cloudIn[size_t(c) * size_t(n) + size_t(i)] = v[c];
    }
    std::vector<float*> out;
    for (int k = 0, at = 0; k < int(channels.size()); at += channels[size_t(k)].comps, ++k)
        out.push_back(cloudOut.data() + size_t(at) * size_t(n));
    CloudQuery q;
    q.n = n;
    q.active = x.allOn() ? nullptr : x.mask;
    for (int c = 0; c < 3; ++c) {
        q.P[c] = cloudIn.data() + size_t(c) * size_t(n);
        q.N[c] = cloudIn.data() + size_t(3 + c) * size_t(n);
    }
    q.channels = &channels;
    q.out = out.data();
    std::string error;
    std::vector<std::string> missing;
    if (!source->texture3d(file, q, &error, &missing)) {
        x.vm.warnOnce(x, in, "texture3d-file", "texture3d: " + error + "; it reads 0 and leaves the variables as they were");
        return;
    }
    std::vector<bool> found(channels.size(), true);
    for (const std::string& m : missing) {
        x.vm.warnOnce(x, in, "texture3d-channel",
                      "texture3d: point cloud \"" + file + "\" has no channel \"" + m +
                          "\" of that type (bake3d it with that name and type): the variable is left as it was");
        for (size_t k = 0; k < channels.size(); ++k)
            if (channels[k].name == m) found[k] = false;
    }
    for (size_t k = 0; k < channels.size(); ++k) {
        if (!found[k]) continue;
        const RegView v = x.view(outs[k]);  // a varying copy the code generator made
        for (int c = 0; c < channels[k].comps && c < v.comps; ++c)
            for (int i = 0; i < n; ++i)
                if (x.mask[i]) v.comp(c)[i] = out[k][size_t(c) * size_t(n) + size_t(i)];
    }
    for (int i = 0; i < n; ++i)
        if (x.mask[i]) d.comp(0)[d.varying ? i : 0] = 1.0f;
}

// bake(file, s, t, value): a0 unused (void); extra = file, s, t, value.
void bake(Exec& x, const Instr& in) {
    if (x.active == 0) return;
    PointCloudSource* source = x.vm.pointClouds();
    if (!source) return;
    const int32_t* r = x.extra(in.a[1]);
    const std::string& file = x.str(r[0]);
    const RegView s = x.view(r[1]), t = x.view(r[2]), v = x.view(r[3]);
    const int comps = v.comps;
    const int stride = 2 + comps;
    const int pointsOut = x.n;
    records.resize(size_t(pointsOut) * size_t(stride));
    int written = 0;
    for (int i = 0; i < pointsOut; ++i) {
        if (!x.mask[i]) continue;
        float* rec = records.data() + size_t(written) * size_t(stride);
        rec[0] = s.at(0, i), rec[1] = t.at(0, i);
        loadValue(v, i, rec + 2);
        bool finite = true;
        for (int f = 0; f < stride; ++f) finite = finite && std::isfinite(rec[f]);
        if (finite) ++written;
    }
    if (written > 0) source->bake(file, comps, records.data(), written);
}

}  // namespace streyes::sl::ops
