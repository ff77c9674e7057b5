// libFuzzer target for the frame-sequence reader (frame files and FrameBegin blocks merged into a
// spacetime scene, then rendered): see fuzz_sequence.h. Built with clang by the STREYES_FUZZ option,
// and in the sanitized tree; run by tools/fuzz.sh --target sequence.
#include <cstddef>
#include <cstdint>

#include "fuzz_sequence.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    streyes::fuzz::readFuzzedSequence({reinterpret_cast<const char*>(data), size});
    return 0;
}
