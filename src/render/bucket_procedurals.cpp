// The bucket worker's procedurals: a moving one's views per level of detail, the expansion of
// one the split loop reaches (kept and shared, or this bucket's own), and what lets a kept
// expansion go once no bucket left can reach it (render/expansion_release.h).
#include <algorithm>
#include <cmath>

#include "cull/view_cull.h"
#include "geom/root_chunks.h"
#include "procedural/procedural.h"
#include "render/bucket.h"
#include "render/bucket_bounds.h"
#include "render/expansion_release.h"
#include "util/sampling.h"

namespace streyes {

using namespace bucket;

// A moving procedural: the frames whose exposures its bound reaches the bucket in (halving the
// range, as for moving bodies), each at the level of detail of its own bound; runs of frames that
// share a level make one view, across frames whose bound misses the bucket if they share it too
// (so two views of one level never have their children's pieces meet: see levelRun).
void BucketWorker::pushProceduralViews(const ProceduralBody& procedural, int fa, int fb) {
    levels_.clear();
    collectLevels(procedural, fa, fb);
    const double open = scene_.shutter.open, close = scene_.shutter.close;
    for (size_t i = 0; i < levels_.size();) {
        size_t j = i + 1;
        while (j < levels_.size() && levels_[j].second == levels_[i].second &&
               sameLevelBetween(procedural, levels_[j - 1].first, levels_[j].first, levels_[i].second))
            ++j;
        const int first = levels_[i].first, last = levels_[j - 1].first;
        std::unique_ptr<ProceduralBody> view = procedural.view(bucket_.firstFrame + first + open,
                                                               bucket_.firstFrame + last + close, levels_[i].second);
        view->exposure = last == first ? bucket_.firstFrame + first : Body::kNoExposure;
        push(std::move(view));
        i = j;
    }
}

void BucketWorker::collectLevels(const ProceduralBody& procedural, int fa, int fb) {
    const double a = bucket_.firstFrame + fa + scene_.shutter.open, b = bucket_.firstFrame + fb + scene_.shutter.close;
    const Bounds3f box = procedural.boundDuring(a, b);
    const PixelRect& R = bucket_.rect;
    if (boxOutside(cameraOf(procedural), box, {R.x0 - 1, R.y0 - 1, R.x1 + 1, R.y1 + 1})) {
        ++counters.culledView;
        return;
    }
    if (fa < fb) {
        const int mid = fa + (fb - fa) / 2;
        collectLevels(procedural, fa, mid);
        collectLevels(procedural, mid + 1, fb);
        return;
    }
    levels_.push_back({fa, levelInFrame(procedural, bucket_.firstFrame + fa)});
}

// Are the frames strictly between block indices fa and fb all at `level`?
bool BucketWorker::sameLevelBetween(const ProceduralBody& procedural, int fa, int fb, int level) const {
    for (int f = fa + 1; f < fb; ++f)
        if (levelInFrame(procedural, bucket_.firstFrame + f) != level) return false;
    return true;
}

int BucketWorker::levelInFrame(const ProceduralBody& procedural, int frame) const {
    const Bounds3f box = procedural.boundDuring(frame + scene_.shutter.open, frame + scene_.shutter.close);
    const Camera& cam = scene_.cameras.ofFrame(frame);
    if (cam.perspective() && box.lo.z < cam.eyePlane()) return kDetailUnbounded;
    const Bounds3f r = rasterOfBox(cam, box);
    return detailLevel(double(r.hi.x - r.lo.x) * double(r.hi.y - r.lo.y));
}

// A view stands for a run of the block's frames at one level of detail, cut where the block ends.
// Its children are cut into chunks of frames (pushChunks) that may reach past the view: they are
// wanted only in the frames at the view's level, found frame by frame around the view as far as
// the longest chunk reaches. So a frame's pieces are the same in every block (the run does not end
// where the block does) and no frame gets the children of two levels.
FrameRun BucketWorker::levelRun(const ProceduralBody& view, int first, int last) const {
    const ProceduralBody& procedural = view.rootBody();
    const int level = view.level(cameraOf(view));
    constexpr int kReach = std::max(kMaxChunkFrames, kMaxWorldChunkFrames) - 1;
    FrameRun run{first, last};
    while (run.lo > first - kReach && levelInFrame(procedural, run.lo - 1) == level) --run.lo;
    while (run.hi < last + kReach && levelInFrame(procedural, run.hi + 1) == level) ++run.hi;
    return run;
}

Bounds3f BucketWorker::reach(const ProceduralBody& procedural, bool* everywhere) const {
    // As process() takes a body's raster bound before its view cull (views of a moving procedural
    // are bounded within their root's bound over the shot).
    const Camera& cam = cameraOf(procedural);
    const Bounds3f swept = displaced(procedural, procedural.bound().swept());
    *everywhere = cam.perspective() && !(swept.lo.z >= cam.eyePlane());
    if (*everywhere) return swept;
    return cullRaster(cam, procedural, procedural.measure(cam), swept);
}

// The children enter the loop like roots. The expansion itself happens once, in whichever
// bucket gets there first; the others reuse its children.
void BucketWorker::expand(const ProceduralBody& procedural) {
    bool expandedHere = false;
    const std::vector<BodyPtr>* made;
    if (procedural.keepsChildren()) {
        bool madeHere = false, madeAgain = false;
        ChildrenLease lease = procedural.children(*scene_.factory, cameraOf(procedural), log_, &madeHere, &madeAgain);
        made = &lease->bodies;
        expandedHere = madeHere && !madeAgain;  // made again after a release: counted apart
        counters.proceduralsMadeAgain += madeHere && madeAgain;
        if (release_) {
            const ProceduralBody& root = procedural.rootBody();
            bool everywhere = false;
            const Bounds3f raster = reach(root, &everywhere);
            release_->add(root, procedural.level(cameraOf(procedural)), raster, everywhere, bucket_.tileIndex, root.heldBy());
        }
        leases_.push_back(std::move(lease));  // holds them until the split loop is done
    } else {  // this bucket's own, freed when it is done (ProceduralGenerator::keepsChildren)
        ProceduralChildren& own = ownChildren_.emplace_back();
        procedural.expandInto(own, *scene_.factory, cameraOf(procedural), log_);
        // Every bucket that expands it makes the same children: keyed by the procedural, the
        // level and their place, their grids are shared as a kept expansion's are.
        const uint64_t key =
            hashCombine(procedural.rootKey(), 0x300000000ull + uint64_t(uint32_t(procedural.level(cameraOf(procedural)))));
        for (size_t i = 0; i < own.bodies.size(); ++i) own.bodies[i]->pieceKey = hashCombine(key, i);
        made = &own.bodies;
        expandedHere = true;
    }
    const std::vector<BodyPtr>& children = *made;
    if (expandedHere) {
        ++counters.proceduralsExpanded;
        const size_t d = size_t(procedural.depth());
        if (counters.proceduralsExpandedByDepth.size() <= d) counters.proceduralsExpandedByDepth.resize(d + 1, 0);
        ++counters.proceduralsExpandedByDepth[d];
    }
    // A view of a moving procedural stands for some of the bucket's frames: its children (bodies
    // over the whole shot) are wanted in those only.
    const int fa = std::max(0, int(std::lround(procedural.time().t0 - scene_.shutter.open)) - bucket_.firstFrame);
    const int fb = std::min(bucket_.frameCount - 1,
                            int(std::lround(procedural.time().t1 - scene_.shutter.close)) - bucket_.firstFrame);
    FrameRun run;
    if (&procedural != &procedural.rootBody() && procedural.rootBody().moving())
        run = levelRun(procedural, bucket_.firstFrame + fa, bucket_.firstFrame + fb);
    for (const BodyPtr& child : children) pushRoot(*child, fa, fb, run);
}

}  // namespace streyes
