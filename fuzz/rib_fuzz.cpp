// libFuzzer target for the RIB parser (and what a parsed scene goes through): see fuzz_rib.h.
// Built with clang by the STREYES_FUZZ option; run by tools/fuzz.sh (briefly in the test suite).
#include <cstddef>
#include <cstdint>

#include "fuzz_rib.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    streyes::fuzz::parseAndRender({reinterpret_cast<const char*>(data), size});
    return 0;
}
