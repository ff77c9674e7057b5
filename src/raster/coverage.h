// Coverage for occlusion culling: which pixel-frame cells of a bucket are fully covered by
// opaque hits nearer than a depth boundary. The cull stage sums it into a SummedVolumeTable.
#pragma once

#include <cstdint>
#include <vector>

#include "raster/image_block.h"

namespace streyes {

// Coverage of a bucket's block of samples: cell (x, y, frame) is 1 when every sample of the
// pixel in that frame has a hit nearer than `boundary`. Cells already set stay set (depths only
// ever decrease, and the boundary only grows). Returns how many cells were newly covered.
// coverage is indexed [(fi * rect height + y - y0) * rect width + x - x0].
// With `frames` = 1 only the first frame's cells are made (the caller knows every frame sees the
// same: nothing in the block has a record yet).
// `farthest`, when given, receives for each cell scanned (those not covered before) the farthest
// depth of the pixel's hits in that frame, +inf unless every sample has an opaque hit: a surface
// strictly farther than it at every cell it reaches cannot change a sample there. It also stands
// for that measure where nothing was written since: a pixel the block has not marked touched
// (ImageBlock::touch) keeps the value farthest holds, and is not read again (the caller clears
// the marks once it has the coverage: untouchAll()).
uint64_t updateCoverage(const ImageBlock& block, float boundary, std::vector<uint8_t>& coverage, int frames = -1,
                        std::vector<float>* farthest = nullptr);

}  // namespace streyes
