// Helpers shared by the tests: source paths, temporary folders, and rendering a RIB string
// in memory (no files, no OpenImageIO).
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "film/film.h"
#include "pixel_camera.h"  // test::pixelCamera
#include "streyes/renderer.h"
#include "streyes/scene.h"
#include "streyes/stats.h"

namespace streyes::test {

// Built with the address sanitizer (GCC defines __SANITIZE_ADDRESS__; clang has the feature). It
// pads every allocation and keeps freed memory in quarantine, and runs some renders 40x slower.
#if defined(__SANITIZE_ADDRESS__)
inline constexpr bool kAddressSanitizer = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
inline constexpr bool kAddressSanitizer = true;
#else
inline constexpr bool kAddressSanitizer = false;
#endif
#else
inline constexpr bool kAddressSanitizer = false;
#endif

// The scenes whose whole-scene tests (the epsilon = 0 identity, frame-block invariance, the ray
// tracer's checksum) take one to four minutes each under the sanitizers: procedural forests that
// the ray tracer expands whole, blobs, and hundreds of trees or atoms whose shadows build a
// ray-tracing hierarchy, the four Weber-Penn trees (200 s of the sanitized suite's 1250) and the
// Weber-Penn forest with sun shadows, ray-traced or from depth maps (2048 x 1076 depth frames,
// rendered at their own Format whatever the picture's size). There they run only their checksum
// with the default algorithm, which renders them through the same code; the release suite runs
// every test on every scene. It keeps CI under its half hour (docs/ARCHITECTURE.md, "Hard cases,
// fuzzing and sanitizers").
inline bool slowUnderSanitizers(const std::string& sceneFile) {
    const size_t slash = sceneFile.find_last_of('/');
    const std::string name = sceneFile.substr(slash == std::string::npos ? 0 : slash + 1);
    for (const char* slow : {"atom.rib", "blobby.rib", "forest.rib", "forest-flyover.rib", "forest-small.rib",
                             "forest-wp.rib", "forest-wp-maps.rib", "grove.rib", "meadow-sky.rib", "split_budget.rib",
                             "trees-presets.rib"})
        if (name == slow) return kAddressSanitizer;
    return false;
}

// Under the sanitizers, a test whose point holds at any resolution (renders that must agree bit for
// bit: whatever the threads, the block, the cache) renders its scene of width x height at half of
// each, a quarter of the pixels; the release suite renders the scene's own. It keeps the sanitized
// suite's heaviest invariance tests near a quarter of their time.
inline void halfResolutionUnderSanitizers(RenderOptions& o, int width, int height) {
    if (kAddressSanitizer) {
        o.xres = width / 2;
        o.yres = height / 2;
    }
}

// The ray tracer expands every procedural up front: the 100,000 trees of these scenes take
// minutes, so the scene tests render them with the rasterizer only.
inline bool tooLargeToRayTrace(const std::string& sceneFile) {
    return sceneFile == "scenes/forest.rib" || sceneFile == "scenes/forest-flyover.rib";
}

// Absolute path of a file in the source tree, e.g. sourcePath("scenes/ramp.rib").
std::string sourcePath(const std::string& relative);

// A scene file holding several worlds (FrameBegin blocks: depth frames rendered from a light,
// MakeShadow, pictures reading the maps): the command renders it as passes (streyes/passes.h), and
// the scene-wide tests of tests/core, which read a file as one world, leave it to
// tests/cli/multipass_scenes_test.cpp, which renders it as the command does.
bool multiPassScene(const std::string& path);
// The scene files of scenes/ and scenes/hard ("scenes/ramp.rib"), sorted: the multi-pass ones
// (multiPassScene) or all the others.
std::vector<std::string> sceneFiles(bool multiPass);

// A fresh, empty temporary folder for one test, /tmp/streyes-TAG-XXXXXX, removed with all it holds
// when the TempDir goes (at the end of the test that holds it), so that test runs leave nothing
// in /tmp. Movable, not copyable.
class TempDir {
  public:
    explicit TempDir(const std::string& tag);
    ~TempDir();
    TempDir(TempDir&& other) noexcept : path_(std::move(other.path_)) { other.path_.clear(); }
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;
    TempDir& operator=(TempDir&&) = delete;
    const std::string& path() const { return path_; }

