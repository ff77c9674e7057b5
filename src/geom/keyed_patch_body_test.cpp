#include <gtest/gtest.h>

#include <stdexcept>

#include "geom/body.h"
#include "geom/grid.h"
#include "geom/root_chunks.h"

namespace streyes {
namespace {

using Corners = TrilinearBody::Corners;

Corners square(float x) { return {{{x, 0, 5}, {x + 1, 0, 5}, {x, 1, 5}, {x + 1, 1, 5}}}; }

// Five keys at t = 0..4 with x = 0, 2, 1, 3, 3 (a path that turns, and a still last segment).
KeyedPatchBody makeBody() {
    std::vector<double> t{0, 1, 2, 3, 4};
    std::vector<Corners> k{square(0), square(2), square(1), square(3), square(3)};
    return KeyedPatchBody(t, k, {}, nullptr);
}

TEST(KeyedPatchBody, SplitsInTimeAtKeysIntoTheTrilinearBodiesOfItsSegments) {
    KeyedPatchBody body = makeBody();
    EXPECT_FALSE(body.diceableInTime());
    EXPECT_TRUE(body.moving());
    BodyPtr h[2];
    body.split(SplitAxis::T, h);
    EXPECT_EQ(h[0]->time().t1, 2.0);  // the middle key, exactly
    EXPECT_EQ(h[1]->time().t0, 2.0);
    // Split until only two-key pieces remain: they are the four segments, corners exact.
    std::vector<BodyPtr> work;
    work.push_back(std::move(h[0]));
    work.push_back(std::move(h[1]));
    std::vector<const TrilinearBody*> segments;
    std::vector<BodyPtr> keep;
    while (!work.empty()) {
        BodyPtr b = std::move(work.back());
        work.pop_back();
        if (b->diceableInTime()) {
            segments.push_back(static_cast<const TrilinearBody*>(b.get()));
            keep.push_back(std::move(b));
            continue;
        }
        BodyPtr p[2];
        b->split(SplitAxis::T, p);
        work.push_back(std::move(p[0]));
        work.push_back(std::move(p[1]));
    }
    ASSERT_EQ(segments.size(), 4u);
    const float xs[5] = {0, 2, 1, 3, 3};
    for (const TrilinearBody* s : segments) {
        const int i = int(s->time().t0);
        EXPECT_EQ(s->time().t1, i + 1.0);
        EXPECT_EQ(s->corners(0), square(xs[i]));
        EXPECT_EQ(s->corners(1), square(xs[i + 1]));
        EXPECT_EQ(s->moving(), i != 3);  // the last segment stands still
    }
}

TEST(KeyedPatchBody, BoundHoldsEveryKeyAndRestrictionInterpolates) {
    KeyedPatchBody body = makeBody();
    Bounds3f b = body.bound().swept();
    EXPECT_EQ(b.lo.x, 0.0f);
    EXPECT_EQ(b.hi.x, 4.0f);
    BodyPtr r = body.restrictedTo(0.5, 2.5);
    ASSERT_FALSE(r->diceableInTime());  // keys 0.5, 1, 2, 2.5
    Bounds3f rb = r->bound().swept();
    EXPECT_FLOAT_EQ(rb.lo.x, 1.0f);  // x = 1 at t = 0.5, 2 at t = 1, 1 at t = 2, 2 at t = 2.5
    EXPECT_FLOAT_EQ(rb.hi.x, 3.0f);
    BodyPtr one = body.restrictedTo(3.2, 3.6);  // inside the still segment: two keys
    EXPECT_TRUE(one->diceableInTime());
    EXPECT_FALSE(one->moving());
    Grid g;
    EXPECT_THROW(body.dice(2, 2, g), std::logic_error);
}

TEST(KeyedPatchBody, SplitInUKeepsEveryKey) {
    KeyedPatchBody body = makeBody();
    BodyPtr h[2];
    body.split(SplitAxis::U, h);
    EXPECT_FALSE(h[0]->diceableInTime());
    EXPECT_EQ(h[0]->time().t0, 0.0);
    EXPECT_EQ(h[0]->time().t1, 4.0);
    EXPECT_FLOAT_EQ(h[0]->bound().swept().hi.x, 3.5f);  // the left half at x = 3 is [3, 3.5]
    EXPECT_FLOAT_EQ(h[1]->bound().swept().lo.x, 0.5f);
}

// A leaf keyed every 2 frames over frames 0..32 that stands still over [12, 20] and moves
// elsewhere, one unit a key, under a perspective camera.
KeyedPatchBody longLeaf() {
    std::vector<double> t;
    std::vector<Corners> k;
    for (int i = 0; i <= 16; ++i) {
        t.push_back(2.0 * i);
        const int x = i < 6 ? i : i <= 10 ? 6 : 6 + (i - 10);
        k.push_back(square(float(x)));
    }
    return KeyedPatchBody(t, k, {}, nullptr);
}

Camera leafCamera() {
    CameraDesc cd;
    cd.projection = ProjectionKind::Perspective;
    cd.fov = 60;
    cd.xres = 320, cd.yres = 240;
    return Camera(cd);
}

TEST(KeyedPatchBody, KeysOverAWindowKeepThoseBracketingItAndTheWholeRootsDecisions) {
    const KeyedPatchBody leaf = longLeaf();
    const Camera cam = leafCamera();
    const int chunk = rootChunkFrames(leaf, cam);
    // Over [13, 17.5] (still there): the keys 12 .. 18, and it still counts as moving, with the
    // chunk of frames measured over every key.
    std::unique_ptr<KeyedPatchBody> part = leaf.keysOver(13, 17.5, cam);
    ASSERT_TRUE(part);
    ASSERT_EQ(part->keyCount(), 4u);
    EXPECT_EQ(part->keyTime(0), 12.0);
    EXPECT_EQ(part->keyTime(3), 18.0);
    EXPECT_FALSE(part->time().openEnd);
    EXPECT_TRUE(part->moving());
    EXPECT_EQ(rootChunkFrames(*part, cam), chunk);
    EXPECT_EQ(part->pieceKey, leaf.pieceKey);
    EXPECT_EQ(part->bound().swept().hi.x, leaf.bound().swept().hi.x);  // x = 17 at the last key
    // Every piece cut over times inside the window is the whole root's, bit for bit.
    for (const auto& w : {std::pair<double, double>{13, 13.5}, {12, 18}, {14.25, 17.75}, {13, 17.5}}) {
        const BodyPtr a = leaf.restrictedTo(w.first, w.second), b = part->restrictedTo(w.first, w.second);
        EXPECT_EQ(a->diceableInTime(), b->diceableInTime());
        EXPECT_EQ(a->moving(), b->moving());
        EXPECT_EQ(a->time().t0, b->time().t0);
        EXPECT_EQ(a->time().t1, b->time().t1);
        EXPECT_EQ(a->time().openEnd, b->time().openEnd);
        const RasterMeasure ma = a->measure(cam), mb = b->measure(cam);
        EXPECT_EQ(ma.extentU, mb.extentU);
        EXPECT_EQ(ma.extentV, mb.extentV);
        EXPECT_EQ(ma.motion, mb.motion);
        EXPECT_EQ(a->boundDuring(w.first, w.second).lo.x, b->boundDuring(w.first, w.second).lo.x);
        EXPECT_EQ(a->boundDuring(w.first, w.second).hi.x, b->boundDuring(w.first, w.second).hi.x);
        EXPECT_EQ(leaf.boundDuring(w.first, w.second).hi.x, part->boundDuring(w.first, w.second).hi.x);
    }
    // Three keys at least; near the end, the root's own end.
    std::unique_ptr<KeyedPatchBody> end = leaf.keysOver(31.5, 32, cam);
    ASSERT_TRUE(end);
    EXPECT_EQ(end->keyCount(), 3u);
    EXPECT_EQ(end->keyTime(2), 32.0);
    // A window over every key keeps the root as it is.
    EXPECT_FALSE(leaf.keysOver(-1, 40, cam));
    EXPECT_FALSE(leaf.keysOver(1, 31, cam));
}

}  // namespace
}  // namespace streyes
