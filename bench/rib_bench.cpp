// Reading RIB as it is stored: a parse-heavy scene (scenes/grove.rib, 350 KB of meshes and
// curves) as ASCII, as binary RIB with 64- and 32-bit reals, and gzip-compressed. Bytes/s are of
// the file as read (the compressed size for gzip).
#include <benchmark/benchmark.h>

#include <fstream>
#include <sstream>

#include "scene/rib_gzip.h"
#include "scene/rib_writer.h"
#include "streyes/rib.h"

namespace streyes {
namespace {

const std::string& groveText() {
    static const std::string text = [] {
        std::ifstream in(std::string(STREYES_SOURCE_DIR) + "/scenes/grove.rib", std::ios::binary);
        std::ostringstream s;
        s << in.rdbuf();
        return s.str();
    }();
    return text;
}

// 0 ASCII, 1 binary (64-bit reals), 2 binary (32-bit reals), 3 gzip ASCII, 4 gzip binary (32-bit).
std::string encoded(int kind) {
    const std::string& text = groveText();
    switch (kind) {
    case 1: return encodeRib(text, "grove.rib", {true, false, false});
    case 2: return encodeRib(text, "grove.rib", {true, true, false});
    case 3: return gzip(text);
    case 4: return encodeRib(text, "grove.rib", {true, true, true});
    default: return text;
    }
}

void BM_ParseRib(benchmark::State& state) {
    const std::string bytes = encoded(int(state.range(0)));
    const std::string path = std::string(STREYES_SOURCE_DIR) + "/scenes/grove.rib";  // shaders beside it
    Log log;
    log.setQuiet(true);
    for (auto _ : state) {
        Scene scene = parseRibString(bytes, path, log);
        benchmark::DoNotOptimize(scene.polygonMeshes.data());
    }
    state.SetBytesProcessed(int64_t(state.iterations()) * int64_t(bytes.size()));
    state.counters["file_bytes"] = double(bytes.size());
}
BENCHMARK(BM_ParseRib)->ArgName("encoding")->DenseRange(0, 4)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace streyes
