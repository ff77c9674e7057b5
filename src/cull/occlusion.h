// Occlusion culling with summed-volume tables (the second paper's Algorithms C' and S).
//
// After each depth layer, the coverage volume C[f][y][x] (1 where every sample of pixel (x, y)
// in frame f is hit by an opaque surface nearer than the layer's boundary) is summed into a
// table of integers, exact, with no float drift. For a body's raster-spacetime block
// [x0,x1] x [y0,y1] x [f0,f1] (volume B), eight lookups give the covered count A; the body is
// dropped when B - A <= epsilon * B. With one frame the table is Catmull's summed-area table.
#pragma once

#include <cstddef>
#include <cstdint>
#include <type_traits>
#include <vector>


namespace streyes {

// Inclusive cell ranges of a raster-spacetime block.
struct CellBlock {
    int x0, x1, y0, y1, f0, f1;
    uint64_t volume() const { return uint64_t(x1 - x0 + 1) * uint64_t(y1 - y0 + 1) * uint64_t(f1 - f0 + 1); }
};

// T[f][y][x] = sum of C over [0..x] x [0..y] x [0..f]. Count is uint32_t where the volume fits
// (every count is at most the volume), uint64_t beyond.
template <typename Count>
class SummedVolumeTable {
    static_assert(std::is_unsigned<Count>::value, "counts are unsigned integers");

  public:
    // Builds from a 0/1 volume, coverage[(f * height + y) * width + x], with three separable
    // prefix-sum passes (x, then y, then f).
    void build(const uint8_t* coverage, int width, int height, int depth);

    int width() const { return w_; }
    int height() const { return h_; }
    int depth() const { return d_; }
    // Covered cells in the block (ranges inside the table): eight lookups.
    Count sum(const CellBlock& b) const {
        return Count(at(b.x1, b.y1, b.f1) - at(b.x0 - 1, b.y1, b.f1) - at(b.x1, b.y0 - 1, b.f1) -
                     at(b.x1, b.y1, b.f0 - 1) + at(b.x0 - 1, b.y0 - 1, b.f1) + at(b.x0 - 1, b.y1, b.f0 - 1) +
                     at(b.x1, b.y0 - 1, b.f0 - 1) - at(b.x0 - 1, b.y0 - 1, b.f0 - 1));
    }
    size_t bytes() const { return t_.capacity() * sizeof(Count); }

  private:
    // Table entry, with 0 for any index of -1 (the empty prefix).
    Count at(int x, int y, int f) const {
        if (x < 0 || y < 0 || f < 0) return 0;
        return t_[(size_t(f) * size_t(h_) + size_t(y)) * size_t(w_) + size_t(x)];
    }
    std::vector<Count> t_;
    int w_ = 0, h_ = 0, d_ = 0;
};

extern template class SummedVolumeTable<uint32_t>;
extern template class SummedVolumeTable<uint64_t>;

// The culling rule: drop when B - A <= epsilon * B. epsilon * B is computed in double with a
// relative slack of 1e-12, so a block exactly at the threshold (B - A == epsilon * B in exact
// arithmetic) is dropped even when epsilon has no exact binary form.
inline bool occludedWithin(uint64_t volume, uint64_t covered, double epsilon) {
    const double uncovered = double(volume - covered);
    return uncovered <= epsilon * double(volume) * (1.0 + 1e-12);
}

}  // namespace streyes
