#include <gtest/gtest.h>

#include <stdexcept>

#include "geom/body.h"
#include "geom/grid.h"

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

}  // namespace
}  // namespace streyes
