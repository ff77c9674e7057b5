// Which light shaders are directional (shade/light_direction.h): solar(axis, angle) with uniform
// arguments, read with the instance's parameters; never an illuminate light.
#include "shade/light_direction.h"

#include <gtest/gtest.h>

#include <cmath>

#include "shade/sl/compiler.h"
#include "shade/vm/vm_test_util.h"

namespace streyes {
namespace {

TEST(LightDirection, TheSunsAxisAndAngleComeFromItsParameters) {
    sl::ShaderInstance sun(sl::compileShaderFile(sl::test::shaderPath("sunlight")));
    std::optional<SolarCone> c = solarCone(sun, Matrix4());
    ASSERT_TRUE(c);  // the shader's defaults: from (0 1 1) to the origin, 0.27 degrees
    EXPECT_EQ(c->axis.x, 0.0);
    EXPECT_EQ(c->axis.y, -1.0);
    EXPECT_EQ(c->axis.z, -1.0);
    EXPECT_NEAR(c->angle, 0.27 * M_PI / 180, 1e-8);
    sun.set("from", sl::BaseType::Point, {3, 4, 0});
    sun.set("angle", sl::BaseType::Float, {2});
    c = solarCone(sun, Matrix4());
    ASSERT_TRUE(c);
    EXPECT_EQ(c->axis.x, -3.0);
    EXPECT_EQ(c->axis.y, -4.0);
    EXPECT_NEAR(c->angle, 2 * M_PI / 180, 1e-8);
    // A hard sun: angle 0.
    sun.set("angle", sl::BaseType::Float, {0});
    c = solarCone(sun, Matrix4());
    ASSERT_TRUE(c);
    EXPECT_EQ(c->angle, 0.0);
    sl::ShaderInstance hard(sl::compileShader(
        "light hardsun(point from = point \"shader\" (0, 0, 0); point to = point \"shader\" (0, 0, 1);) {\n"
        "  solar(to - from, 0) { Cl = 1; }\n}\n"));
    hard.set("to", sl::BaseType::Point, {1, 0, 1});
    c = solarCone(hard, Matrix4());
    ASSERT_TRUE(c);
    EXPECT_EQ(c->axis.x, 1.0);
    EXPECT_EQ(c->axis.z, 1.0);
    EXPECT_EQ(c->angle, 0.0);
    // An axis named in world space is taken to the light's own space.
    sl::ShaderInstance down(sl::compileShader("light down() { solar(vector \"world\" (0, -1, 0), 0.1) { Cl = 1; } }"));
    c = solarCone(down, Matrix4::rotate(90, {0, 0, 1}));
    ASSERT_TRUE(c);
    const Vec3d inWorld = Matrix4::rotate(90, {0, 0, 1}).vector(c->axis);
    EXPECT_NEAR(inWorld.x, 0, 1e-6);
    EXPECT_NEAR(inWorld.y, -1, 1e-6);
    EXPECT_NEAR(c->angle, 0.1, 1e-7);
}

TEST(LightDirection, LightsThatShineFromAPointOrVaryAreNot) {
    for (const char* source : {
             "light lamp(point from = point \"shader\" (0, 0, 0)) { illuminate(from) { Cl = 1; } }",
             "light both(point from = 0) { solar(vector(0, 0, 1), 0) { Cl = 1; } illuminate(from) { Cl = 1; } }",
             "light everywhere() { solar() { Cl = 1; } }",
             "light varies() { solar(Ps - point \"shader\" (0, 0, 0), 0) { Cl = 1; } }",
             "light amb() { Cl = 1; }",
         }) {
        SCOPED_TRACE(source);
        const sl::ShaderInstance l(sl::compileShader(source));
        EXPECT_FALSE(solarCone(l, Matrix4()));
    }
}

}  // namespace
}  // namespace streyes
