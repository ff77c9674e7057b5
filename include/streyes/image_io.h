// Image files in and out, through OpenImageIO. The only part of streyes that links it.
//
// Frames are written to a temporary file in the destination folder and renamed into place, so
// a failed or interrupted write never leaves a partial frame under the final name.
#pragma once

#include <string>
#include <vector>

#include "streyes/frame_image.h"
#include "streyes/quantize.h"

namespace streyes {

// "rgb", "rgba" or "rgbaz", or a comma-separated list of outputs ("rgba,N,P", "z", "motion": see
// docs/SCENE-FORMAT.md). EXR files store R G B A as half, Z and output variables as 32-bit float.
bool validChannelMode(const std::string& mode);

// Replaces the run of '#' in `pattern` with the zero-padded frame number ("a.####.exr", 7 ->
// "a.0007.exr"). A pattern without '#' is returned unchanged.
std::string expandFramePattern(const std::string& pattern, int frame);
bool hasFrameField(const std::string& pattern);
// Inserts ".####" before the extension: "out.exr" -> "out.####.exr".
std::string addFrameField(const std::string& pattern);
// The frames whose files exist for `pattern`, ascending: frame f is listed when the file
// expandFramePattern(pattern, f) exists. The '#' run must be in the file name, not in a folder
// name (InputError otherwise). An unreadable or missing folder gives no frames.
std::vector<int> findFrames(const std::string& pattern);

// Before rendering: can a file be written at `path`? Its folder must exist, be a folder, and take
// a probe file (".STEM.probePID", created and removed at once). Throws RenderError naming `path`,
// the folder and what to do (`option`, "-o" or "--stats", is where the path came from), as
// writeFrame does when it finds the same; nothing is left behind.
void checkWritableFolder(const std::string& path, const std::string& option);

// Writes one frame atomically: encoded in memory, written to temporaryFrameName(path, pid) with
// every write checked and synced, then renamed to `path`. Throws RenderError with a clear message
// on failure (a full disk, a file size limit, an unwritable folder) and leaves nothing behind.
// A file that is not EXR (TIFF, PNG, ...) is quantized as `quantize` says (docs/SCENE-FORMAT.md,
// Quantize): 8- or 16-bit integers, or floats (one = 0, the default here); EXR files always hold
// floats.
// Where a frame's pixels lie in the whole frame. A crop (CropWindow) is written as RenderMan writes
// it: an EXR's data window at (x0, y0) inside a display window of fullWidth x fullHeight (other
// formats hold the crop's pixels alone). fullWidth 0: the pixels are the whole frame.
struct FrameWindow {
    int x0 = 0, y0 = 0, fullWidth = 0, fullHeight = 0;
};

void writeFrame(const std::string& path, const FrameImage& image, const std::string& mode,
                const Quantize& quantize = Quantize{}, const FrameWindow& window = FrameWindow{});

// One file a frame is written to: its name, display mode and quantization, and where its pixels lie.
struct FrameOutput {
    std::string path, mode;
    Quantize quantize;
    FrameWindow window;
};

// Writes `bytes` to `path` as writeFrame writes a frame: to a temporary file beside it, every
// write checked and synced, then renamed. Throws RenderError on failure, leaving nothing behind.
void writeFileAtomically(const std::string& path, const std::vector<unsigned char>& bytes);

// The temporary name process `pid` writes `path` under: ".STEM.tmpPID.EXT" in the same folder.
std::string temporaryFrameName(const std::string& path, int pid);

// Removes the temporary frames that renders which no longer run (killed mid-write) left in the
// folder of the output `pattern` ("out/f.####.exr"), for names that pattern makes. Temporaries
// of running processes are left alone. Returns how many were removed.
int removeStaleTemporaries(const std::string& pattern);

// True when `path` is an image of width x height with exactly the channels of `mode` (R G B,
// then A, then Z) whose every pixel reads back: a frame a render finished writing.
bool isCompleteFrame(const std::string& path, int width, int height, const std::string& mode);

// An image read back: float pixels, interleaved, with its channel names and per-channel formats
// ("half", "float", "uint8", ...).
struct ImageData {
    int width = 0, height = 0;
    std::vector<std::string> channels;
    std::vector<std::string> formats;
    std::vector<float> pixels;  // width * height * channels.size()
    int channelIndex(const std::string& name) const;
    float at(int x, int y, int c) const { return pixels[(size_t(y) * size_t(width) + size_t(x)) * channels.size() + size_t(c)]; }
};
// Throws RenderError when the file cannot be read.
ImageData readImage(const std::string& path);

}  // namespace streyes
