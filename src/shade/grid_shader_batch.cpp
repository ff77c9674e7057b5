// Small grids of one material shaded together: one interpreter run over their points, each grid
// differenced on its own (sl::ShadingGrid::parts). On scenes of many small grids (the forest's
// leaves: about 12 points a run) a run's fixed costs (binding, the per-instruction dispatch and
// set-up, the lights' checks) outweigh its per-point work; a batch pays them once.
//
// Sound only where one run gives every point the value its grid alone gives it, bit for bit:
// the uniform inputs of the run must be the same for all its grids (the key below: the material,
// which fixes the shaders, their instances, lights, attributes and Os; the shading time, which
// fixes every space, the lights' places and `time`; the shadow slots), and the programs must
// compute each point from its own grid (sl::batchProgramSafe). du and dv, which differ with
// each grid's dicing rate, are varying globals: bound point by point, each grid's own (on the
// forest, keying batches by them cut runs to 4.7 grids; without: 16).
#include <algorithm>

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

// Can slots a and b share a run? Not keyed by du and dv: they are bound point by point.
bool sameKey(const GridShader::Slot& a, const GridShader::Slot& b) {
    return a.grid->material == b.grid->material && a.time == b.time && a.grid->shadowSlots == b.grid->shadowSlots;
}

}  // namespace

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
    for (size_t i = 0; i < count; ++i) {
        if (slotDone_[i]) continue;
        const Slot& s = slots[i];
        if (!batchable(s.grid->material, s.grid->vertexCount(), s.grid->aovCount)) {
            shadeSlot(*s.grid, s.k, s.time);
            slotDone_[i] = 1;
            continue;
        }
        // This slot and the later ones of its key, in order, kBatchPoints at most a run.
        group_.clear();
        int points = 0;
        for (size_t j = i; j < count; ++j) {
            if (slotDone_[j] || !sameKey(s, slots[j])) continue;
            const int n = slots[j].grid->vertexCount();
            if (points + n > kBatchPoints) break;
            if (j != i && !batchable(slots[j].grid->material, n, slots[j].grid->aovCount)) continue;
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
    const double time = slots[0]->time;
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
    batch_.resize(total - 1, 0, false);
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
