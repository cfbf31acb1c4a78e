// SPDX-License-Identifier: BSD-3-Clause
/**
 * pss::EdgeMap, the mesher's flat hash map from edge keys, against std::map on the same
 * operations: every key inserted is found with its value, a second insertion keeps the first
 * value, absent keys are not found, growth keeps every entry, and the reserved key is refused.
 */
#include "pss/EdgeMap.h"

#include <gtest/gtest.h>

#include <map>
#include <random>
#include <stdexcept>
#include <vector>

TEST(EdgeMap, AgreesWithStdMapThroughGrowth)
{
  pss::EdgeMap<std::uint32_t> map;
  std::map<std::uint64_t, std::uint32_t> truth;
  std::mt19937 random(7);
  std::uniform_int_distribution<std::uint32_t> vertex(0, 5000);
  for (std::uint32_t i = 0; i < 100000; ++i)
  {
    const std::uint32_t a = vertex(random);
    const std::uint32_t b = a + 1 + vertex(random) % 8; // neighbouring indices, as a mesh's edges
    const std::uint64_t key = pss::edgeKey(a, b);
    ASSERT_EQ(key, pss::edgeKey(b, a));
    const auto [value, added] = map.tryEmplace(key, i);
    const bool expected = truth.emplace(key, i).second;
    ASSERT_EQ(added, expected);
    ASSERT_EQ(value, truth[key]) << "a second insertion keeps the first value";
  }
  EXPECT_EQ(map.size(), truth.size());
  for (const auto& [key, value] : truth)
  {
    const std::uint32_t* found = map.find(key);
    ASSERT_NE(found, nullptr);
    EXPECT_EQ(*found, value);
  }
  std::size_t visited = 0;
  map.forEach([&](std::uint64_t key, std::uint32_t value) {
    ++visited;
    EXPECT_EQ(truth.at(key), value);
  });
  EXPECT_EQ(visited, truth.size());
  EXPECT_EQ(map.find(pss::edgeKey(6000, 7000)), nullptr);
  map[pss::edgeKey(6000, 7000)] = 5;
  EXPECT_EQ(*map.find(pss::edgeKey(6000, 7000)), 5u);
}

TEST(EdgeMap, ReserveClearAndTheReservedKey)
{
  pss::EdgeMap<double> map;
  EXPECT_TRUE(map.empty());
  EXPECT_EQ(map.find(1), nullptr) << "an empty map finds nothing";
  map.reserve(1000);
  for (std::uint64_t k = 0; k < 1000; ++k)
  {
    map[k] = static_cast<double>(k) / 2.0;
  }
  EXPECT_EQ(map.size(), 1000u);
  EXPECT_EQ(*map.find(999), 499.5);
  EXPECT_THROW(map.tryEmplace(pss::EdgeMap<double>::EmptyKey, 1.0), std::invalid_argument);
  EXPECT_EQ(map.find(pss::EdgeMap<double>::EmptyKey), nullptr);
  map.clear();
  EXPECT_TRUE(map.empty());
  EXPECT_EQ(map.find(999), nullptr);
  map[3] = 1.0;
  EXPECT_EQ(map.size(), 1u);
}
