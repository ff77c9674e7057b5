// Small grids of one material shaded together: one interpreter run over their points, each grid
// differenced on its own (sl::ShadingGrid::parts). On scenes of many small grids (the forest's
// leaves: about 12 points a run) a run's fixed costs (binding, the per-instruction dispatch and
// set-up, the lights' checks) outweigh its per-point work; a batch pays them once.
//
// Sound only where one run gives every point the value its grid alone gives it, bit for bit:
// the uniform inputs of the run must be the same for all its grids (the key below: the material,
// which fixes the shaders, their instances, lights, attributes and Os; the spaces the shading
// time gives, and the time itself where a program reads `time`; the shadow slots), and the
// programs must compute each point from its own grid (sl::batchProgramSafe). du and dv, which
// differ with each grid's dicing rate, are varying globals: bound point by point, each grid's
// own. A swaying leaf's key grids (times 0, 4, 8 ...) under a still camera, lights and shader
// space see the same spaces at each key: they share runs. (On the forest, keying runs by du
// and dv and the exact time cut them to 4.7 grids.) What else a run reads of the time (rays,
// maps) is a grid-wide operation, refused in a batch.
#include <algorithm>
#include <cstring>

#include "bodies/material.h"
#include "shade/grid_shader.h"
#include "shade/vm/batch_safety.h"

