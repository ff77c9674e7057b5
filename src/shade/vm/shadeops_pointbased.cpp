// Point-based occlusion() and indirectdiffuse() (point_based_ops.h): the call's options, the
// points taken to the cloud's space (world unless "coordsystem" says otherwise, as bake3d wrote
// them), one PointCloudSource call per call site and grid.
//
// The rule (docs/SCENE-FORMAT.md): a call is point-based when it names a cloud with "filename"
// and does not say "pointbased" 0. A cloud that cannot be read (missing, truncated, not a
// cloud; for indirectdiffuse, without "_radiosity") gives 0, warned once at the call, as Aqsis
// (whose occlusion() is only point-based) and PRMan ("pointbased" 1) give.
#include "shade/vm/point_based_ops.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "shade/point_based_buffer.h"
#include "shade/vm/environment_lookup.h"
#include "shade/vm/vm.h"

namespace streyes::sl::ops {

namespace {

thread_local std::vector<float> pbScratch;
// The "environmentmap" in the microbuffer's pixel directions: looked up once a call site and
// grid (the pixels' directions are the cloud space's axes' whatever the point), not per point.
thread_local CubeMicrobuffer pbPixels;
thread_local std::vector<float> pbEnvironment, pbEnvScratch;

// Row vectors: p' = p M (a point), and a normal by the inverse transpose given the inverse.
V3 xformPoint(const float* m, V3 p) {
    const float x = p.x * m[0] + p.y * m[4] + p.z * m[8] + m[12];
    const float y = p.x * m[1] + p.y * m[5] + p.z * m[9] + m[13];
    const float z = p.x * m[2] + p.y * m[6] + p.z * m[10] + m[14];
    const float w = p.x * m[3] + p.y * m[7] + p.z * m[11] + m[15];
    return w != 1.0f && w != 0.0f ? V3{x / w, y / w, z / w} : V3{x, y, z};
}
V3 xformNormal(const float* inv, V3 n) {
    return {n.x * inv[0] + n.y * inv[1] + n.z * inv[2], n.x * inv[4] + n.y * inv[5] + n.z * inv[6],
            n.x * inv[8] + n.y * inv[9] + n.z * inv[10]};
}

}  // namespace

bool pointBasedCall(Exec& x, const Instr& in, bool indirect) {
    const int32_t* r = x.extra(in.a[1]);
    const int count = in.a[2];
    const int k = r[0];
    int lane = 0;
    while (lane < x.n - 1 && !x.mask[lane]) ++lane;
    std::string file, space = "world", envSpace;
    float pointbased = -1, bias = 0;
    PointBasedQuery q;
    q.indirect = indirect;
    RayOptions env;
    env.shader = &x.prog.name;
    int32_t occlusionOut = -1, environmentOut = -1;  // output registers (copies the code generator stores back)
    for (int j = 1 + k; j + 1 < count; j += 2) {
        const std::string& name = x.str(r[j]);
        if (isRayOutputOption(indirect ? "indirectdiffuse" : "occlusion", name)) {
            (indirect ? occlusionOut : environmentOut) = r[j + 1];
            continue;
        }
        const bool isString = x.reg(r[j + 1]).type.isString();
        if (isString) {
            if (name == "filename") file = x.str(r[j + 1]);
            else if (name == "coordsystem") space = x.str(r[j + 1]);
            else if (name == "environmentmap") env.environmentmap = x.str(r[j + 1]);
            else if (name == "environmentspace") envSpace = x.str(r[j + 1]);
            continue;
        }
        const float v = x.view(r[j + 1]).at(0, lane);
        if (name == "pointbased") pointbased = v;
        else if (name == "microbufres") q.microbufres = std::isfinite(v) ? int(std::max(1.0f, std::min(v, 256.0f))) : 10;
        else if (name == "maxsolidangle" && v >= 0) q.maxsolidangle = v;
        else if (name == "coneangle" && v >= 0) q.coneangle = v;
        else if (name == "bias" && std::isfinite(v)) bias = v;
    }
    const char* fn = indirect ? "indirectdiffuse" : "occlusion";
    if (pointbased == 0) return false;
    if (file.empty()) {
        if (pointbased > 0)
            x.vm.warnOnce(x, in, "pointbased-nofile",
                          std::string(fn) + ": \"pointbased\" 1 without a \"filename\" naming the point cloud: ray-traced instead");
        return false;
    }
    PointCloudSource* source = x.vm.pointClouds();
    const RegView d = x.view(in.a[0]);
    float toSpace[16], fromSpace[16];
    for (int c = 0; c < 16; ++c) toSpace[c] = fromSpace[c] = c % 5 == 0 ? 1.0f : 0.0f;
    if (space != "current") {
        x.vm.currentToSpace(space, toSpace);
        x.vm.spaceToCurrent(space, fromSpace);
    }
    const int n = x.n;
    pbScratch.resize(size_t(n) * 7);
    float* a = pbScratch.data();
    const RegView P = x.view(r[1]), N = x.view(r[2]);
    for (int i = 0; i < n; ++i) {
        if (!x.mask[i]) continue;
        V3 nn = xformNormal(fromSpace, load3(N, i));
        const float len = std::sqrt(dot3(nn, nn));
        nn = len > 0 ? V3{nn.x / len, nn.y / len, nn.z / len} : V3{0, 0, 0};
        V3 p = xformPoint(toSpace, load3(P, i));
        p = {p.x + bias * nn.x, p.y + bias * nn.y, p.z + bias * nn.z};
        const float v[6] = {p.x, p.y, p.z, nn.x, nn.y, nn.z};
        for (int c = 0; c < 6; ++c) a[size_t(c) * size_t(n) + size_t(i)] = v[c];
    }
    for (int c = 0; c < 3; ++c) {
        q.P[c] = a + size_t(c) * size_t(n);
        q.N[c] = a + size_t(3 + c) * size_t(n);
    }
    q.n = n;
    q.active = x.allOn() ? nullptr : x.mask;
    if (!env.environmentmap.empty() && (indirect || environmentOut >= 0)) {
        // Pixel directions are the cloud space's; the map's are current space's times
        // "environmentspace"'s: d_map = d_cloud * cloudToCurrent * currentToMap (row vectors).
        float toMap[16];
        for (int c = 0; c < 16; ++c) toMap[c] = c % 5 == 0 ? 1.0f : 0.0f;
        if (!envSpace.empty()) x.vm.currentToSpace(envSpace, toMap);
        for (int row = 0; row < 3; ++row)
            for (int col = 0; col < 3; ++col)
                env.environmentFromCurrent[row * 4 + col] = fromSpace[row * 4] * toMap[col] +
                                                            fromSpace[row * 4 + 1] * toMap[4 + col] +
                                                            fromSpace[row * 4 + 2] * toMap[8 + col];
        // Each pixel filtered over its own solid angle (a square cone of that area). Not kept from
        // grid to grid: a map may change between renders under the same name.
        pbPixels.setResolution(q.microbufres);
        const int pixels = pbPixels.pixels();
        pbEnvironment.resize(size_t(pixels) * 4);
        float* widths = pbEnvironment.data() + size_t(pixels) * 3;
        for (int p = 0; p < pixels; ++p) widths[p] = std::sqrt(pbPixels.solidAngles()[p]);
        // A map that cannot be read: black, as the ray-traced path's misses (the texture source warns).
        if (lookupEnvironment(x.vm.textureSource(), env, pbPixels.directions(), pixels, widths, 0, float(x.grid.time),
                              pbEnvScratch, pbEnvironment.data()))
            q.environment = pbEnvironment.data();
    }
    // The destination and the outputs are varying (the code generator makes them so): n floats a
    // component.
    const RegView occ = x.view(occlusionOut >= 0 ? occlusionOut : in.a[0]);
    const RegView seen = x.view(environmentOut >= 0 ? environmentOut : in.a[0]);
    float* out[4] = {indirect ? (occlusionOut >= 0 ? occ.comp(0) : a + size_t(6) * size_t(n)) : d.comp(0),
                     d.comp(0), d.comps > 1 ? d.comp(1) : d.comp(0), d.comps > 2 ? d.comp(2) : d.comp(0)};
    if (environmentOut >= 0) {
        q.environmentColour = true;
        for (int c = 0; c < 3; ++c) out[1 + c] = seen.comp(std::min(c, seen.comps - 1));
    }
    q.out = out;
    std::string error = "no point clouds in this render";
    if (!source || !source->pointBased(file, q, &error)) {
        for (int c = 0; c < d.comps; ++c) std::fill(d.comp(c), d.comp(c) + d.w, 0.0f);
        if (occlusionOut >= 0) std::fill(occ.comp(0), occ.comp(0) + occ.w, 0.0f);
        if (environmentOut >= 0)
            for (int c = 0; c < seen.comps; ++c) std::fill(seen.comp(c), seen.comp(c) + seen.w, 0.0f);
        x.vm.warnOnce(x, in, "pointbased-file", std::string(fn) + ": " + error + "; point-based, it gives 0");
    }
    return true;
}

}  // namespace streyes::sl::ops
