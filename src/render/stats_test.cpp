#include "streyes/stats.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>

#include <algorithm>
#include <string>
#include <vector>

namespace streyes {
namespace {

using Json = nlohmann::ordered_json;

// Every counter a different value, by its place in STREYES_RENDER_COUNTERS: counts 100 + i,
// lists {i, 2i} (one longer for odd i), seconds i + 0.25.
RenderCounters distinctCounters(uint64_t offset) {
    RenderCounters c;
    uint64_t i = offset;
#define STREYES_FILL_COUNT(member, key) c.member = 100 + i++;
#define STREYES_FILL_LIST(member, key)                 \
    c.member = {i, 2 * i};                             \
    if (i % 2) c.member.push_back(3 * i);              \
    ++i;
#define STREYES_FILL_SECONDS(member, key) c.member = double(i++) + 0.25;
#define STREYES_SKIP(key, expression)
    STREYES_RENDER_COUNTERS(STREYES_FILL_COUNT, STREYES_FILL_LIST, STREYES_FILL_SECONDS, STREYES_SKIP)
    return c;
}

TEST(RenderCounters, SumAddsEveryCounter) {
    const RenderCounters a = distinctCounters(0), b = distinctCounters(1000);
    RenderCounters sum = a;
    sum += b;
    auto listSum = [](const std::vector<uint64_t>& x, const std::vector<uint64_t>& y) {
        std::vector<uint64_t> r(std::max(x.size(), y.size()), 0);
        for (size_t k = 0; k < x.size(); ++k) r[k] += x[k];
        for (size_t k = 0; k < y.size(); ++k) r[k] += y[k];
        return r;
    };
#define STREYES_CHECK(member, key) EXPECT_EQ(sum.member, a.member + b.member) << key;
#define STREYES_CHECK_LIST(member, key) EXPECT_EQ(sum.member, listSum(a.member, b.member)) << key;
    STREYES_RENDER_COUNTERS(STREYES_CHECK, STREYES_CHECK_LIST, STREYES_CHECK, STREYES_SKIP)
    // Lists of different lengths: the shorter is padded, not truncated.
    EXPECT_EQ(sum.culledOcclusionByLayer.size(), 3u);
    EXPECT_EQ(sum.splits(), sum.splitsU + sum.splitsV + sum.splitsT);
}

// The --stats JSON is read by tools/ (streyes_runs.py, bench, speed-vs-error, occlusion-report):
// its keys, nesting, order and values, here in full (compared as JSON, not as text: the layout
// is nlohmann-json's). A new counter adds its line.
TEST(RenderStats, JsonKeepsItsKeysAndLayout) {
    RenderStats s;
    RenderCounters& c = s.counters;
    c.rootBodies = 12, c.buckets = 4, c.splitsU = 1, c.splitsV = 2, c.splitsT = 3, c.culledOcclusion = 9;
    c.culledOcclusionByLayer = {0, 4, 5}, c.cellsCoveredByLayer = {7}, c.proceduralsExpanded = 7;
    c.proceduralsExpandedByDepth = {1, 6}, c.sampleTests = 8, c.sampleHits = 6, c.eyeRays = 9, c.rayBoxTests = 11;
    c.timeSplit = 0.5, c.timeTrace = 1.25;
    s.algorithm = "spacetime-occlusion";
    s.firstFrame = 1, s.lastFrame = 8, s.width = 64, s.height = 36, s.samplesPerPixel = 16, s.threads = 2;
    s.simd = "AVX2";
    s.frameBlock = 8, s.bucketSize = 32, s.tolerance = 0.05, s.layers = 0;
    s.timeParse = 0.5, s.timeBuild = 1.5, s.timeRender = 2.5, s.timeWrite = 3.5, s.timeTotal = 8.125;
    s.peakMemoryBytes = 1 << 20, s.memoryEstimateBytes = 1 << 19, s.memoryBudgetBytes = 1 << 30;
    s.exrChunksCompressed = 23, s.exrChunksReused = 45;
    s.framesSkipped = 2, s.procedurals = 130, s.proceduralsByDepth = {1, 129}, s.bodiesGenerated = 999, s.passes = 2;
    const Json expected = Json::parse(R"({
  "algorithm": "spacetime-occlusion",
  "frames": [1, 8],
  "resolution": [64, 36],
  "samples_per_pixel": 16,
  "threads": 2,
  "simd": "AVX2",
  "bucket_size": 32,
  "frame_block": 8,
  "tolerance": 0.05,
  "layers": "adaptive",
  "counters": {
    "root_bodies": 12,
    "buckets": 4,
    "splits": {"u": 1, "v": 2, "t": 3, "total": 6},
    "eye_splits": 0,
    "culled_view": 0,
    "culled_clip": 0,
    "culled_eye_split_limit": 0,
    "culled_split_limit": 0,
    "culled_occlusion": 9,
    "culled_occlusion_by_layer": [0, 4, 5],
    "culled_hidden": 0,
    "cells_covered_by_layer": [7],
    "occlusion_tables": 0,
    "procedurals": 130,
    "procedurals_expanded": 7,
    "procedurals_by_depth": [1, 129],
    "procedurals_expanded_by_depth": [1, 6],
    "procedurals_released": 0,
    "procedurals_made_again": 0,
    "procedurals_never_expanded": 123,
    "bodies_generated": 999,
    "passes": 2,
    "renders": 1,
    "grids_diced": 0,
    "micropolygons": 0,
    "grids_shared": 0,
    "micropolygons_shared": 0,
    "grids_evicted": 0,
    "shading": {"points_builtin": 0, "points_surface": 0, "light_shader_runs": 0, "batch_runs": 0, "batched_grids": 0, "sanitised": 0, "indices_clamped": 0, "loops_stopped": 0},
    "sample_tests": 8,
    "sample_hits": 6,
    "samples_behind": 0,
    "grid_groups_behind": 0,
    "patch_groups_behind": 0,
    "patch_groups_outside": 0,
    "sample_fragments": 0,
    "hit_efficiency": 0.75,
    "trace": {"bodies": 0, "bounding_volumes": 0, "eye_rays": 9, "shadow_rays": 0, "shadow_vertex_rays": 0, "shadow_folded_grids": 0, "shader_rays": 0, "ray_body_tests": 0, "ray_box_tests": 11}
  },
  "seconds": {
    "parse": 0.5,
    "build_bodies": 1.5,
    "render": 2.5,
    "write": 3.5,
    "total": 8.125,
    "cpu_by_stage": {"sample_generation": 0, "split_cull": 0.5, "dice": 0, "shade": 0, "sample": 0, "occlusion_tables": 0, "resolve": 0, "hierarchy_build": 0, "trace": 1.25}
  },
  "peak_memory_bytes": 1048576,
  "memory_estimate_bytes": 524288,
  "memory_budget_bytes": 1073741824,
  "memory_program_bytes": 0,
  "memory_bodies_bytes": 0,
  "exr_chunks_compressed": 23,
  "exr_chunks_reused": 45,
  "frames_skipped": 2
}
)");
    const std::string text = s.toJson();
    EXPECT_EQ(Json::parse(text), expected) << text;  // ordered: the members' order counts too
    EXPECT_EQ(text.back(), '\n');
    s.layers = 3;  // a number, not "adaptive"
    EXPECT_EQ(Json::parse(s.toJson())["layers"], 3);
    // A ratio of nothing is null (JSON has no NaN), not a file no reader takes.
    s.tolerance = std::nan("");
    EXPECT_TRUE(Json::parse(s.toJson())["tolerance"].is_null());
}

}  // namespace
}  // namespace streyes
