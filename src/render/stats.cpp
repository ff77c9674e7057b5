#include "streyes/stats.h"

#include <sys/resource.h>

#include <cstdio>
#include <sstream>

namespace streyes {

RenderCounters& RenderCounters::operator+=(const RenderCounters& o) {
    rootBodies += o.rootBodies;
    splitsU += o.splitsU;
    splitsV += o.splitsV;
    splitsT += o.splitsT;
    eyeSplits += o.eyeSplits;
    culledView += o.culledView;
    culledClip += o.culledClip;
    culledEyeLimit += o.culledEyeLimit;
    culledSplitLimit += o.culledSplitLimit;
    culledOcclusion += o.culledOcclusion;
    occlusionTables += o.occlusionTables;
    proceduralsExpanded += o.proceduralsExpanded;
    auto addVec = [](std::vector<uint64_t>& a, const std::vector<uint64_t>& b) {
        if (a.size() < b.size()) a.resize(b.size(), 0);
        for (size_t i = 0; i < b.size(); ++i) a[i] += b[i];
    };
    addVec(culledOcclusionByLayer, o.culledOcclusionByLayer);
    addVec(cellsCoveredByLayer, o.cellsCoveredByLayer);
    addVec(proceduralsExpandedByDepth, o.proceduralsExpandedByDepth);
    timeOcclusion += o.timeOcclusion;
    gridsDiced += o.gridsDiced;
    micropolygons += o.micropolygons;
    sampleTests += o.sampleTests;
    sampleHits += o.sampleHits;
    buckets += o.buckets;
    traceBodies += o.traceBodies;
    boundingVolumes += o.boundingVolumes;
    eyeRays += o.eyeRays;
    shadowRays += o.shadowRays;
    rayBodyTests += o.rayBodyTests;
    rayBoxTests += o.rayBoxTests;
    timeSampleGen += o.timeSampleGen;
    timeSplit += o.timeSplit;
    timeDice += o.timeDice;
    timeShade += o.timeShade;
    timeSample += o.timeSample;
    timeResolve += o.timeResolve;
    timeHierarchy += o.timeHierarchy;
    timeTrace += o.timeTrace;
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
std::string list(const std::vector<uint64_t>& v) {
    std::string s = "[";
    for (size_t i = 0; i < v.size(); ++i) s += (i ? ", " : "") + std::to_string(v[i]);
    return s + "]";
}

std::string num(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.6g", v);
    return buf;
}
}  // namespace

std::string RenderStats::toJson() const {
    const RenderCounters& c = counters;
    std::ostringstream o;
    o << "{\n"
      << "  \"algorithm\": \"" << algorithm << "\",\n"
      << "  \"frames\": [" << firstFrame << ", " << lastFrame << "],\n"
      << "  \"resolution\": [" << width << ", " << height << "],\n"
      << "  \"samples_per_pixel\": " << samplesPerPixel << ",\n"
      << "  \"threads\": " << threads << ",\n"
      << "  \"bucket_size\": " << bucketSize << ",\n"
      << "  \"frame_block\": " << frameBlock << ",\n"
      << "  \"tolerance\": " << num(tolerance) << ",\n"
      << "  \"layers\": " << (layers > 0 ? std::to_string(layers) : std::string("\"adaptive\"")) << ",\n"
      << "  \"counters\": {\n"
      << "    \"root_bodies\": " << c.rootBodies << ",\n"
      << "    \"buckets\": " << c.buckets << ",\n"
      << "    \"splits\": {\"u\": " << c.splitsU << ", \"v\": " << c.splitsV << ", \"t\": " << c.splitsT
      << ", \"total\": " << c.splits() << "},\n"
      << "    \"eye_splits\": " << c.eyeSplits << ",\n"
      << "    \"culled_view\": " << c.culledView << ",\n"
      << "    \"culled_clip\": " << c.culledClip << ",\n"
      << "    \"culled_eye_split_limit\": " << c.culledEyeLimit << ",\n"
      << "    \"culled_split_limit\": " << c.culledSplitLimit << ",\n"
      << "    \"culled_occlusion\": " << c.culledOcclusion << ",\n"
      << "    \"culled_occlusion_by_layer\": " << list(c.culledOcclusionByLayer) << ",\n"
      << "    \"cells_covered_by_layer\": " << list(c.cellsCoveredByLayer) << ",\n"
      << "    \"occlusion_tables\": " << c.occlusionTables << ",\n"
      << "    \"procedurals\": " << procedurals << ",\n"
      << "    \"procedurals_expanded\": " << c.proceduralsExpanded << ",\n"
      << "    \"procedurals_by_depth\": " << list(proceduralsByDepth) << ",\n"
      << "    \"procedurals_expanded_by_depth\": " << list(c.proceduralsExpandedByDepth) << ",\n"
      << "    \"procedurals_never_expanded\": " << (procedurals - c.proceduralsExpanded) << ",\n"
      << "    \"bodies_generated\": " << bodiesGenerated << ",\n"
      << "    \"passes\": " << passes << ",\n"
      << "    \"grids_diced\": " << c.gridsDiced << ",\n"
      << "    \"micropolygons\": " << c.micropolygons << ",\n"
      << "    \"sample_tests\": " << c.sampleTests << ",\n"
      << "    \"sample_hits\": " << c.sampleHits << ",\n"
      << "    \"hit_efficiency\": " << num(c.sampleTests ? double(c.sampleHits) / double(c.sampleTests) : 0) << ",\n"
      << "    \"trace\": {\"bodies\": " << c.traceBodies << ", \"bounding_volumes\": " << c.boundingVolumes
      << ", \"eye_rays\": " << c.eyeRays
      << ", \"shadow_rays\": " << c.shadowRays << ", \"ray_body_tests\": " << c.rayBodyTests
      << ", \"ray_box_tests\": " << c.rayBoxTests << "}\n"
      << "  },\n"
      << "  \"seconds\": {\n"
      << "    \"parse\": " << num(timeParse) << ",\n"
      << "    \"build_bodies\": " << num(timeBuild) << ",\n"
      << "    \"render\": " << num(timeRender) << ",\n"
      << "    \"write\": " << num(timeWrite) << ",\n"
      << "    \"total\": " << num(timeTotal) << ",\n"
      << "    \"cpu_by_stage\": {\"sample_generation\": " << num(c.timeSampleGen) << ", \"split_cull\": "
      << num(c.timeSplit) << ", \"dice\": " << num(c.timeDice) << ", \"shade\": " << num(c.timeShade)
      << ", \"sample\": " << num(c.timeSample) << ", \"occlusion_tables\": " << num(c.timeOcclusion)
      << ", \"resolve\": " << num(c.timeResolve) << ", \"hierarchy_build\": " << num(c.timeHierarchy)
      << ", \"trace\": " << num(c.timeTrace) << "}\n"
      << "  },\n"
      << "  \"peak_memory_bytes\": " << peakMemoryBytes << ",\n"
      << "  \"memory_estimate_bytes\": " << memoryEstimateBytes << ",\n"
      << "  \"memory_budget_bytes\": " << memoryBudgetBytes << ",\n"
      << "  \"memory_program_bytes\": " << memoryProgramBytes << ",\n"
      << "  \"frames_skipped\": " << framesSkipped << "\n"
      << "}\n";
    return o.str();
}

}  // namespace streyes
