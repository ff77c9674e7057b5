// Level of detail (RI Spec 3.2, 4.2.4 and 4.1.5): Detail gives a model's box, DetailRange the range
// of raster areas of that box over which the primitives that follow are the model's
// representation, RelativeDetail scales every area. The scene only records them (Attributes::
// detail, RenderSettings::relativeDetail): which representation a frame draws is decided from that
// frame's camera when bodies are made (bodies/level_of_detail.h).
#include <cmath>
#include <limits>

#include "scene/rib_requests.h"

namespace streyes {

namespace {

// Detail [xmin xmax ymin ymax zmin zmax]: in the current coordinate system.
void detail(RibParser& reader, RibArgs& args) {
    const std::vector<double> b = args.numbers(6, "xmin xmax ymin ymax zmin zmax");
    args.expectEnd();
    for (int a = 0; a < 3; ++a)
        if (!(b[size_t(2 * a)] <= b[size_t(2 * a + 1)]))
            args.fail("the box's " + std::string(1, char('x' + a)) + "min (" + formatNumber(b[size_t(2 * a)]) +
                      ") is above its max (" + formatNumber(b[size_t(2 * a + 1)]) + ")");
    RibState& s = reader.state();
    auto lod = std::make_shared<LevelOfDetail>();
    if (s.attributes->detail) *lod = *s.attributes->detail;
    lod->bound = Bounds3d({b[0], b[2], b[4]}, {b[1], b[3], b[5]});
    lod->boundToWorld = s.ctm;
    lod->hasBound = true;
    s.mutableAttributes().detail = std::move(lod);
}

// DetailRange minvisible lowertransition uppertransition maxvisible (raster areas, in order).
void detailRange(RibParser& reader, RibArgs& args) {
    const std::vector<double> r = args.numbers(4, "minvisible lowertransition uppertransition maxvisible");
    args.expectEnd();
    for (double v : r)
        if (!(v >= 0)) args.fail("the areas must not be negative, got " + formatNumber(v));
    if (!(r[0] <= r[1] && r[1] <= r[2] && r[2] <= r[3]))
        args.fail("the areas must not decrease: minvisible <= lowertransition <= uppertransition <= maxvisible, got " +
                  formatNumber(r[0]) + " " + formatNumber(r[1]) + " " + formatNumber(r[2]) + " " + formatNumber(r[3]));
    RibState& s = reader.state();
    auto lod = std::make_shared<LevelOfDetail>();
    if (s.attributes->detail) *lod = *s.attributes->detail;
    if (!lod->hasBound)
        reader.log().lenient("detail:nobound", args.loc(),
                             "DetailRange without a Detail box before it: its area is taken as infinite (the "
                             "representation for the largest areas is drawn)");
    // RIB writers give 1e38 (RI_INFINITY) for "no upper end".
    for (size_t i = 0; i < 4; ++i) lod->range[i] = r[i] >= 1e30 ? std::numeric_limits<double>::infinity() : r[i];
    lod->loc = args.loc();
    s.mutableAttributes().detail = std::move(lod);
}

void relativeDetail(RibParser& reader, RibArgs& args) {
    const double r = args.number("relativedetail");
    args.expectEnd();
    if (!(r >= 0) || !std::isfinite(r)) args.fail("RelativeDetail must be a finite number >= 0, got " + formatNumber(r));
    reader.scene().settings.relativeDetail = r;
}

}  // namespace

void addDetailRequests(RibRequestTable& table) {
    table.add("Detail", {detail, "Detail [xmin xmax ymin ymax zmin zmax]"});
    table.add("DetailRange", {detailRange, "DetailRange minvisible lowertransition uppertransition maxvisible"});
    table.add("RelativeDetail", {relativeDetail, "RelativeDetail scale", RibPhase::Options});
}

}  // namespace streyes
