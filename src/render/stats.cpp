#include "streyes/stats.h"

#include <sys/resource.h>

#include <cstdio>

#include <nlohmann/json.hpp>

namespace streyes {

RenderCounters& RenderCounters::operator+=(const RenderCounters& o) {
    auto addList = [](std::vector<uint64_t>& a, const std::vector<uint64_t>& b) {
        if (a.size() < b.size()) a.resize(b.size(), 0);
        for (size_t i = 0; i < b.size(); ++i) a[i] += b[i];
    };
#define STREYES_ADD(member, key) member += o.member;
#define STREYES_ADD_LIST(member, key) addList(member, o.member);
#define STREYES_NOTHING(key, expression)
    STREYES_RENDER_COUNTERS(STREYES_ADD, STREYES_ADD_LIST, STREYES_ADD, STREYES_NOTHING)
#undef STREYES_ADD
#undef STREYES_ADD_LIST
#undef STREYES_NOTHING
    return *this;
}

uint64_t peakResidentBytes() {
    // VmHWM, which writing "5" to /proc/self/clear_refs resets (tests measure one render that
    // way); getrusage's maximum, which nothing resets, where /proc is not there.
    if (FILE* f = std::fopen("/proc/self/status", "r")) {
        char line[256];
        unsigned long long kb = 0;
        bool found = false;
        while (!found && std::fgets(line, sizeof line, f)) found = std::sscanf(line, "VmHWM: %llu kB", &kb) == 1;
        std::fclose(f);
        if (found) return uint64_t(kb) * 1024;
    }
    struct rusage ru {};
    getrusage(RUSAGE_SELF, &ru);
    return uint64_t(ru.ru_maxrss) * 1024;  // Linux reports kilobytes
}

namespace {
using Json = nlohmann::ordered_json;

// A field "group.key" goes in the object "group" (made when first met), others at the top.
void setField(Json& object, const std::string& path, Json value) {
    const size_t dot = path.find('.');
    if (dot == std::string::npos) object[path] = std::move(value);
    else object[path.substr(0, dot)][path.substr(dot + 1)] = std::move(value);
}
}  // namespace

std::string RenderStats::toJson() const {
    const RenderStats& s = *this;
    const RenderCounters& c = counters;
    Json o = Json::object();
    o["algorithm"] = algorithm;
    o["frames"] = {firstFrame, lastFrame};
    o["resolution"] = {width, height};
    o["samples_per_pixel"] = samplesPerPixel;
    o["threads"] = threads;
    o["simd"] = simd;
    o["bucket_size"] = bucketSize;
    o["frame_block"] = frameBlock;
    o["tolerance"] = tolerance;
    o["layers"] = layers > 0 ? Json(layers) : Json("adaptive");
    if (!layerDepths.empty()) o["layer_depths"] = layerDepths;
    Json& counts = o["counters"] = Json::object();
#define STREYES_FIELD(member, key) setField(counts, key, c.member);
#define STREYES_SHOWN(key, expression) setField(counts, key, expression);
#define STREYES_NOTHING(member, key)
    STREYES_RENDER_COUNTERS(STREYES_FIELD, STREYES_FIELD, STREYES_NOTHING, STREYES_SHOWN)
    Json& seconds = o["seconds"] = Json::object();
    seconds["parse"] = timeParse;
    seconds["build_bodies"] = timeBuild;
    seconds["render"] = timeRender;
    seconds["write"] = timeWrite;
    seconds["total"] = timeTotal;
#define STREYES_SECONDS(member, key) setField(seconds, key, c.member);
#define STREYES_NOTHING_SHOWN(key, expression)
    STREYES_RENDER_COUNTERS(STREYES_NOTHING, STREYES_NOTHING, STREYES_SECONDS, STREYES_NOTHING_SHOWN)
#undef STREYES_FIELD
#undef STREYES_SHOWN
#undef STREYES_NOTHING
#undef STREYES_SECONDS
#undef STREYES_NOTHING_SHOWN
    o["peak_memory_bytes"] = peakMemoryBytes;
    o["memory_estimate_bytes"] = memoryEstimateBytes;
    o["memory_budget_bytes"] = memoryBudgetBytes;
    o["memory_program_bytes"] = memoryProgramBytes;
    o["memory_bodies_bytes"] = memoryBodiesBytes;
    o["exr_chunks_compressed"] = exrChunksCompressed;
    o["exr_chunks_reused"] = exrChunksReused;
    o["frames_skipped"] = framesSkipped;
    // NaN and infinities (a ratio of nothing) as null, which JSON readers take.
    return o.dump(2, ' ', false, Json::error_handler_t::replace) + "\n";
}

}  // namespace streyes
