// The mixer benchmark's column order (bench/ColumnOrder.h): a stable permutation of the sampler's
// points, tile after tile.
#include <gtest/gtest.h>

#include <deme/Samplers.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>
#include <vector>

#include "../bench/ColumnOrder.h"

using deme::float3;

namespace {
auto asTuple(const float3& p) { return std::make_tuple(p.x, p.y, p.z); }
}  // namespace

TEST(BenchColumnOrder, StablePermutationTileAfterTile) {
    const float spacing = 0.01f, tile = 4.f * spacing;
    std::vector<float3> points =
        deme::HCPSampler(spacing).SampleCylinderZ(deme::make_float3(0.f, 0.f, 0.f), 0.2f, 0.05f);
    ASSERT_GT(points.size(), 1000u);
    const std::vector<float3> before = points;
    deme_bench::orderInColumns(points, tile);

    // The same points.
    ASSERT_EQ(points.size(), before.size());
    auto sorted = [](std::vector<float3> v) {
        std::sort(v.begin(), v.end(), [](const float3& a, const float3& b) { return asTuple(a) < asTuple(b); });
        return v;
    };
    const std::vector<float3> a = sorted(before), b = sorted(points);
    for (size_t i = 0; i < a.size(); i++) ASSERT_EQ(asTuple(a[i]), asTuple(b[i])) << i;

    // Tile after tile (rows of x tiles), and within a tile the sampler's order.
    float xmin = before[0].x, ymin = before[0].y;
    for (const float3& p : before) {
        xmin = std::min(xmin, p.x);
        ymin = std::min(ymin, p.y);
    }
    const float xmax = std::max_element(before.begin(), before.end(), [](auto& p, auto& q) { return p.x < q.x; })->x;
    const long nx = (long)std::floor((xmax - xmin) / tile) + 1;
    auto tileOf = [&](const float3& p) { return (long)((p.y - ymin) / tile) * nx + (long)((p.x - xmin) / tile); };
    std::map<std::tuple<float, float, float>, size_t> indexOf;
    for (size_t i = 0; i < before.size(); i++) indexOf[asTuple(before[i])] = i;
    auto indexBefore = [&](const float3& p) { return indexOf.at(asTuple(p)); };
    size_t tiles = 1;
    for (size_t i = 1; i < points.size(); i++) {
        const long t0 = tileOf(points[i - 1]), t1 = tileOf(points[i]);
        ASSERT_LE(t0, t1) << i;
        if (t0 == t1)
            ASSERT_LT(indexBefore(points[i - 1]), indexBefore(points[i])) << i;
        else
            tiles++;
    }
    EXPECT_GT(tiles, 50u);  // the cylinder is some 10 tiles across
}

TEST(BenchColumnOrder, EmptyAndOnePointStayAsTheyAre) {
    std::vector<float3> none;
    deme_bench::orderInColumns(none, 1.f);
    EXPECT_TRUE(none.empty());
    std::vector<float3> one{deme::make_float3(1.f, 2.f, 3.f)};
    deme_bench::orderInColumns(one, 1.f);
    ASSERT_EQ(one.size(), 1u);
    EXPECT_EQ(asTuple(one[0]), std::make_tuple(1.f, 2.f, 3.f));
}