  private:
    std::string path_;
};

struct RenderResult {
    std::vector<FrameImage> frames;
    RenderStats stats;
    std::vector<std::string> warnings;
    const FrameImage& frame(int f) const;  // by frame number
    float alpha(int f, int x, int y) const { return frame(f).rgba[(size_t(y) * size_t(frame(f).width) + size_t(x)) * 4 + 3]; }
    float channel(int f, int x, int y, int c) const {
        return frame(f).rgba[(size_t(y) * size_t(frame(f).width) + size_t(x)) * 4 + size_t(c)];
    }
    float z(int f, int x, int y) const { return frame(f).z[size_t(y) * size_t(frame(f).width) + size_t(x)]; }
};

// Default render options but for the algorithm.
inline RenderOptions optionsFor(Algorithm a) {
    RenderOptions o;
    o.algorithm = a;
    return o;
}

RenderResult renderRib(const std::string& rib, const RenderOptions& options = {});
// With `strict` (streyes render --strict): what the peers warn about is an InputError.
RenderResult renderRib(const std::string& rib, const RenderOptions& options, bool strict);
// Frames [first, last] of a RIB rendered together, and frame `frame` rendered alone (`options`
// otherwise): for tests of what a frame's render depends on.
struct ShotAndFrame {
    RenderResult shot, alone;
    bool samePixels(int frame) const;  // the shot's frame and the lone render, bit for bit
};
ShotAndFrame renderShotAndFrame(const std::string& rib, RenderOptions options, int first, int last, int frame);
// The InputError a RIB string read as "bad.rib" makes, or "" when it reads.
// Under `strict` (streyes render --strict), what the peers warn about is an InputError too.
std::string ribError(const std::string& rib, bool strict = false);
RenderResult renderScene(const Scene& scene, const RenderOptions& options = {});
RenderResult renderFile(const std::string& path, const RenderOptions& options = {});

// The pixel checksums of tests/data/scene_checksums.txt (tests/core/scene_checksum_test.cpp):
// FNV-1a over the bits of every RGBA and Z value of every frame, in frame order; the recorded
// checksums by key ("scenes/ramp.rib:spacetime-occlusion"); and recording one (several test
// processes may record at once: each rewrites the file with what it read plus its own entry).
uint64_t pixelChecksum(const RenderResult& r);
std::map<std::string, std::string> recordedChecksums();
void recordChecksum(const std::string& key, const std::string& value);
extern const char* const kChecksumFile;
// `checksum` against the one recorded for `key`: "" when they agree, else what is wrong (none
// recorded, or the pixels changed); with STREYES_RECORD_CHECKSUMS set it records it and gives "".
std::string checkRecordedChecksum(const std::string& key, uint64_t checksum);

// The sum of frame `frame`'s alpha over its pixels: the covered area in pixels.
double alphaSum(const RenderResult& r, int frame = 0);

// True when every pixel of every frame is bit-identical (RGBA and Z): a NaN equals a NaN of the
// same bits, +0 differs from -0.
bool identicalPixels(const RenderResult& a, const RenderResult& b);
// |x - y| for comparing two renders within a tolerance: 0 when x == y (+0 and -0, equal
// infinities), +inf when either is NaN (NaN in both included: a render that makes NaN is broken,
// and std::max or a sum would otherwise drop it) or only one is infinite.
float absDifference(float x, float y);
// Largest and mean absDifference of RGBA over all frames and pixels (+inf when a NaN is met).
float maxAbsDifference(const RenderResult& a, const RenderResult& b);
float meanAbsDifference(const RenderResult& a, const RenderResult& b);
// Pixels of two images of one size where some RGBA channel differs by more than `threshold`
// (by absDifference: a NaN counts).
size_t differingPixels(const FrameImage& a, const FrameImage& b, float threshold);

// The JSON keys of the counts (not the seconds) that differ between two renders' counters:
// empty when every count agrees. Walks STREYES_RENDER_COUNTERS, so it covers every counter.
std::vector<std::string> differingCounts(const RenderCounters& a, const RenderCounters& b);

// An orthographic camera where one scene unit is one pixel (raster x = x, raster y = h - y), a
// box filter one pixel wide, then `extra` options, WorldBegin and Surface "constant".
std::string orthoHeader(int w, int h, const std::string& extra = "");
// Patch "bilinear" of the axis-aligned square [x0, x1] x [y0, y1] at depth z.
std::string square(double x0, double x1, double y0, double y1, double z);
// A 2 x 2-face Catmull-Clark sheet keyed at t = 0, 1, ..., lastKey: MotionBegin ... MotionEnd, its
// 3 x 3 control points at key k (x, y, z for point i + 3 j) from vertex(k, i, j).
std::string keyedSheet(int lastKey, const std::function<std::array<double, 3>(int k, int i, int j)>& vertex);
// Fraction of pixel [p, p+1] covered by [a, b].
double overlap(double p, double a, double b);
// The algorithm's name as a test name ("raytrace_frames").
std::string testName(Algorithm a);

// Every sample of a render as the buckets left it before the pixel filter, in image order:
// ((frame - first) * height + y) * width + x, then stratum.
struct SampleRecord {
    int width = 0, height = 0, frames = 0, samplesPerPixel = 0;
    std::vector<SamplePosition> positions;
    std::vector<SampleHit> hits;
};
SampleRecord renderSamples(const std::string& rib, RenderOptions options = {});

// Sample by sample: how many samples two renders of the same samples agree on.
struct SampleAgreement {
    size_t samples = 0;
    size_t hitOrMiss = 0;   // both hit or both missed
    size_t sameSurface = 0; // that, and where both hit, the same surface (colour and depth agree)
    double share() const { return samples ? double(sameSurface) / double(samples) : 0; }
};
// Same surface: the same primitive, colours within colorTolerance (max over channels) and depths
// within a relative depthTolerance (by absDifference: a NaN agrees with nothing, nor does a NaN
// alpha). Throws when the two do not hold the same sample positions.
SampleAgreement compareSamples(const SampleRecord& a, const SampleRecord& b, float colorTolerance = 1e-3f,
                               float depthTolerance = 1e-3f);

}  // namespace streyes::test
