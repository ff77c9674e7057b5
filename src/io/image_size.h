// Whether an image's header can be believed before its pixels are read into memory. A corrupt or
// forged header can claim any size (a texture "60000 x 60000" in a 200 KB file), and reading it
// whole (a frame into an ImageData, an untiled texture into OpenImageIO's cache, maketx's input)
// would take that memory, or abort inside OpenImageIO. Header-only: the image module
// (libstreyes_oiio.so) and the EXR reader both use it.
#pragma once

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <string>

namespace streyes {

// No compression an image streyes reads uses packs more than about 2,000 to 1 (zlib's deflate, of
// EXR's ZIP and TIFF's, at most 1,032 to 1; run lengths far less): a header claiming more than this
// many times the file's size in samples, and more than kBelievedImageBytes, is not a real image.
constexpr uint64_t kMaxImageCompression = 16384;
// Claims up to this many bytes of samples are believed whatever the file's size (a truncated file
// then fails as it is read, for what that costs).
constexpr uint64_t kBelievedImageBytes = uint64_t(1) << 30;

// "" when a header's `width` x `height` x `channels` samples of `bytesPerSample` bytes can be what
// a file of `fileBytes` holds; else why not, for a message that names the file.
inline std::string implausibleImageSize(int64_t width, int64_t height, int64_t channels, int64_t bytesPerSample,
                                        uint64_t fileBytes) {
    auto bytesText = [](long double b) {
        char buf[48];
        if (b >= 1024.0L * 1024 * 1024) std::snprintf(buf, sizeof buf, "%.1f GiB", double(b / (1024.0L * 1024 * 1024)));
        else if (b >= 1024.0L * 1024) std::snprintf(buf, sizeof buf, "%.1f MiB", double(b / (1024.0L * 1024)));
        else std::snprintf(buf, sizeof buf, "%.0f bytes", double(b));
        return std::string(buf);
    };
    const std::string size = std::to_string(width) + " x " + std::to_string(height) + " pixels of " +
                             std::to_string(channels) + " channel" + (channels == 1 ? "" : "s");
    if (width <= 0 || height <= 0 || channels <= 0 || bytesPerSample <= 0)
        return "its header says " + size + ": it is corrupt";
    // In long double: a forged header's product overflows 64 bits.
    const long double bytes = (long double)width * (long double)height * (long double)channels * (long double)bytesPerSample;
    const long double limit = std::max((long double)kBelievedImageBytes, (long double)fileBytes * kMaxImageCompression);
    if (bytes <= limit) return "";
    return "its header says " + size + " (" + bytesText(bytes) + " of samples), more than a file of " +
           bytesText((long double)fileBytes) + " can hold: it is corrupt or not what it claims to be";
}

}  // namespace streyes
