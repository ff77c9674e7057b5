// Render statistics: the counters every speed figure is quoted with, and the time per stage.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace streyes {

// Every counter of a render, once, in the order `--stats` writes it under "counters" (tools/ read
// that JSON): the struct's members, its sum (operator+=), the JSON (RenderStats::toJson) and the
// tests' comparison of two renders' counts are all made from this list, so a new counter is one
// line here. The four kinds, each given a JSON key ("group.key": inside the object "group",
// which the keys that follow each other share):
//   COUNT(member, key)      uint64_t, summed over buckets and threads
//   LIST(member, key)       std::vector<uint64_t> by layer or depth, summed element by element
//   SECONDS(member, key)    double, CPU seconds summed over threads (under "seconds" in the JSON)
//   SHOWN(key, expression)  written under "counters" but not a member: derived from the counters
//                           `c`, or the render's own (`s`, a RenderStats)
#define STREYES_RENDER_COUNTERS(COUNT, LIST, SECONDS, SHOWN)                                          \
    COUNT(rootBodies, "root_bodies") /* bodies made from the scene (a motion segment the frames reach) */ \
    COUNT(buckets, "buckets")                                                                          \
    COUNT(splitsU, "splits.u")                                                                         \
    COUNT(splitsV, "splits.v")                                                                         \
    COUNT(splitsT, "splits.t")                                                                         \
    SHOWN("splits.total", c.splits())                                                                  \
    COUNT(eyeSplits, "eye_splits")         /* splits of bodies reaching the eye plane */               \
    COUNT(culledView, "culled_view")       /* outside the bucket's spacetime block (incl. frustum) */  \
    COUNT(culledClip, "culled_clip")       /* wholly nearer than the near plane or beyond the far */   \
    COUNT(culledEyeLimit, "culled_eye_split_limit")  /* dropped at the eye-split limit */              \
    COUNT(culledSplitLimit, "culled_split_limit")    /* dropped at the split-depth limit or budget */  \
    COUNT(culledOcclusion, "culled_occlusion")       /* dropped: nearer layers cover their block */    \
    LIST(culledOcclusionByLayer, "culled_occlusion_by_layer") /* culled while that layer was current */ \
    COUNT(culledHidden, "culled_hidden") /* dropped: behind the farthest hit of every cell it reaches */     \
    LIST(cellsCoveredByLayer, "cells_covered_by_layer") /* pixel-frame cells covered when it ended */  \
    COUNT(occlusionTables, "occlusion_tables")       /* summed-volume (or -area) tables built */       \
    SHOWN("procedurals", s.procedurals)                                                                \
    COUNT(proceduralsExpanded, "procedurals_expanded")                                                 \
    SHOWN("procedurals_by_depth", s.proceduralsByDepth)                                                \
    LIST(proceduralsExpandedByDepth, "procedurals_expanded_by_depth") /* [0] declared, [1] children */  \
    COUNT(proceduralsReleased, "procedurals_released") /* expansions freed once no bucket left reached them */ \
    COUNT(proceduralsMadeAgain, "procedurals_made_again") /* released, then asked for again: made again */ \
    SHOWN("procedurals_never_expanded", s.procedurals - c.proceduralsExpanded)                         \
    SHOWN("bodies_generated", s.bodiesGenerated)                                                       \
    SHOWN("passes", s.passes)                                                                          \
    SHOWN("renders", s.renders)        /* spacetime renders run: one per block of each pass */         \
    COUNT(gridsDiced, "grids_diced")                                                                   \
    COUNT(micropolygons, "micropolygons")  /* diced (and shaded) */                                    \
    COUNT(gridsShared, "grids_shared")     /* sampled from a grid another bucket diced (grid_cache.h) */ \
    COUNT(micropolygonsShared, "micropolygons_shared")                                                 \
    COUNT(gridsEvicted, "grids_evicted")   /* shared grids dropped for room before every bucket took them */ \
    COUNT(pointsShadedBuiltin, "shading.points_builtin") /* vertices the built-in shading shaded */   \
    COUNT(pointsShadedSurface, "shading.points_surface") /* vertices Shading Language surfaces ran on */ \
    COUNT(lightShaderRuns, "shading.light_shader_runs")  /* light shader runs over a grid */          \
    COUNT(shadingBatchRuns, "shading.batch_runs") /* surface runs over several small grids at once */ \
    COUNT(shadingBatchedGrids, "shading.batched_grids") /* grid slots shaded in those runs */         \
    COUNT(shadingSanitised, "shading.sanitised")  /* NaN, infinity or out-of-domain results set to 0 */ \
    COUNT(shadingIndicesClamped, "shading.indices_clamped") /* array accesses out of range (a grid and place each) */ \
    COUNT(shadingLoopsStopped, "shading.loops_stopped") /* shader runs past the loop budget */        \
    COUNT(sampleTests, "sample_tests")                                                                 \
    COUNT(sampleHits, "sample_hits")                                                                   \
    COUNT(samplesBehind, "samples_behind") /* not tested: the micropolygon lay behind their hit */    \
    COUNT(gridGroupsBehind, "grid_groups_behind") /* a moving grid's slices skipped: all of it behind */ \
    COUNT(patchGroupsBehind, "patch_groups_behind") /* the same for a patch of 4 x 4 of its quads */ \
    COUNT(patchGroupsOutside, "patch_groups_outside") /* a patch of 4 x 4 quads outside the bucket over a group */ \
    COUNT(sampleFragments, "sample_fragments") /* see-through hits kept to composite (Oi < 1) */   \
    SHOWN("hit_efficiency", c.sampleTests ? double(c.sampleHits) / double(c.sampleTests) : 0.0)        \
    /* Ray tracing (--algorithm raytrace*, and shadow rays): the paper's Tables 1 and 2. */           \
    COUNT(traceBodies, "trace.bodies")     /* bodies the ray tracer holds (trilinear segments) */      \
    COUNT(boundingVolumes, "trace.bounding_volumes") /* nodes built (summed over frames: -frames) */   \
    COUNT(eyeRays, "trace.eye_rays")                                                                   \
    COUNT(shadowRays, "trace.shadow_rays") /* per sample (or eye-ray hit) */                          \
    COUNT(shadowVertexRays, "trace.shadow_vertex_rays") /* per vertex of still grids, at still occluders */ \
    COUNT(shadowFoldedGrids, "trace.shadow_folded_grids") /* still grids whose shadows are in their colour */ \
    COUNT(shaderRays, "trace.shader_rays") /* rays occlusion(), trace() ... cast (and their hits' shadow rays) */ \
    COUNT(rayBodyTests, "trace.ray_body_tests")      /* ray/body tests (each body once per ray) */     \
    COUNT(rayBoxTests, "trace.ray_box_tests")        /* ray/bounding-volume tests */                   \
    SECONDS(timeSampleGen, "cpu_by_stage.sample_generation")                                           \
    SECONDS(timeSplit, "cpu_by_stage.split_cull")                                                      \
    SECONDS(timeDice, "cpu_by_stage.dice")                                                             \
    SECONDS(timeShade, "cpu_by_stage.shade")                                                           \
    SECONDS(timeSample, "cpu_by_stage.sample")                                                         \
    SECONDS(timeOcclusion, "cpu_by_stage.occlusion_tables") /* building coverage and tables */        \
    SECONDS(timeResolve, "cpu_by_stage.resolve")                                                       \
    SECONDS(timeHierarchy, "cpu_by_stage.hierarchy_build")  /* building the ray tracer's hierarchies */ \
    SECONDS(timeTrace, "cpu_by_stage.trace")                /* tracing and shading rays */

