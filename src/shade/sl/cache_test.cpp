// The shader cache: found along the search path, compiled once per file and modification
// time, shared by threads.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <thread>

#include <unistd.h>

#include "shade/vm/vm_test_util.h"

namespace streyes::sl {
namespace {

namespace fs = std::filesystem;

struct ScratchDir {
    fs::path path;
    ScratchDir() {
        path = fs::temp_directory_path() / ("streyes-sl-" + std::to_string(::getpid()) + "-" +
                                            std::to_string(std::chrono::steady_clock::now().time_since_epoch().count()));
        fs::create_directories(path);
    }
    ~ScratchDir() {
        std::error_code ec;
        fs::remove_all(path, ec);
    }
    void write(const std::string& name, const std::string& text) {
        std::ofstream(path / name) << text;
    }
};

TEST(SlCache, CompilesOncePerFileAndModificationTime) {
    ScratchDir dir;
    dir.write("glow.sl", "surface glow(float k = 1) { Ci = k; }");
    ShaderCache cache({dir.path.string(), std::string(STREYES_SOURCE_DIR) + "/shaders"});
    ProgramPtr a = cache.get("glow");
    ProgramPtr b = cache.get("glow.sl");
    EXPECT_EQ(a, b);
    EXPECT_EQ(cache.compiledCount(), 1u);
    EXPECT_EQ(cache.get("plastic")->name, "plastic");  // further along the path
    // Edited: compiled again.
    dir.write("glow.sl", "surface glow(float k = 2) { Ci = k; }");
    fs::last_write_time(dir.path / "glow.sl", fs::last_write_time(dir.path / "glow.sl") + std::chrono::seconds(5));
    ProgramPtr c = cache.get("glow");
    EXPECT_NE(a, c);
    EXPECT_FLOAT_EQ(c->params[0].defaultFloats[0], 2.0f);
    // Not found: an error at the request.
    SourceLoc loc{std::make_shared<const std::string>("scene.rib"), 4};
    try {
        cache.get("nosuch", loc);
        FAIL();
    } catch (const InputError& e) {
        EXPECT_EQ(std::string(e.what()).rfind("scene.rib:4: shader \"nosuch\" not found", 0), 0u) << e.what();
    }
    // A bad shader: its own file:line:column.
    dir.write("bad.sl", "surface bad() {\n  Ci = nope;\n}\n");
    try {
        cache.get("bad");
        FAIL();
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("bad.sl:2:8: undefined variable 'nope'"), std::string::npos) << e.what();
    }
}

TEST(SlCache, SearchPathSpecification) {
    ShaderCache cache({"a", "std"});
    cache.setSearchPath("b:&");
    EXPECT_EQ(cache.searchPath(), (std::vector<std::string>{"b", "a", "std"}));
    cache.setSearchPath("c:@");  // '@' is the path the cache was made with, '&' the one before
    EXPECT_EQ(cache.searchPath(), (std::vector<std::string>{"c", "a", "std"}));
}

TEST(SlCache, ThreadsShareOneCompilationAndShadeIndependently) {
    ShaderCache cache({std::string(STREYES_SOURCE_DIR) + "/shaders"});
    std::vector<ProgramPtr> got(8);
    std::vector<float> red(8);
    std::vector<std::thread> threads;
    for (int k = 0; k < 8; ++k)
        threads.emplace_back([&, k] {
            got[size_t(k)] = cache.get("ground");
            ShaderInstance inst(got[size_t(k)]);
            test::TestGrid g(16, 16);
            g.setVarying(Global::P, 3, [](int i) { return Vec3f{float(i % 17) * 0.1f, 0, float(i / 17) * 0.1f}; });
            g.setVec(Global::N, {0, 1, 0});
            g.setVec(Global::I, {0, -1, 0});
            ShadingVM vm;  // one per thread
            vm.run(inst, g.grid);
            red[size_t(k)] = vm.result(Global::Ci).at(0, 100);
        });
    for (auto& t : threads) t.join();
    EXPECT_EQ(cache.compiledCount(), 1u);
    for (int k = 1; k < 8; ++k) {
        EXPECT_EQ(got[size_t(k)], got[0]);
        EXPECT_EQ(red[size_t(k)], red[0]);
    }
}

}  // namespace
}  // namespace streyes::sl
