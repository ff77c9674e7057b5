// A RIB's values for a shader's unsized (resizable) array parameters: the array takes the
// value's length; a fixed-size array given another count stays an error at the RIB's line.
#include <gtest/gtest.h>

#include <string>

#include "shade/scene_shaders.h"
#include "shade/sl/compiler.h"
#include "shade/vm/vm.h"
#include "streyes/rib.h"

namespace streyes {
namespace {

const char* const kShader =
    "float sumOf(float v[]) {\n"
    "  float s = 0;\n"
    "  uniform float i;\n"
    "  for (i = 0; i < arraylength(v); i += 1) s += v[i];\n"
    "  return s;\n"
    "}\n"
    "surface arrsum(float a[] = {1, 2}; float b[2] = {0, 0}; output uniform float total = 0;\n"
    "               output uniform float count = 0) {\n"
    "  total = sumOf(a) + sumOf(b);\n"
    "  count = arraylength(a);\n"
    "}\n";

// The surface's parameters of the first sphere of a RIB world body.
ParamList surfaceParams(const std::string& world, Scene& scene) {
    Log log;
    const std::string rib = "Display \"t.exr\" \"file\" \"rgba\"\nFormat 16 16 1\nProjection \"perspective\"\n"
                            "WorldBegin\n" + world + "\nWorldEnd\n";
    scene = parseRibString(rib, "arrays.rib", log);
    EXPECT_EQ(scene.quadrics.size(), 1u);
    return scene.quadrics.empty() ? ParamList{} : scene.quadrics[0].attributes->surface.params;
}

// total and count after running the shader with the surface's parameters from `world`.
std::pair<float, float> run(const std::string& world) {
    Scene scene;
    const ParamList params = surfaceParams(world, scene);
    sl::ShaderInstance inst(sl::compileShader(kShader, "arrsum.sl"));
    Log log;
    setShaderParams(inst, params, log);
    sl::ShadingGrid grid;
    grid.n = 4;
    sl::ShadingVM vm;
    vm.run(inst, grid);
    return {vm.output("total").at(0, 0), vm.output("count").at(0, 0)};
}

TEST(ResizableArrayParams, TheRibsValueSizesAnUnsizedParameter) {
    EXPECT_EQ(run("Surface \"arrsum\"\nSphere 1 -1 1 360"), std::make_pair(3.0f, 2.0f));
    EXPECT_EQ(run("Surface \"arrsum\" \"float a\" [1 2 3 4]\nSphere 1 -1 1 360"), std::make_pair(10.0f, 4.0f));
    // Undeclared, it takes the shader's type; a declared length is a length like any other.
    EXPECT_EQ(run("Surface \"arrsum\" \"a\" [5 6 7]\nSphere 1 -1 1 360"), std::make_pair(18.0f, 3.0f));
    EXPECT_EQ(run("Surface \"arrsum\" \"float[5] a\" [1 1 1 1 1] \"b\" [2 3]\nSphere 1 -1 1 360"),
              std::make_pair(10.0f, 5.0f));
}

TEST(ResizableArrayParams, AFixedArrayGivenAnotherCountIsAnErrorAtTheRibLine) {
    try {
        run("Surface \"arrsum\" \"float b\" [1 2 3]\nSphere 1 -1 1 360");
        ADD_FAILURE() << "no error";
    } catch (const InputError& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("arrays.rib:5"), std::string::npos) << what;
        EXPECT_NE(what.find("it takes 2 values, not 3"), std::string::npos) << what;
    }
}

}  // namespace
}  // namespace streyes
