#include "streyes/stats.h"

#include <sys/resource.h>

#include <cstdio>
#include <sstream>

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
std::string value(const std::vector<uint64_t>& v) {
    std::string s = "[";
    for (size_t i = 0; i < v.size(); ++i) s += (i ? ", " : "") + std::to_string(v[i]);
    return s + "]";
}
std::string value(uint64_t v) { return std::to_string(v); }
std::string value(int v) { return std::to_string(v); }
std::string value(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.6g", v);
    return buf;
}
std::string value(const std::vector<float>& v) {
    std::string s = "[";
    for (size_t i = 0; i < v.size(); ++i) s += (i ? ", " : "") + value(double(v[i]));
    return s + "]";
}

// The fields of one JSON object, a line each; fields "group.key" that follow each other share a
// line as the object "group": {"key": ..., ...}.
class JsonFields {
  public:
    JsonFields(std::ostringstream& out, const char* indent) : out_(out), indent_(indent) {}
    void add(const std::string& path, const std::string& v) {
        const size_t dot = path.find('.');
        const std::string group = dot == std::string::npos ? "" : path.substr(0, dot);
        const std::string key = dot == std::string::npos ? path : path.substr(dot + 1);
        if (fields_ > 0 && !group.empty() && group == group_) {
            out_ << ", ";
        } else {
            if (fields_ > 0) out_ << (group_.empty() ? "" : "}") << ",\n";
            out_ << indent_;
            if (!group.empty()) out_ << "\"" << group << "\": {";
        }
        out_ << "\"" << key << "\": " << v;
        group_ = group;
        ++fields_;
    }
    void end() { out_ << (group_.empty() ? "" : "}") << "\n"; }

  private:
    std::ostringstream& out_;
    const char* indent_;
    std::string group_;
    int fields_ = 0;
};
}  // namespace

std::string RenderStats::toJson() const {
    const RenderStats& s = *this;
    const RenderCounters& c = counters;
    std::ostringstream o;
    o << "{\n"
      << "  \"algorithm\": \"" << algorithm << "\",\n"
      << "  \"frames\": [" << firstFrame << ", " << lastFrame << "],\n"
      << "  \"resolution\": [" << width << ", " << height << "],\n"
      << "  \"samples_per_pixel\": " << samplesPerPixel << ",\n"
      << "  \"threads\": " << threads << ",\n"
      << "  \"simd\": \"" << simd << "\",\n"
      << "  \"bucket_size\": " << bucketSize << ",\n"
      << "  \"frame_block\": " << frameBlock << ",\n"
      << "  \"tolerance\": " << value(tolerance) << ",\n"
      << "  \"layers\": " << (layers > 0 ? std::to_string(layers) : std::string("\"adaptive\"")) << ",\n";
    if (!layerDepths.empty()) o << "  \"layer_depths\": " << value(layerDepths) << ",\n";
    o << "  \"counters\": {\n";
    JsonFields counts(o, "    ");
#define STREYES_FIELD(member, key) counts.add(key, value(c.member));
#define STREYES_SHOWN(key, expression) counts.add(key, value(expression));
#define STREYES_NOTHING(member, key)
    STREYES_RENDER_COUNTERS(STREYES_FIELD, STREYES_FIELD, STREYES_NOTHING, STREYES_SHOWN)
    counts.end();
    o << "  },\n"
      << "  \"seconds\": {\n";
    JsonFields seconds(o, "    ");
    seconds.add("parse", value(timeParse));
    seconds.add("build_bodies", value(timeBuild));
    seconds.add("render", value(timeRender));
    seconds.add("write", value(timeWrite));
    seconds.add("total", value(timeTotal));
#define STREYES_SECONDS(member, key) seconds.add(key, value(c.member));
#define STREYES_NOTHING_SHOWN(key, expression)
    STREYES_RENDER_COUNTERS(STREYES_NOTHING, STREYES_NOTHING, STREYES_SECONDS, STREYES_NOTHING_SHOWN)
#undef STREYES_FIELD
#undef STREYES_SHOWN
#undef STREYES_NOTHING
#undef STREYES_SECONDS
#undef STREYES_NOTHING_SHOWN
    seconds.end();
    o << "  },\n"
      << "  \"peak_memory_bytes\": " << peakMemoryBytes << ",\n"
      << "  \"memory_estimate_bytes\": " << memoryEstimateBytes << ",\n"
      << "  \"memory_budget_bytes\": " << memoryBudgetBytes << ",\n"
      << "  \"memory_program_bytes\": " << memoryProgramBytes << ",\n"
      << "  \"memory_bodies_bytes\": " << memoryBodiesBytes << ",\n"
      << "  \"exr_chunks_compressed\": " << exrChunksCompressed << ",\n"
      << "  \"exr_chunks_reused\": " << exrChunksReused << ",\n"
      << "  \"frames_skipped\": " << framesSkipped << "\n"
      << "}\n";
    return o.str();
}

}  // namespace streyes
