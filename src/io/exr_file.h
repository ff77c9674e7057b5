// EXR files through OpenEXR directly: a frame encoded in memory, and any scanline EXR read back.
//
// OpenImageIO made every process load about 260 shared libraries (0.15 s of CPU before the first
// request); frames, the files streyes writes and reads most, need only OpenEXR. Other formats go
// through the image library module (image_library.h), loaded when first needed.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "streyes/frame_image.h"
#include "streyes/image_io.h"

namespace streyes {

struct FrameWindow;  // image_io.h

// A file's chunks of scanlines are compressed on this many threads (1 at the start). The bytes
// are the same whatever the count. The render command sets its thread count: after the last block
// the writer is alone, and one thread encoding 48 frames left the other core idle for a third
// of the demo's wall time.
void setExrEncodeThreads(int threads);

// The frame as an EXR file's bytes: R, G, B (and A) as half floats, Z as float, ZIP compression
// (the format frames have always had; libdeflate makes it, exr_file.cpp). Nothing in them depends
// on the time, the thread count or the machine.
// `window` (may be null): where the pixels lie in the frame (a crop, image_io.h).
std::vector<unsigned char> encodeExr(const FrameImage& image, bool alpha, bool z, const FrameWindow* window = nullptr);

// The chunks of 16 scanlines the encoders have stored since the program started: compressed, or
// reused from the last file of the same size and channels, where that file packed the same bytes
// there (the file is the same, bit for bit, as if compressed again).
struct ExrChunkCounts {
    uint64_t reused = 0, compressed = 0;
};
ExrChunkCounts exrChunkCounts();
// For tests: the next files compress every chunk.
void forgetExrChunks();

// Floats to half-float bits, rounded to nearest even as Imath's half(float) rounds them: eight at
// a time by F16C where the CPU has it (Imath uses F16C only when the whole program is compiled
// for it), else through Imath. Exposed for tests.
void floatsToHalves(const float* in, size_t n, uint16_t* out);

// Any channels, interleaved floats per pixel (channels.size() each): R, G, B, A as half floats, the
// others (Z, output variables) as float; ZIP compression, as encodeExr.
// `window`: where the pixels lie in the frame (a crop, image_io.h), null: the whole frame.
std::vector<unsigned char> encodeExrChannels(int width, int height, const std::vector<std::string>& channels,
                                             const std::vector<float>& pixels, const FrameWindow* window = nullptr);

// Reads every pixel of an EXR file as float, channels in the order R, G, B, A, then the others by
// name (as OpenImageIO presents them). False, with *error saying why, when the file cannot be
// opened or a pixel cannot be read (a truncated file has a good header).
bool readExr(const std::string& path, ImageData* out, std::string* error);

// Whether the file starts with the EXR magic number.
bool isExrFile(const std::string& path);

}  // namespace streyes