namespace streyes {

namespace {

// Colours in [0, 1] per channel as shadeSurface keeps them (grid_shader.cpp's clampOpacity).
Color clampOpacityOf(Color o) {
    auto c = [](float v) { return v >= 0 ? (v <= 1 ? v : 1.0f) : (v < 0 ? 0.0f : 1.0f); };
    return {c(o.x), c(o.y), c(o.z)};
}

float stepU(const Grid& g) { return g.nu > 0 ? (g.u1 - g.u0) / float(g.nu) : 0.0f; }
float stepV(const Grid& g) { return g.nv > 0 ? (g.v1 - g.v0) / float(g.nv) : 0.0f; }

void appendMatrix(const Matrix4& m, std::vector<double>& out) { out.insert(out.end(), m.m.begin(), m.m.end()); }

}  // namespace

bool GridShader::spacesAt(const Material& m, double time, std::vector<double>& out) const {
    if (m.surface->program().globalReg[int(sl::Global::time)] >= 0) return false;
    appendMatrix(shaders_->worldToCameraAt(time), out);
    appendMatrix(camera_.worldToCamera().at(time), out);
    if (m.attributes) appendMatrix(m.attributes->surface.shaderToWorld.at(time), out);
    if (m.objectSpaceKnown) appendMatrix(m.objectToWorld.at(time), out);
    for (int li : m.lights) {
        const sl::ShaderInstance* s = shaders_->light(size_t(li));
        if (!s) continue;
        if (lights_.isArea(li) || s->program().globalReg[int(sl::Global::time)] >= 0) return false;
        appendMatrix(lights_.lightToCamera(li, time), out);
    }
    return true;
}

int GridShader::timeClass(const Material& m, double time) {
    for (const TimeClass& c : timeClasses_)
        if (c.material == &m && c.time == time) return c.cls;
    const size_t at = signatures_.size();
    int cls = int(timeClasses_.size());
    if (spacesAt(m, time, signatures_)) {
        const size_t len = signatures_.size() - at;
        for (const TimeClass& c : timeClasses_)
            if (c.material == &m && c.length == len &&  // bit for bit (-0 is not 0 to a product's sign)
                std::memcmp(signatures_.data() + at, signatures_.data() + c.signature, len * sizeof(double)) == 0) {
                cls = c.cls;
                break;
            }
    } else {
        signatures_.resize(at);  // not comparable: a class of its own
    }
    timeClasses_.push_back({&m, time, cls, at, signatures_.size() - at});
    return cls;
}

bool GridShader::programSafe(const sl::ShaderProgram& p) {
    for (const auto& [prog, safe] : safePrograms_)
        if (prog == &p) return safe;
    const bool safe = sl::batchProgramSafe(p);
    safePrograms_.emplace_back(&p, safe);
    return safe;
}

bool GridShader::batchable(const Material* m, int points, int aovCount) {
    if (!batching_ || !shaders_ || depthLayers_ || depthOnly_ || !m || points > kBatchGridPoints) return false;
    if (std::find(refused_.begin(), refused_.end(), m) != refused_.end()) return false;
    if (!m->surface || m->displacement || m->atmosphere || m->layers || !m->primvars.params.empty()) return false;
    if (aovs_ && aovCount == aovs_->count) return false;
    if (!programSafe(m->surface->program())) return false;
    for (int li : m->lights) {
        const sl::ShaderInstance* s = shaders_->light(size_t(li));
        if (s && !programSafe(s->program())) return false;
    }
    return true;
}

void GridShader::shadeSlots(const Slot* slots, size_t count) {
    slotDone_.assign(count, 0);
    // The key of each batchable slot (-1: shaded alone): its material's, its time's class.
    slotClass_.assign(count, -1);
    timeClasses_.clear();
    signatures_.clear();
    for (size_t i = 0; i < count; ++i)
        if (batchable(slots[i].grid->material, slots[i].grid->vertexCount(), slots[i].grid->aovCount))
            slotClass_[i] = timeClass(*slots[i].grid->material, slots[i].time);
    for (size_t i = 0; i < count; ++i) {
        if (slotDone_[i]) continue;
        const Slot& s = slots[i];
        if (slotClass_[i] < 0) {
            shadeSlot(*s.grid, s.k, s.time);
            slotDone_[i] = 1;
            continue;
        }
        // This slot and the later ones of its key, in order, kBatchPoints at most a run.
        group_.clear();
        int points = 0;
        for (size_t j = i; j < count; ++j) {
            if (slotDone_[j] || slotClass_[j] != slotClass_[i] || slots[j].grid->shadowSlots != s.grid->shadowSlots) continue;
            const int n = slots[j].grid->vertexCount();
            if (points + n > kBatchPoints) break;
            group_.push_back(&slots[j]);
            slotDone_[j] = 1;
            points += n;
        }
        if (group_.size() == 1) shadeSlot(*s.grid, s.k, s.time);
        else shadeBatch(group_.data(), group_.size());
    }
}

void GridShader::shadeBatch(const Slot* const* slots, size_t count) {
    const Grid& first = *slots[0]->grid;
    const Material& m = *first.material;
    const double time = slots[0]->time;  // the others' give the same spaces (timeClass)
    int total = 0;
    for (size_t b = 0; b < count; ++b) total += slots[b]->grid->vertexCount();
    // One row of `total` points carrying the grids' inputs one after another.
    batch_.shadowSlots = first.shadowSlots;
    batch_.aovCount = 0;
    batch_.material = &m;
    batch_.primitiveId = first.primitiveId;
    batch_.primvarCorners = nullptr;
    batch_.u0 = first.u0, batch_.u1 = first.u1, batch_.v0 = first.v0, batch_.v1 = first.v1;
    batch_.t0 = batch_.t1 = time;
    // Its arrays only grow: every value a run reads is written below, so a shorter row needs no
    // zero-filling (Grid::resize would fill what a longer one left).
    if (batch_.P[0].size() < size_t(total) || batch_.Cl[0].size() < size_t(total) * size_t(first.shadowSlots))
        batch_.resize(total - 1, 0, false);
    batch_.nu = total - 1;
    batch_.nv = 0;
    batch_.moving = false;
    parts_.resize(count);
    int at = 0;
    for (size_t b = 0; b < count; ++b) {
        const Grid& g = *slots[b]->grid;
        const int k = slots[b]->k, n = g.vertexCount();
        std::copy(g.P[k].begin(), g.P[k].begin() + n, batch_.P[0].begin() + at);
        std::copy(g.N[k].begin(), g.N[k].begin() + n, batch_.N[0].begin() + at);
        std::copy(g.Cs.begin(), g.Cs.begin() + n, batch_.Cs.begin() + at);
        parts_[b] = {at, g.nu, g.nv};
        at += n;
    }
    prepare(m, batch_, 0, time);
    // What prepare made of the row as one grid, each grid's own: u and v over its piece (as
    // prepare spreads them), du and dv at each of its points (varying globals: the grids of a
    // batch may be diced at other rates), its shape.
    batchDu_.resize(size_t(total));
    batchDv_.resize(size_t(total));
    for (size_t b = 0; b < count; ++b) {
        const Grid& g = *slots[b]->grid;
        const float du = stepU(g), dv = stepV(g);
        const int o = parts_[b].offset, n = g.vertexCount();
        float* u = u_.data() + o;
        float* v = v_.data() + o;
        for (int j = 0; j <= g.nv; ++j)
            for (int i = 0; i <= g.nu; ++i) {
                u[g.index(i, j)] = i == g.nu ? g.u1 : g.u0 + float(i) * du;
                v[g.index(i, j)] = j == g.nv ? g.v1 : g.v0 + float(j) * dv;
            }
        std::fill_n(batchDu_.begin() + o, n, du);
        std::fill_n(batchDv_.begin() + o, n, dv);
    }
    sgrid_.set(sl::Global::du, sl::ValueRef::soa(batchDu_.data()));
    sgrid_.set(sl::Global::dv, sl::ValueRef::soa(batchDv_.data()));
    sgrid_.nu = sgrid_.nv = 0;
    sgrid_.parts = parts_.data();
    sgrid_.partCount = int(count);
    try {
        runSurface(m, batch_, 0, time);
    } catch (const sl::BatchRefused&) {
        // A grid-wide operation ran (a light's shadow map, a texture ...): each grid alone, and
        // the material's grids alone from now on.
        sgrid_.parts = nullptr;
        sgrid_.partCount = 0;
        refused_.push_back(&m);
        for (size_t b = 0; b < count; ++b) shadeSlot(*slots[b]->grid, slots[b]->k, slots[b]->time);
        return;
    }
    const sl::ValueRef oi = vm_->result(sl::Global::Oi);  // as shadeSurface reads it, after every run
    sgrid_.parts = nullptr;
    sgrid_.partCount = 0;
    // Back to each grid: Ci, the shadowed lights' parts, and Oi kept where some point of the
    // grid is see-through (shadeSurface's rule, grid by grid).
    const size_t slotsPer = size_t(first.shadowSlots);
    for (size_t b = 0; b < count; ++b) {
        Grid& g = *slots[b]->grid;
        const int k = slots[b]->k, n = g.vertexCount(), o = parts_[b].offset;
        std::copy(batch_.Ci[0].begin() + o, batch_.Ci[0].begin() + o + n, g.Ci[k].begin());
        if (slotsPer > 0)
            std::copy(batch_.Cl[0].begin() + long(size_t(o) * slotsPer), batch_.Cl[0].begin() + long(size_t(o + n) * slotsPer),
                      g.Cl[k].begin());
        g.Oi[k].clear();
        if (!oi.valid()) continue;
        for (int i = 0; i < n; ++i) {
            const Color c = oi.vec(o + i);
            if (!(c.x >= 1 && c.y >= 1 && c.z >= 1)) {
                g.Oi[k].resize(size_t(n));
                for (int j = 0; j < n; ++j) g.Oi[k][size_t(j)] = clampOpacityOf(oi.vec(o + j));
                break;
            }
        }
    }
    ++batchRuns_;
    batchedGrids_ += count;
}

}  // namespace streyes
