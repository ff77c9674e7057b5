// gradientNoise over many points at once (noise.h, gradientNoisePoints): the SIMD kernel,
// compiled once per instruction set (Highway's foreach_target) and chosen at run time. It makes
// the scalar gradientNoise's operations in the same order on each lane (no fused multiply-add
// here: the build has -ffp-contract=off), so the two agree bit for bit (noise_test.cpp).
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "shade/vm/noise_kernels.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "shade/vm/noise.h"

HWY_BEFORE_NAMESPACE();
namespace streyes::sl {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

namespace {

const hn::ScalableTag<float> kF;
const hn::RebindToSigned<decltype(kF)> kI;
const hn::RebindToUnsigned<decltype(kF)> kU;
using VF = hn::Vec<decltype(kF)>;
using VI = hn::Vec<decltype(kI)>;
using VU = hn::Vec<decltype(kU)>;

// noise.cpp's hashInts of the 2^D corners of each lane's cell (corner c takes hi[k] where bit k
// of c is set, lo[k] elsewhere). A corner's state after k rounds depends on its first k
// coordinates alone, so corners share their rounds: 2 + 4 + ... + 2^D instead of D 2^D, each
// round the same integer operations as hashInts' (exact).
template <int D>
HWY_INLINE void cornerHashes(const VI* lo, const VI* hi, uint32_t seed, VU* h) {
    h[0] = hn::Set(kU, 0x9e3779b9u ^ seed);
    for (int k = 0; k < D; ++k) {
        VU x[2];
        for (int bit = 0; bit < 2; ++bit) {
            VU v = hn::Mul(hn::BitCast(kU, bit ? hi[k] : lo[k]), hn::Set(kU, 0xcc9e2d51u));
            v = hn::RotateRight<17>(v);  // (x << 15) | (x >> 17)
            x[bit] = hn::Mul(v, hn::Set(kU, 0x1b873593u));
        }
        // h[0, 2^k) hold the states so far: corner c | (1 << k) continues c's with hi[k] (written
        // first, past what is read), c itself with lo[k].
        for (int c = 0; c < (1 << k); ++c)
            for (int bit = 1; bit >= 0; --bit) {
                VU t = hn::Xor(h[c], x[bit]);
                t = hn::RotateRight<19>(t);  // (h << 13) | (h >> 19)
                h[c | (bit << k)] = hn::Add(hn::Mul(t, hn::Set(kU, 5u)), hn::Set(kU, 0xe6546b64u));
            }
    }
    for (int c = 0; c < (1 << D); ++c) {
        VU t = hn::Xor(h[c], hn::Set(kU, uint32_t(D)));
        t = hn::Xor(t, hn::ShiftRight<16>(t));
        t = hn::Mul(t, hn::Set(kU, 0x85ebca6bu));
        t = hn::Xor(t, hn::ShiftRight<13>(t));
        t = hn::Mul(t, hn::Set(kU, 0xc2b2ae35u));
        h[c] = hn::Xor(t, hn::ShiftRight<16>(t));
    }
}

// noise.cpp's gradDot: the lattice point's gradient (components from the hash's bytes) dotted
// with the offset d.
template <int D>
HWY_INLINE VF gradDotLanes(VU h, const VF* d) {
    const VU byte = hn::Set(kU, 0xffu);
    VF s = hn::Zero(kF);
    for (int k = 0; k < D; ++k) {
        VU bits;
        if (k == 0) bits = hn::And(h, byte);
        if (k == 1) bits = hn::And(hn::ShiftRight<8>(h), byte);
        if (k == 2) bits = hn::And(hn::ShiftRight<16>(h), byte);
        if (k == 3) bits = hn::And(hn::Xor(hn::ShiftRight<24>(h), hn::ShiftLeft<3>(h)), byte);
        const VF g = hn::Sub(hn::Mul(hn::ConvertTo(kF, hn::BitCast(kI, bits)), hn::Set(kF, 2.0f / 255.0f)), hn::Set(kF, 1.0f));
        s = hn::Add(s, hn::Mul(g, d[k]));
    }
    return s;
}

constexpr float kScale[5] = {0, 1.9f, 1.5f, 1.3f, 1.15f};  // noise.cpp's

template <int D>
void noiseLanes(const float* const* p, const int32_t* const* period, size_t n, uint32_t seed, float* out) {
    const size_t N = hn::Lanes(kF);
    const VF zero = hn::Zero(kF), one = hn::Set(kF, 1.0f);
    HWY_ALIGN float tail[D][hn::MaxLanes(kF)];
    HWY_ALIGN int32_t lanesBase[hn::MaxLanes(kF)];
    for (size_t i = 0; i < n; i += N) {
        const size_t m = std::min(N, n - i);
        VF frac[D], w[D];
        VI lo[D], hi[D];  // each coordinate's lattice points: the cell's, and the next (wrapped)
        bool far = false;
        for (int k = 0; k < D; ++k) {
            VF v;
            if (m == N) {
                v = hn::LoadU(kF, p[k] + i);
            } else {  // the last, partial vector: its other lanes compute on zeros
                std::fill(tail[k], tail[k] + N, 0.0f);
                std::copy(p[k] + i, p[k] + i + m, tail[k]);
                v = hn::Load(kF, tail[k]);
            }
            const VF pk = hn::IfThenElse(hn::IsFinite(v), v, zero);
            const VF f = hn::Floor(pk);
            // Far out noise.cpp wraps the lattice with fmod (cellOf): the scalar code does those.
            far = far || !hn::AllTrue(kF, hn::Lt(hn::Abs(f), hn::Set(kF, 1073741824.0f)));
            lo[k] = hn::ConvertTo(kI, f);
            frac[k] = hn::Sub(pk, f);
            const VF t = frac[k];  // fade: t t t (t (t 6 - 15) + 10)
            w[k] = hn::Mul(hn::Mul(hn::Mul(t, t), t),
                           hn::Add(hn::Mul(t, hn::Sub(hn::Mul(t, hn::Set(kF, 6.0f)), hn::Set(kF, 15.0f))), hn::Set(kF, 10.0f)));
            hi[k] = hn::Add(lo[k], hn::Set(kI, 1));
        }
        if (far) {
            for (size_t j = 0; j < m; ++j) {
                float q[D];
                int per[D];
                for (int k = 0; k < D; ++k) q[k] = p[k][i + j], per[k] = period ? period[k][i + j] : 1;
                out[i + j] = gradientNoise(D, q, period ? per : nullptr, seed);
            }
            continue;
        }
        if (period) {
            // c mod period, non-negative, as noise.cpp wraps each corner: the cell's lattice
            // point lane by lane (integer division has no SIMD form), the next one after it.
            for (int k = 0; k < D; ++k) {
                hn::Store(lo[k], kI, lanesBase);
                for (size_t j = 0; j < m; ++j) {
                    const int per = std::max(1, period[k][i + j]);
                    int c = lanesBase[j] % per;
                    if (c < 0) c += per;
                    lanesBase[j] = c;
                }
                HWY_ALIGN int32_t pers[hn::MaxLanes(kF)];
                for (size_t j = 0; j < N; ++j) pers[j] = j < m ? std::max(1, period[k][i + j]) : 1;
                lo[k] = hn::Load(kI, lanesBase);
                const VI next = hn::Add(lo[k], hn::Set(kI, 1));
                hi[k] = hn::IfThenZeroElse(hn::Eq(next, hn::Load(kI, pers)), next);
            }
        }
        VU hashes[1 << D];
        cornerHashes<D>(lo, hi, seed, hashes);
        VF sum = zero;
        for (int corner = 0; corner < (1 << D); ++corner) {
            VF d[D], weight = one;
            for (int k = 0; k < D; ++k) {
                const int bit = (corner >> k) & 1;
                d[k] = hn::Sub(frac[k], hn::Set(kF, float(bit)));
                weight = hn::Mul(weight, bit ? w[k] : hn::Sub(one, w[k]));
            }
            sum = hn::Add(sum, hn::Mul(weight, gradDotLanes<D>(hashes[corner], d)));
        }
        const VF v = hn::Add(hn::Set(kF, 0.5f), hn::Mul(hn::Set(kF, 0.5f * kScale[D]), sum));
        const VF atLeast0 = hn::IfThenElse(hn::Lt(zero, v), v, zero);  // std::max(0.0f, v)
        const VF clamped = hn::IfThenElse(hn::Lt(atLeast0, one), atLeast0, one);  // std::min(1.0f, ...)
        if (m == N) {
            hn::StoreU(clamped, kF, out + i);
        } else {
            hn::Store(clamped, kF, tail[0]);
            std::copy(tail[0], tail[0] + m, out + i);
        }
    }
}

void NoisePoints(int dims, const float* const* p, const int32_t* const* period, size_t n, uint32_t seed, float* out) {
    switch (dims) {
        case 1: return noiseLanes<1>(p, period, n, seed, out);
        case 2: return noiseLanes<2>(p, period, n, seed, out);
        case 3: return noiseLanes<3>(p, period, n, seed, out);
        default: return noiseLanes<4>(p, period, n, seed, out);
    }
}

}  // namespace

NoisePointsFn NoiseKernel() { return &NoisePoints; }
const char* NoiseTarget() { return hwy::TargetName(HWY_TARGET); }

}  // namespace HWY_NAMESPACE
}  // namespace streyes::sl
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace streyes::sl {

HWY_EXPORT(NoiseKernel);
HWY_EXPORT(NoiseTarget);

namespace {

void scalarNoisePoints(int dims, const float* const* p, const int32_t* const* period, size_t n, uint32_t seed, float* out) {
    for (size_t i = 0; i < n; ++i) {
        float q[4];
        int per[4];
        for (int k = 0; k < dims; ++k) q[k] = p[k][i], per[k] = period ? period[k][i] : 1;
        out[i] = gradientNoise(dims, q, period ? per : nullptr, seed);
    }
}

}  // namespace

NoisePointsFn noisePointsKernel() {
    static const NoisePointsFn kernel = HWY_DYNAMIC_DISPATCH(NoiseKernel)();
    return kernel;
}

NoisePointsFn noisePointsScalar() { return &scalarNoisePoints; }

void gradientNoisePoints(int dims, const float* const* p, const int32_t* const* period, size_t n, uint32_t seed,
                         float* out) {
    noisePointsKernel()(dims, p, period, n, seed, out);
}

std::vector<std::pair<std::string, NoisePointsFn>> noiseKernelsOfEveryTarget() {
    std::vector<std::pair<std::string, NoisePointsFn>> out;
    for (const int64_t target : hwy::SupportedAndGeneratedTargets()) {
        hwy::SetSupportedTargetsForTest(target);  // the next dispatch chooses it
        out.emplace_back(hwy::TargetName(target), HWY_DYNAMIC_DISPATCH(NoiseKernel)());
    }
    hwy::SetSupportedTargetsForTest(0);
    return out;
}

}  // namespace streyes::sl
#endif  // HWY_ONCE
