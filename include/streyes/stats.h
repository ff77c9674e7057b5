// Render statistics: the counters every speed figure is quoted with, and the time per stage.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace streyes {

struct RenderCounters {
    uint64_t rootBodies = 0;       // bodies made from the scene (one per motion segment)
    uint64_t splitsU = 0, splitsV = 0, splitsT = 0;
    uint64_t eyeSplits = 0;        // splits of bodies reaching the eye plane
    uint64_t culledView = 0;       // bodies outside the bucket's spacetime block (incl. frustum)
    uint64_t culledClip = 0;       // bodies wholly nearer than the near plane or beyond the far plane
    uint64_t culledEyeLimit = 0;   // dropped at the eye-split limit
    uint64_t culledSplitLimit = 0; // dropped at the split-depth limit
    uint64_t culledOcclusion = 0;  // dropped because nearer layers cover their block
    std::vector<uint64_t> culledOcclusionByLayer;  // [layer]: bodies culled while that layer was current
    std::vector<uint64_t> cellsCoveredByLayer;     // [layer]: pixel-frame cells newly covered when it ended
    uint64_t occlusionTables = 0;  // summed-volume (or -area) tables built
    uint64_t proceduralsExpanded = 0;
    std::vector<uint64_t> proceduralsExpandedByDepth;  // [0]: declared in the scene, [1]: their children ...
    uint64_t gridsDiced = 0;
    uint64_t micropolygons = 0;
    uint64_t sampleTests = 0;
    uint64_t sampleHits = 0;
    uint64_t buckets = 0;
    // Ray tracing (--algorithm raytrace*, and shadow rays): the paper's Tables 1 and 2.
    uint64_t traceBodies = 0;      // bodies the ray tracer holds (trilinear segments)
    uint64_t boundingVolumes = 0;  // hierarchy nodes built (summed over frames for raytrace-frames)
    uint64_t eyeRays = 0, shadowRays = 0;
    uint64_t rayBodyTests = 0;     // ray/body intersection tests (each body once per ray)
    uint64_t rayBoxTests = 0;      // ray/bounding-volume tests

    // Seconds, summed over threads (so they add up to CPU time, not wall time).
    double timeSampleGen = 0, timeSplit = 0, timeDice = 0, timeShade = 0, timeSample = 0, timeResolve = 0;
    double timeOcclusion = 0;  // building coverage and tables
    double timeHierarchy = 0, timeTrace = 0;  // building hierarchies; tracing and shading rays

    RenderCounters& operator+=(const RenderCounters& o);
    uint64_t splits() const { return splitsU + splitsV + splitsT; }
};

struct RenderStats {
    RenderCounters counters;
    std::string algorithm;
    int firstFrame = 0, lastFrame = 0, width = 0, height = 0, samplesPerPixel = 0, threads = 0;
    int frameBlock = 0, bucketSize = 0;
    double tolerance = 0;
    int layers = 0;  // 0: adaptive
    double timeParse = 0, timeBuild = 0, timeRender = 0, timeWrite = 0, timeTotal = 0;  // wall seconds
    uint64_t peakMemoryBytes = 0;  // peak resident set of the process
    uint64_t memoryEstimateBytes = 0, memoryBudgetBytes = 0;  // memory.h, before rendering
    uint64_t memoryProgramBytes = 0;  // the part of the estimate that is the executable and its libraries
    int framesSkipped = 0;         // already complete (--resume)
    uint64_t procedurals = 0;      // procedurals made (declared, and produced by expansions)
    std::vector<uint64_t> proceduralsByDepth;
    uint64_t bodiesGenerated = 0;  // bodies made, from the scene and by expansions
    int passes = 1;                // > 1 when procedurals outgrew their bounds

    std::string toJson() const;
};

uint64_t peakResidentBytes();

}  // namespace streyes
