// libFuzzer target for the Shading Language compiler (source text in): see fuzz_sl.h.
// Built with clang by the STREYES_FUZZ option, and in the sanitized tree; run by tools/fuzz.sh --target sl.
#include <cstddef>
#include <cstdint>

#include "fuzz_sl.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    streyes::fuzz::compileFuzzedShader({reinterpret_cast<const char*>(data), size});
    return 0;
}
