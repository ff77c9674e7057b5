#include "test_util.h"

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <mutex>
#include <sstream>
#include <stdexcept>

#include "streyes/rib.h"

namespace streyes::test {

std::string sourcePath(const std::string& relative) { return std::string(STREYES_SOURCE_DIR) + "/" + relative; }

bool multiPassScene(const std::string& path) {
    std::ifstream in(path);
    std::string line;
    int worlds = 0;
    while (std::getline(in, line)) {
        const size_t at = line.find_first_not_of(" \t");
        if (at != std::string::npos && line.compare(at, 10, "WorldBegin") == 0 &&
            (line.size() == at + 10 || std::isspace(static_cast<unsigned char>(line[at + 10]))) && ++worlds > 1)
            return true;
    }
    return false;
}

const char* const kChecksumFile = "tests/data/scene_checksums.txt";

uint64_t pixelChecksum(const RenderResult& r) {
    uint64_t h = 1469598103934665603ull;
    auto add = [&](const std::vector<float>& v) {
        for (float f : v) {
            uint32_t bits;
            std::memcpy(&bits, &f, sizeof bits);
            for (int i = 0; i < 4; ++i) {
                h ^= (bits >> (8 * i)) & 0xffu;
                h *= 1099511628211ull;
            }
        }
    };
    std::vector<const FrameImage*> frames;
    for (const FrameImage& f : r.frames) frames.push_back(&f);
    std::sort(frames.begin(), frames.end(), [](const FrameImage* a, const FrameImage* b) { return a->frame < b->frame; });
    for (const FrameImage* f : frames) {
        add(f->rgba);
        add(f->z);
    }
    return h;
}

std::map<std::string, std::string> recordedChecksums() {
    std::map<std::string, std::string> m;
    std::ifstream in(sourcePath(kChecksumFile));
    std::string line;
    while (std::getline(in, line)) {
        if (line.empty() || line[0] == '#') continue;
        std::istringstream s(line);
        std::string key, value;
        if (s >> key >> value) m[key] = value;
    }
    return m;
}

void recordChecksum(const std::string& key, const std::string& value) {
    static std::mutex mutex;
    std::lock_guard<std::mutex> lock(mutex);
    std::map<std::string, std::string> m = recordedChecksums();
    m[key] = value;
    std::ofstream out(sourcePath(kChecksumFile));
    out << "# Pixel checksums of every scene, rendered small and short by tests/core/scene_checksum_test.cpp.\n"
           "# Record again (STREYES_RECORD_CHECKSUMS=1) only when a change alters pixels on purpose.\n";
    for (const auto& [k, v] : m) out << k << " " << v << "\n";
}

std::string checkRecordedChecksum(const std::string& key, uint64_t checksum) {
    char hex[17];
    std::snprintf(hex, sizeof hex, "%016llx", (unsigned long long)checksum);
    if (std::getenv("STREYES_RECORD_CHECKSUMS")) {
        recordChecksum(key, hex);
        return "";
    }
    const std::map<std::string, std::string> recorded = recordedChecksums();
    auto it = recorded.find(key);
    if (it == recorded.end()) return key + " has no recorded checksum in " + kChecksumFile;
    return it->second == hex ? "" : key + ": the pixels changed (recorded " + it->second + ", now " + hex + ")";
}

std::vector<std::string> sceneFiles(bool multiPass) {
    std::vector<std::string> files;
    for (const char* dir : {"scenes", "scenes/hard"})
        for (const auto& entry : std::filesystem::directory_iterator(sourcePath(dir)))
            if (entry.path().extension() == ".rib" && multiPassScene(entry.path().string()) == multiPass)
                files.push_back(std::string(dir) + "/" + entry.path().filename().string());
    std::sort(files.begin(), files.end());
    return files;
}

std::string ribError(const std::string& rib, bool strict) {
    Log log;
    log.setQuiet(true);
    log.setStrict(strict);
    try {
        parseRibString(rib, "bad.rib", log);
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

TempDir::TempDir(const std::string& tag) {
    std::string tmpl = (std::filesystem::temp_directory_path() / ("streyes-" + tag + "-XXXXXX")).string();
    if (!mkdtemp(tmpl.data())) throw std::runtime_error("mkdtemp failed for " + tmpl);
    path_ = tmpl;
}

TempDir::~TempDir() {
    if (path_.empty()) return;
    namespace fs = std::filesystem;
    // Tests take permissions away (read-only folders, unreadable files): given back first, so that
    // the folder can be emptied without root. Errors are ignored; a destructor does not throw.
    std::error_code ec, ignore;
    const fs::perms all = fs::perms::owner_all;
    fs::permissions(path_, all, fs::perm_options::add, ignore);
    for (fs::recursive_directory_iterator it(path_, ec), end; !ec && it != end; it.increment(ec))
        if (!it->is_symlink(ignore) && it->is_directory(ignore))
            fs::permissions(it->path(), all, fs::perm_options::add, ignore);
    fs::remove_all(path_, ignore);
}

const FrameImage& RenderResult::frame(int f) const {
    for (const FrameImage& img : frames)
        if (img.frame == f) return img;
    throw std::runtime_error("frame " + std::to_string(f) + " was not rendered");
}

static RenderResult renderWithLog(const Scene& scene, const RenderOptions& options, Log& log) {
    RenderResult r;
    Renderer renderer(scene, options, log);
    // A frame may come again (a second pass for procedurals that outgrew their bounds).
    r.stats = renderer.render([&](const FrameImage& img) {
        for (FrameImage& f : r.frames)
            if (f.frame == img.frame) {
                f = img;
                return;
            }
        r.frames.push_back(img);
    });
    r.warnings = log.warnings();
    return r;
}

RenderResult renderRib(const std::string& rib, const RenderOptions& options) { return renderRib(rib, options, false); }

RenderResult renderRib(const std::string& rib, const RenderOptions& options, bool strict) {
    Log log;
    log.setStrict(strict);
    Scene scene = parseRibString(rib, "test.rib", log);
    return renderWithLog(scene, options, log);
}

ShotAndFrame renderShotAndFrame(const std::string& rib, RenderOptions options, int first, int last, int frame) {
    ShotAndFrame r;
    options.hasFrames = true;
    options.firstFrame = first;
    options.lastFrame = last;
    r.shot = renderRib(rib, options);
    options.firstFrame = options.lastFrame = frame;
    r.alone = renderRib(rib, options);
    return r;
}

bool ShotAndFrame::samePixels(int frame) const {
    RenderResult one;
    one.frames = {shot.frame(frame)};
    return identicalPixels(one, alone);
}

RenderResult renderScene(const Scene& scene, const RenderOptions& options) {
    Log log;
    return renderWithLog(scene, options, log);
}

RenderResult renderFile(const std::string& path, const RenderOptions& options) {
    Log log;
    Scene scene = parseRibFile(path, log);
    return renderWithLog(scene, options, log);
}

// memcmp, not ==: bit identity (NaN payloads, the sign of zero), and sizes first.
static bool sameBits(const std::vector<float>& x, const std::vector<float>& y) {
    return x.size() == y.size() && std::memcmp(x.data(), y.data(), x.size() * sizeof(float)) == 0;
}

bool identicalPixels(const RenderResult& a, const RenderResult& b) {
    if (a.frames.size() != b.frames.size()) return false;
    for (size_t i = 0; i < a.frames.size(); ++i) {
        const FrameImage &x = a.frames[i], &y = b.frames[i];
        if (x.frame != y.frame || x.width != y.width || x.height != y.height) return false;
        if (!sameBits(x.rgba, y.rgba) || !sameBits(x.z, y.z)) return false;
    }
    return true;
}

float absDifference(float x, float y) {
    if (x == y) return 0;
    const float d = std::fabs(x - y);  // NaN when either is NaN, +inf for infinities that differ
    return std::isnan(d) ? std::numeric_limits<float>::infinity() : d;
}

static void forEachPair(const RenderResult& a, const RenderResult& b, const std::function<void(float, float)>& fn) {
    if (a.frames.size() != b.frames.size()) throw std::runtime_error("frame counts differ");
    for (size_t i = 0; i < a.frames.size(); ++i) {
        if (a.frames[i].rgba.size() != b.frames[i].rgba.size()) throw std::runtime_error("sizes differ");
        for (size_t k = 0; k < a.frames[i].rgba.size(); ++k) fn(a.frames[i].rgba[k], b.frames[i].rgba[k]);
    }
}

float maxAbsDifference(const RenderResult& a, const RenderResult& b) {
    float m = 0;
    forEachPair(a, b, [&](float x, float y) { m = std::max(m, absDifference(x, y)); });
    return m;
}

float meanAbsDifference(const RenderResult& a, const RenderResult& b) {
    double s = 0;
    size_t n = 0;
    forEachPair(a, b, [&](float x, float y) {
        s += double(absDifference(x, y));
        ++n;
    });
    return n ? float(s / double(n)) : 0.0f;
}

size_t differingPixels(const FrameImage& a, const FrameImage& b, float threshold) {
    if (a.rgba.size() != b.rgba.size()) throw std::runtime_error("sizes differ");
    size_t n = 0;
    for (size_t i = 0; i < a.rgba.size(); i += 4) {
        bool differs = false;
        for (size_t c = 0; c < 4; ++c) differs = differs || absDifference(a.rgba[i + c], b.rgba[i + c]) > threshold;
        n += differs;
    }
    return n;
}

std::vector<std::string> differingCounts(const RenderCounters& a, const RenderCounters& b) {
    std::vector<std::string> keys;
#define STREYES_COMPARE(member, key) \
    if (a.member != b.member) keys.push_back(key);
#define STREYES_SKIP(member, key)
    STREYES_RENDER_COUNTERS(STREYES_COMPARE, STREYES_COMPARE, STREYES_SKIP, STREYES_SKIP)
#undef STREYES_COMPARE
#undef STREYES_SKIP
    return keys;
}

}  // namespace streyes::test

namespace streyes::test {

double alphaSum(const RenderResult& r, int frame) {
    const FrameImage& f = r.frame(frame);
    double sum = 0;
    for (size_t i = 3; i < f.rgba.size(); i += 4) sum += f.rgba[i];
    return sum;
}

std::string orthoHeader(int w, int h, const std::string& extra) {
    return "Format " + std::to_string(w) + " " + std::to_string(h) + " 1\n" +
           "Projection \"orthographic\"\nScreenWindow 0 " + std::to_string(w) + " 0 " + std::to_string(h) + "\n" +
           "PixelFilter \"box\" 1 1\n" + extra + "WorldBegin\nSurface \"constant\"\n";
}

std::string keyedSheet(int lastKey, const std::function<std::array<double, 3>(int k, int i, int j)>& vertex) {
    std::string times, keys;
    for (int k = 0; k <= lastKey; ++k) {
        times += std::to_string(k) + (k < lastKey ? " " : "");
        std::string P;
        for (int j = 0; j < 3; ++j)
            for (int i = 0; i < 3; ++i)
                for (double c : vertex(k, i, j)) P += std::to_string(c) + " ";
        keys += "SubdivisionMesh \"catmull-clark\" [4 4 4 4] [0 1 4 3 1 2 5 4 3 4 7 6 4 5 8 7] "
                "[\"interpolateboundary\"] [0 0] [] [] \"P\" [" + P + "]\n";
    }
    return "MotionBegin [" + times + "]\n" + keys + "MotionEnd\n";
}

std::string square(double x0, double x1, double y0, double y1, double z) {
    auto n = [](double v) { return std::to_string(v); };
    return "Patch \"bilinear\" \"P\" [" + n(x0) + " " + n(y0) + " " + n(z) + "  " + n(x1) + " " + n(y0) + " " + n(z) +
           "  " + n(x0) + " " + n(y1) + " " + n(z) + "  " + n(x1) + " " + n(y1) + " " + n(z) + "]\n";
}

double overlap(double p, double a, double b) { return std::max(0.0, std::min(p + 1, b) - std::max(p, a)); }

std::string testName(Algorithm a) {
    std::string n = algorithmName(a);
    std::replace(n.begin(), n.end(), '-', '_');
    return n;
}

SampleRecord renderSamples(const std::string& rib, RenderOptions options) {
    struct Taken {
        int frame, x, y;
        std::vector<SamplePosition> positions;
        std::vector<SampleHit> hits;
    };
    std::vector<Taken> taken;
    std::mutex mutex;
    // Each bucket's own tile (its guard band belongs to its neighbours).
    options.sampleObserver = [&](const ImageBlock& block, const PixelRect& tile) {
        const int S = block.samplesPerPixel();
        std::vector<Taken> mine;
        for (int y = tile.y0; y <= tile.y1; ++y)
            for (int x = tile.x0; x <= tile.x1; ++x)
                for (int fi = 0; fi < block.frameCount(); ++fi) {
                    const size_t i = block.pixelIndex(x, y);
                    Taken t{block.firstFrame() + fi, x, y, {}, {}};
                    const SampleHit* h = block.hits(fi, i);
                    for (int j = 0; j < S; ++j) t.positions.push_back(block.position(fi, i, j));
                    t.hits.assign(h, h + S);
                    mine.push_back(std::move(t));
                }
        std::lock_guard<std::mutex> lock(mutex);
        for (Taken& t : mine) taken.push_back(std::move(t));
    };
    RenderResult r = renderRib(rib, options);
    SampleRecord rec;
    rec.width = r.stats.width;
    rec.height = r.stats.height;
    rec.frames = r.stats.lastFrame - r.stats.firstFrame + 1;
    rec.samplesPerPixel = r.stats.samplesPerPixel;
    const size_t S = size_t(rec.samplesPerPixel);
    const size_t n = size_t(rec.width) * size_t(rec.height) * size_t(rec.frames) * S;
    rec.positions.resize(n);
    rec.hits.resize(n);
    if (taken.size() * S != n) throw std::runtime_error("the buckets did not cover the image exactly once");
    for (const Taken& t : taken) {
        const size_t at = ((size_t(t.frame - r.stats.firstFrame) * size_t(rec.height) + size_t(t.y)) *
                               size_t(rec.width) + size_t(t.x)) * S;
        std::copy(t.positions.begin(), t.positions.end(), rec.positions.begin() + long(at));
        std::copy(t.hits.begin(), t.hits.end(), rec.hits.begin() + long(at));
    }
    return rec;
}

SampleAgreement compareSamples(const SampleRecord& a, const SampleRecord& b, float colorTolerance,
                               float depthTolerance) {
    if (a.positions.size() != b.positions.size())
        throw std::runtime_error("the renders hold different numbers of samples");
    SampleAgreement r;
    r.samples = a.hits.size();
    for (size_t i = 0; i < a.hits.size(); ++i) {
        const SamplePosition &p = a.positions[i], &q = b.positions[i];
        if (p.x != q.x || p.y != q.y || p.tf != q.tf) throw std::runtime_error("the renders used different samples");
        const SampleHit &x = a.hits[i], &y = b.hits[i];
        if (std::isnan(x.z) || std::isnan(y.z)) continue;  // neither a hit nor a miss: agrees with nothing
        const bool hx = !x.empty(), hy = !y.empty();
        if (hx != hy) continue;
        ++r.hitOrMiss;
        if (!hx) {
            ++r.sameSurface;
            continue;
        }
        const float dc =
            std::max({absDifference(x.c.x, y.c.x), absDifference(x.c.y, y.c.y), absDifference(x.c.z, y.c.z)});
        if (x.id == y.id && dc <= colorTolerance &&
            absDifference(x.z, y.z) <= depthTolerance * std::max(std::fabs(x.z), std::fabs(y.z)))
            ++r.sameSurface;
    }
    return r;
}

}  // namespace streyes::test
