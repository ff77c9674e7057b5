// The built-in shading of part of a grid (shadeGridSlot's `need`): a bucket shades only the
// vertices it samples of a frame's grid (render/bucket_world.cpp). Those get the colours shading
// the whole grid gives them, bit for bit; the others keep what they held.
#include "shade/shading.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "geom/body.h"
#include "geom/grid.h"

namespace streyes {
namespace {

TEST(Shading, PartOfAGridIsShadedAsTheWholeGridShadesIt) {
    Material m;
    m.kind = SurfaceKind::Plastic;
    m.Ks = 1;
    m.roughness = 0.05f;
    LightDesc distant, point;
    distant.type = "distantlight";
    Param from;
    from.name = "from";
    from.type = ParamType::Point;
    from.nums = {-1, 2, -1};
    distant.params.params = {from};
    point.type = "pointlight";
    from.nums = {1, 1, 2};
    point.params.params = {from};
    const LightSet lights({distant, point}, MotionTransform());
    m.lights = {0, 1};
    // A bumpy 8 x 6 grid moving in depth: both slots shaded.
    TrilinearBody::Corners a{{{-1, -1, 4}, {1, -1, 5}, {-1, 1, 4.5f}, {1, 1, 3}}}, b = a;
    for (auto& c : b) c.z += 0.5f;
    TrilinearBody body({0, 1}, a, b, {}, &m);
    Grid whole;
    body.dice(8, 6, whole);
    whole.Cs.assign(whole.P[0].size(), Color{0.2f, 0.3f, 0.8f});
    Grid part = whole;
    const size_t n = size_t(whole.vertexCount());
    std::vector<uint8_t> need(n);
    for (size_t i = 0; i < n; ++i) need[i] = uint8_t((i * 7) % 3 == 0);
    const Color kUnshaded{-1, -2, -3};
    std::vector<CameraLight> scratch;
    for (int k = 0; k < 2; ++k) {
        part.Ci[k].assign(n, kUnshaded);
        shadeGridSlot(whole, k, k, lights, false, scratch);
        shadeGridSlot(part, k, k, lights, false, scratch, need.data());
    }
    size_t shaded = 0;
    for (int k = 0; k < 2; ++k)
        for (size_t i = 0; i < n; ++i) {
            const Color& got = part.Ci[k][i];
            const Color want = need[i] ? whole.Ci[k][i] : kUnshaded;
            ASSERT_EQ(std::memcmp(&got, &want, sizeof(Color)), 0) << "slot " << k << " vertex " << i;
            shaded += need[i];
            // Lit, and not all alike: the comparison is of real colours.
            if (need[i]) {
                ASSERT_GT(got.x + got.y + got.z, 0.0f);
            }
        }
    EXPECT_GT(shaded, n / 4);
    EXPECT_NE(std::memcmp(&whole.Ci[0][0], &whole.Ci[0][n - 1], sizeof(Color)), 0);
}

}  // namespace
}  // namespace streyes