struct RenderCounters {
#define STREYES_DECLARE_COUNT(member, key) uint64_t member = 0;
#define STREYES_DECLARE_LIST(member, key) std::vector<uint64_t> member;
#define STREYES_DECLARE_SECONDS(member, key) double member = 0;
#define STREYES_DECLARE_NOTHING(key, expression)
    STREYES_RENDER_COUNTERS(STREYES_DECLARE_COUNT, STREYES_DECLARE_LIST, STREYES_DECLARE_SECONDS,
                            STREYES_DECLARE_NOTHING)
#undef STREYES_DECLARE_COUNT
#undef STREYES_DECLARE_LIST
#undef STREYES_DECLARE_SECONDS
#undef STREYES_DECLARE_NOTHING

    RenderCounters& operator+=(const RenderCounters& o);
    uint64_t splits() const { return splitsU + splitsV + splitsT; }
};

struct RenderStats {
    RenderCounters counters;
    std::string algorithm;
    int firstFrame = 0, lastFrame = 0, width = 0, height = 0, samplesPerPixel = 0, threads = 0;
    int frameBlock = 0, bucketSize = 0;
    std::string simd;  // the instruction set the sample kernels ran ("AVX3" is AVX-512; --simd caps it)
    double tolerance = 0;
    int layers = 0;  // 0: adaptive
    std::vector<float> layerDepths;  // --layers N: the camera depths between its layers
    double timeParse = 0, timeBuild = 0, timeRender = 0, timeWrite = 0, timeTotal = 0;  // wall seconds
    uint64_t peakMemoryBytes = 0;  // peak resident set of the process
    uint64_t memoryEstimateBytes = 0, memoryBudgetBytes = 0;  // memory.h, before rendering
    uint64_t memoryProgramBytes = 0;  // the part of the estimate that is the executable and its libraries
    uint64_t memoryBodiesBytes = 0;   // what the bodies made hold (the scene's, and every expansion's)
    int framesSkipped = 0;         // already complete (--resume)
    // EXR files' chunks of 16 scanlines: compressed, or stored as the last file of the same
    // channels stored them (exr_file.h: an animation's unchanged chunks, the same bytes)
    uint64_t exrChunksCompressed = 0, exrChunksReused = 0;
    uint64_t procedurals = 0;      // procedurals made (declared, and produced by expansions)
    std::vector<uint64_t> proceduralsByDepth;
    uint64_t bodiesGenerated = 0;  // bodies made, from the scene and by expansions
    int passes = 1;                // > 1 when procedurals outgrew their bounds
    int renders = 1;               // spacetime renders: a file's passes' blocks, summed (a zoom is one pass)

    std::string toJson() const;
};

uint64_t peakResidentBytes();

}  // namespace streyes
