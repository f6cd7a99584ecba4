// tests/runtime/test_edge_map.cpp -- the watertight plan's EdgeMap
// (runtime/internal/edge_map.h) against std::unordered_map: what each key holds
// after inserts, growth, emptying by a new stamp (the table kept), and swaps, on
// small tables and on tables of huge pages (2 MiB and more).
#include "edge_map.h"
#include "sub_patches.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <unordered_map>
#include <vector>

namespace {

using lt::edgeKey;

// Inserts `count` random edges among `vertices` vertices into `map` and `oracle`,
// the values the insertion order, then checks both agree on every inserted key and
// on as many keys never inserted.
void fillAndCompare(lt::EdgeMap& map, std::unordered_map<uint64_t, uint32_t>& oracle, size_t count, uint32_t vertices,
                    std::mt19937& rng) {
    std::uniform_int_distribution<uint32_t> vertex(0, vertices - 1);
    std::vector<uint64_t> keys;
    for (size_t i = 0; i < count; ++i) {
        uint32_t a = vertex(rng), b = vertex(rng);
        if (a == b) continue;
        const uint64_t key = edgeKey(a, b);
        const auto [value, added] = map.emplace(key, uint32_t(i));
        const auto [expected, new_] = oracle.emplace(key, uint32_t(i));
        ASSERT_EQ(added, new_);
        ASSERT_EQ(*value, expected->second);
        keys.push_back(key);
    }
    ASSERT_EQ(map.size(), oracle.size());
    for (uint64_t key : keys) {
        const uint32_t* value = map.find(key);
        ASSERT_NE(value, nullptr);
        EXPECT_EQ(*value, oracle.at(key));
    }
    for (size_t i = 0; i < count; ++i) {
        const uint64_t key = edgeKey(vertex(rng), vertices + vertex(rng));  // a vertex never used
        EXPECT_EQ(map.find(key), nullptr);
    }
}

TEST(EdgeMap, HoldsWhatAnUnorderedMapHoldsThroughGrowthAndResets) {
    std::mt19937 rng(7);
    for (size_t count : {size_t(0), size_t(1), size_t(100), size_t(5000), size_t(200000)}) {
        SCOPED_TRACE(count);
        lt::EdgeMap map;
        EXPECT_EQ(map.find(edgeKey(1, 2)), nullptr);  // no table yet
        for (int level = 0; level < 4; ++level) {
            // Room for half the keys: the table grows past it; then, emptied, it is
            // kept and refilled with others.
            map.reset(count / 2);
            EXPECT_EQ(map.size(), 0u);
            std::unordered_map<uint64_t, uint32_t> oracle;
            fillAndCompare(map, oracle, count, uint32_t(count / 3 + 2), rng);
        }
    }
}

TEST(EdgeMap, AResetForgetsEveryKeyOfTheTableItKeeps) {
    lt::EdgeMap map;
    map.reset(1000);
    for (uint32_t v = 0; v < 1000; ++v) map.emplace(edgeKey(v, v + 1), v);
    map.reset(10);  // smaller: the table is kept
    for (uint32_t v = 0; v < 1000; ++v) EXPECT_EQ(map.find(edgeKey(v, v + 1)), nullptr);
    const auto [value, added] = map.emplace(edgeKey(5, 6), 42);
    EXPECT_TRUE(added);
    EXPECT_EQ(*value, 42u);
    EXPECT_EQ(map.size(), 1u);
}

TEST(EdgeMap, SwapExchangesTheContents) {
    lt::EdgeMap a, b;
    a.reset(4);
    b.reset(100000);  // over 2 MiB of slots: a table on huge pages
    a.emplace(edgeKey(1, 2), 1);
    b.emplace(edgeKey(3, 4), 2);
    b.emplace(edgeKey(5, 6), 3);
    a.swap(b);
    EXPECT_EQ(a.size(), 2u);
    EXPECT_EQ(b.size(), 1u);
    ASSERT_NE(a.find(edgeKey(5, 6)), nullptr);
    EXPECT_EQ(*a.find(edgeKey(5, 6)), 3u);
    EXPECT_EQ(a.find(edgeKey(1, 2)), nullptr);
    ASSERT_NE(b.find(edgeKey(1, 2)), nullptr);
    EXPECT_EQ(*b.find(edgeKey(1, 2)), 1u);
}

}  // namespace
