#include "render/expansion_release.h"

#include <utility>

#include "cull/view_cull.h"

namespace streyes {

void ExpansionRelease::start(std::vector<PixelRect> bucketRects, bool enabled, uint64_t threshold,
                             std::function<uint64_t()> madeBytes) {
    std::vector<Entry> forgotten;  // dropped after the lock: they hold children
    std::lock_guard<std::mutex> lock(mutex_);
    enabled_ = enabled && !keepAll_;
    threshold_ = threshold;
    madeBytes_ = std::move(madeBytes);
    pressed_ = false;
    complete_.clear();
    rects_ = std::move(bucketRects);
    done_.assign(rects_.size(), 0);
    waitingOn_.assign(rects_.size(), {});
    forgotten.swap(entries_);
    taken_.clear();
}

void ExpansionRelease::add(const ProceduralBody& procedural, int level, const Bounds3f& raster, bool everywhere,
                           size_t by, ChildrenLease holder) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (!enabled_ || by >= rects_.size() || !taken_.insert({&procedural, level}).second) return;
    const uint32_t e = uint32_t(entries_.size());
    int waiting = 0;
    for (size_t i = 0; i < rects_.size(); ++i)
        if (!done_[i] && (i == by || everywhere || !rasterOutside(raster, rects_[i]))) {
            waitingOn_[i].push_back(e);
            ++waiting;
        }
    entries_.push_back({&procedural, level, std::move(holder), waiting});
}

void ExpansionRelease::bucketDone(size_t i) {
    std::vector<Entry> ready;  // let go after the lock: freeing children takes a while
    {
        std::lock_guard<std::mutex> lock(mutex_);
        if (i >= rects_.size()) return;
        done_[i] = 1;
        std::vector<uint32_t> held;
        held.swap(waitingOn_[i]);
        if (!enabled_) return;
        for (uint32_t e : held)
            if (--entries_[e].waiting == 0) complete_.push_back(e);
        if (!pressed_ && madeBytes_ && madeBytes_() > threshold_) pressed_ = true;
        if (!pressed_) return;
        for (uint32_t e : complete_) {
            Entry& entry = entries_[e];
            taken_.erase({entry.procedural, entry.level});
            ready.push_back({entry.procedural, entry.level, std::move(entry.holder), 0});
            ++released_;
        }
        complete_.clear();
    }
    // The holder keeps the procedural alive (its parent's children) until it has let go.
    for (Entry& entry : ready) {
        entry.procedural->release(entry.level);
        entry.holder.reset();
    }
}

void ExpansionRelease::keepEverything(std::vector<ChildrenLease>&& leases) {
    std::lock_guard<std::mutex> lock(mutex_);
    keepAll_ = true;
    enabled_ = false;
    for (ChildrenLease& l : leases) kept_.push_back(std::move(l));
}

uint64_t ExpansionRelease::released() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return released_;
}

}  // namespace streyes
