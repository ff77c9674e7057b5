// The work the frame-sequence fuzzer does with one input (sequence_fuzz.cpp), shared with the
// regression test that replays what it once found (tests/core/fuzz_regression_test.cpp).
//
// The input is split at form feeds ('\f') into frame files, shot.0001.rib ... (at most 16), read as
// the pattern shot.####.rib; an input without one is one file, read for its FrameBegin blocks.
// readPasses (streyes/passes.h) reads them, at most three frames a job, matching each frame's
// primitives with the previous frame's, and each render job is rendered at 4 x 4 pixels with one
// sample. Frames that cannot be read together must end in an InputError; anything else (another
// exception, a crash, a sanitizer report, a hang) is a bug.
#pragma once

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

#include "fuzz_rib.h"
#include "streyes/passes.h"
#include "streyes/sequence.h"

namespace streyes::fuzz {

constexpr int kMaxFuzzFrames = 16;

// A folder of the process's own for the frame files: in memory (/dev/shm) where there is one;
// removed when the process ends.
struct FuzzFolder {
    std::string path;
    FuzzFolder() {
        std::error_code ec;
        const std::string base = std::filesystem::is_directory("/dev/shm", ec) && access("/dev/shm", W_OK) == 0
                                     ? "/dev/shm"
                                     : std::filesystem::temp_directory_path().string();
        std::string tmpl = base + "/streyes-fuzz-sequence-XXXXXX";
        if (!mkdtemp(tmpl.data())) throw std::runtime_error("mkdtemp failed for " + tmpl);
        path = tmpl;
    }
    ~FuzzFolder() {
        std::error_code ec;
        std::filesystem::remove_all(path, ec);
    }
};
inline const std::string& fuzzFolder() {
    static const FuzzFolder folder;
    return folder.path;
}

inline Outcome readFuzzedSequence(std::string_view text) {
    const RestrictedAccess restricted;  // fuzz_rib.h
    const std::string& dir = fuzzFolder();
    // The frames: pieces between form feeds, written as the pattern's files (those of a longer
    // input before removed), or the whole input as one file of FrameBegin blocks.
    std::vector<std::string_view> pieces;
    for (size_t at = 0; pieces.size() < size_t(kMaxFuzzFrames);) {
        const size_t ff = text.find('\f', at);
        pieces.push_back(text.substr(at, ff == std::string_view::npos ? std::string_view::npos : ff - at));
        if (ff == std::string_view::npos) break;
        at = ff + 1;
    }
    std::string path;
    for (int f = 1; f <= kMaxFuzzFrames; ++f) std::remove(frameFileName(dir + "/shot.####.rib", f).c_str());
    if (pieces.size() == 1) {
        path = dir + "/shot.rib";
        std::ofstream(path, std::ios::binary) << text;
    } else {
        path = dir + "/shot.####.rib";
        for (size_t i = 0; i < pieces.size(); ++i)
            std::ofstream(frameFileName(path, int(i) + 1), std::ios::binary) << pieces[i];
    }
    Log log;
    log.setQuiet(true);
    try {
        PassRequest passes;
        passes.blockFrames = 3;
        // Render jobs only: the maps and textures other jobs would make are not this fuzzer's.
        readPasses(path, passes, log, [&](PassJob&& job) {
            if (job.kind != PassJob::Kind::Render) return;
            const Sequence& seq = job.sequence;
            RenderOptions o = tinyRenderOptions(4);
            o.hasFrames = true;
            const Scene& scene = seq.scene;
            o.firstFrame = scene.settings.hasFrames ? scene.settings.firstFrame : 0;
            o.lastFrame = scene.settings.hasFrames ? scene.settings.lastFrame : o.firstFrame;
            Renderer renderer(scene, o, log);
            renderer.render([](const FrameImage&) {});
        });
        return Outcome::Rendered;
    } catch (const InputError&) {
        return Outcome::BadInput;
    }
}

}  // namespace streyes::fuzz
