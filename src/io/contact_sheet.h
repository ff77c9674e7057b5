// Contact sheets: the frames of an animation laid out on one image, left to right and top to
// bottom like the lines of a book, the way the spacetime papers present their animations.
#pragma once

#include <string>
#include <vector>

namespace streyes {

struct SheetOptions {
    int columns = 0;      // frames per row; 0: ceil(sqrt(count))
    int cellWidth = 0;    // frames are scaled to this width (aspect kept); 0: their own width
    int gap = 4;          // pixels between frames and around the sheet
    bool labels = true;   // the frame number in each cell's lower-left corner
};

// Where each frame goes. Cell i (in reading order) starts at (cellX(i), cellY(i)).
struct SheetLayout {
    int count = 0, columns = 1, rows = 0, cellWidth = 0, cellHeight = 0, gap = 0, width = 0, height = 0;
    int cellX(int i) const { return gap + (i % columns) * (cellWidth + gap); }
    int cellY(int i) const { return gap + (i / columns) * (cellHeight + gap); }
};
SheetLayout layoutSheet(int count, int frameWidth, int frameHeight, const SheetOptions& options);

struct SheetFrame {
    int frame = 0;
    std::string path;
};

// Reads the frames (any format OpenImageIO reads; R G B, premultiplied by A, over black), lays
// them out and writes the sheet atomically as an 8-bit sRGB .png or .jpg. Throws InputError for
// unreadable frames, frames of different sizes or another output format; RenderError when the
// sheet cannot be written.
void writeContactSheet(const std::vector<SheetFrame>& frames, const std::string& path, const SheetOptions& options);

}  // namespace streyes
