// Point clouds: the file format round trip and its refusals, texture3d()'s filter against its
// formula, and the render's store: the same bytes whatever order the points arrive in.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <random>

#include "shade/point_cloud.h"
#include "shade/point_clouds.h"
#include "test_util.h"

namespace streyes {
namespace {

std::string bytesOf(const std::string& path) {
    std::ifstream f(path, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
}

// A 3 x 3 lattice of points one unit apart in z = 0 facing +z, radius 0.5, channel "v" = x + 10 y
// and "c" = (x, y, 1).
BakedPointCloud lattice() {
    std::vector<float> data;
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 3; ++x) {
            const float rec[] = {float(x), float(y), 0, 0, 0, 1, 0.5f, float(x) + 10 * float(y), float(x), float(y), 1};
            data.insert(data.end(), std::begin(rec), std::end(rec));
        }
    return BakedPointCloud({{"v", 1}, {"c", 3}}, data);
}

TEST(BakedPointCloud, WritesAndReadsBackEveryFloat) {
    test::TempDir dir("ptc");
    const std::string path = dir.path() + "/a.ptc";
    const BakedPointCloud a = lattice();
    std::string error;
    ASSERT_TRUE(a.write(path, &error)) << error;
    BakedPointCloud b;
    ASSERT_TRUE(b.read(path, &error)) << error;
    ASSERT_EQ(b.size(), 9u);
    ASSERT_EQ(b.channels().size(), 2u);
    EXPECT_EQ(b.channels()[1].name, "c");
    EXPECT_EQ(b.channels()[1].comps, 3);
    for (size_t i = 0; i < 9; ++i)
        for (int f = 0; f < b.stride(); ++f) EXPECT_EQ(b.point(i)[f], a.point(i)[f]) << i << " " << f;
    int offset = 0, comps = 0;
    EXPECT_TRUE(b.channel("c", &offset, &comps));
    EXPECT_EQ(offset, 8);
    EXPECT_EQ(comps, 3);
    EXPECT_FALSE(b.channel("nope", &offset, &comps));
}

TEST(BakedPointCloud, RefusesMissingTruncatedForeignAndNewerFiles) {
    test::TempDir dir("ptc");
    std::string error;
    BakedPointCloud c;
    EXPECT_FALSE(c.read(dir.path() + "/none.ptc", &error));
    EXPECT_NE(error.find("cannot open"), std::string::npos) << error;

    const std::string good = dir.path() + "/good.ptc";
    ASSERT_TRUE(lattice().write(good, &error));
    const std::string bytes = bytesOf(good);
    auto tryBytes = [&](const std::string& b) {
        const std::string p = dir.path() + "/bad.ptc";
        std::ofstream(p, std::ios::binary) << b;
        error.clear();
        BakedPointCloud x;
        const bool ok = x.read(p, &error);
        return ok ? std::string("read") : error;
    };
    EXPECT_NE(tryBytes(bytes.substr(0, bytes.size() - 4)).find("truncated"), std::string::npos);
    EXPECT_NE(tryBytes(bytes.substr(0, 10)).find("truncated"), std::string::npos);
    EXPECT_NE(tryBytes(bytes + "xxxx").find("corrupt"), std::string::npos);
    EXPECT_NE(tryBytes("Aqsis bake file\n3\n").find("STRYPTC"), std::string::npos);
    std::string newer = bytes;
    newer[8] = 2;  // the version
    EXPECT_NE(tryBytes(newer).find("version 2"), std::string::npos);
    std::string nan = bytes;
    const float q = std::nanf("");
    std::memcpy(&nan[nan.size() - 4], &q, 4);
    EXPECT_NE(tryBytes(nan).find("not finite"), std::string::npos);
    EXPECT_EQ(tryBytes(bytes), "read");
}

TEST(BakedPointCloud, LookupAtABakedPointGivesItsValueExactly) {
    BakedPointCloud c = lattice();
    c.prepare();
    int offset = 0, comps = 0;
    ASSERT_TRUE(c.channel("v", &offset, &comps));
    const float n[3] = {0, 0, 1};
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 3; ++x) {
            const float p[3] = {float(x), float(y), 0};
            float v = -1;
            filterPointCloud(c, p, n, offset, comps, &v);
            EXPECT_EQ(v, float(x) + 10 * float(y));
        }
}

TEST(BakedPointCloud, BetweenPointsTheFourNearestBlendByTheGaussianOfDistanceOverRadius) {
    BakedPointCloud c = lattice();
    c.prepare();
    int offset = 0, comps = 0;
    ASSERT_TRUE(c.channel("v", &offset, &comps));
    // At (0.5, 0.5): the four corners (0,0), (1,0), (0,1), (1,1) are the nearest, each at d^2 = 0.5:
    // equal weights, the mean 5.5.
    const float n[3] = {0, 0, 1};
    const float centre[3] = {0.5f, 0.5f, 0};
    float v = 0;
    filterPointCloud(c, centre, n, offset, comps, &v);
    EXPECT_NEAR(v, (0 + 1 + 10 + 11) / 4.0f, 1e-5f);
    // At (0.25, 0, 0): nearest (0,0) d^2 1/16, (1,0) 9/16, (0,1) 17/16, (1,1) 25/16.
    const float p[3] = {0.25f, 0, 0};
    filterPointCloud(c, p, n, offset, comps, &v);
    const double d2[4] = {1.0 / 16, 9.0 / 16, 17.0 / 16, 25.0 / 16}, val[4] = {0, 1, 10, 11};
    double num = 0, den = 0;
    for (int i = 0; i < 4; ++i) {
        const double w = std::exp(-1.3 * d2[i] / 0.25);
        num += w * val[i];
        den += w;
    }
    EXPECT_NEAR(v, num / den, 1e-5);
    // Points facing away count for nothing: a query facing -z finds no weight and gives 0.
    const float away[3] = {0, 0, -1};
    filterPointCloud(c, p, away, offset, comps, &v);
    EXPECT_EQ(v, 0.0f);
}

// The store: records arriving in any order, split over any number of calls, repeated (a still grid
// shaded in each frame), give the same file byte for byte.
TEST(PointClouds, FileIsTheSameBytesWhateverTheOrderAndRepetitionOfBakes) {
    test::TempDir dir("ptc");
    const std::vector<sl::CloudChannel> channels = {{"v", 1}};
    std::vector<float> recs;
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u(-1, 1);
    for (int i = 0; i < 500; ++i) {
        const float r[] = {u(rng), u(rng), u(rng), 0, 0, 1, 0.1f, u(rng)};
        recs.insert(recs.end(), std::begin(r), std::end(r));
    }
    auto bakeAll = [&](const std::string& file, const std::vector<int>& order, int chunk, int repeat) {
        Log log;
        PointClouds clouds(log);
        std::vector<float> shuffled;
        for (int i : order) shuffled.insert(shuffled.end(), recs.begin() + 8 * i, recs.begin() + 8 * i + 8);
        for (int k = 0; k < repeat; ++k)
            for (size_t at = 0; at < order.size(); at += size_t(chunk)) {
                sl::BakeRecords b;
                b.channels = &channels;
                b.records = shuffled.data() + 8 * at;
                b.count = int(std::min(order.size() - at, size_t(chunk)));
                clouds.bake3d(file, b);
            }
        clouds.write();
        return bytesOf(file);
    };
    std::vector<int> order(500);
    for (int i = 0; i < 500; ++i) order[size_t(i)] = i;
    const std::string a = bakeAll(dir.path() + "/a.ptc", order, 500, 1);
    std::shuffle(order.begin(), order.end(), rng);
    const std::string b = bakeAll(dir.path() + "/b.ptc", order, 37, 3);
    EXPECT_EQ(a.size(), 8 + 4 + 4 + 4 + 1 + 4 + 8 + 500u * 8 * 4);
    EXPECT_TRUE(a == b);
}

TEST(PointClouds, ChannelsOfEveryCallAreMergedInNameOrderWithZerosWhereACallLackedOne) {
    Log log;
    PointClouds clouds(log);
    const std::vector<sl::CloudChannel> first = {{"z", 1}}, second = {{"a", 3}};
    const float r1[] = {0, 0, 0, 0, 0, 1, 1, 7};
    const float r2[] = {1, 0, 0, 0, 0, 1, 1, 2, 3, 4};
    clouds.bake3d("f", {&first, r1, 1});
    clouds.bake3d("f", {&second, r2, 1});
    const BakedPointCloud c = clouds.gathered("f");
    ASSERT_EQ(c.channels().size(), 2u);
    EXPECT_EQ(c.channels()[0].name, "a");
    EXPECT_EQ(c.channels()[1].name, "z");
    ASSERT_EQ(c.size(), 2u);
    // Sorted by position: the point at x = 0 first, with a = 0 and z = 7; then x = 1.
    EXPECT_EQ(c.point(0)[7], 0.0f);
    EXPECT_EQ(c.point(0)[10], 7.0f);
    EXPECT_EQ(c.point(1)[8], 3.0f);
    EXPECT_EQ(c.point(1)[10], 0.0f);
}

TEST(PointClouds, BakeFileIsAqsisTextSortedAndUnwritableIsAnError) {
    test::TempDir dir("bake");
    Log log;
    PointClouds clouds(log);
    const float r[] = {0.5f, 0.25f, 1, 2, 3, 0.125f, 0.75f, 4, 5, 6};
    const std::string path = dir.path() + "/x.bake";
    clouds.bake(path, 3, r, 2);
    clouds.bake(path, 3, r, 1);  // a duplicate: dropped
    clouds.write();
    EXPECT_EQ(bytesOf(path), "Aqsis bake file\n3\n0.125 0.75 4 5 6\n0.5 0.25 1 2 3\n");
    clouds.bake(dir.path() + "/no/such/folder/x.bake", 1, r, 1);
    EXPECT_THROW(clouds.write(), InputError);
}

}  // namespace
}  // namespace streyes
