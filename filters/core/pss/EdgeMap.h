// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file EdgeMap.h
 * @brief A hash map from 64-bit keys (a mesh edge's two vertex indices, a pair of cell corners)
 * to small values, for the mesher's hot bookkeeping.
 *
 * Open addressing with linear probing in one flat array, kept at most half full: a look-up is a
 * multiplication and, nearly always, one cache line, where std::unordered_map allocates a node per
 * entry and follows a pointer per look-up (the trim's edge tables cost half its serial time).
 * The key ~0 is reserved (it marks an empty slot); an edgeKey of two distinct vertices never
 * takes it. There is no erase. Iteration order is the table's, which
 * depends on the insertion history: callers that need a deterministic order sort the keys.
 */
#pragma once

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <utility>
#include <vector>

namespace pss
{

/// The key of the edge between vertices @p a and @p b (either order): min << 32 | max.
inline std::uint64_t edgeKey(std::uint32_t a, std::uint32_t b)
{
  return a < b ? (static_cast<std::uint64_t>(a) << 32) | b : (static_cast<std::uint64_t>(b) << 32) | a;
}

template <class Value>
class EdgeMap
{
public:
  static constexpr std::uint64_t EmptyKey = ~std::uint64_t{ 0 };

  EdgeMap() = default;

  /// Room for @p count entries without growing.
  void reserve(std::size_t count)
  {
    std::size_t capacity = 16;
    while (capacity < 2 * count)
    {
      capacity *= 2;
    }
    if (capacity > Slots.size())
    {
      rehash(capacity);
    }
  }

  std::size_t size() const { return Count; }
  bool empty() const { return Count == 0; }

  void clear()
  {
    Slots.clear();
    Count = 0;
    Shift = 64;
  }

  /// The value of @p key, inserted as @p value when absent; the flag says whether it was inserted.
  /// The reference stays valid until the next insertion.
  std::pair<Value&, bool> tryEmplace(std::uint64_t key, const Value& value)
  {
    if (key == EmptyKey)
    {
      throw std::invalid_argument("pss::EdgeMap: the key ~0 is reserved");
    }
    if (2 * (Count + 1) > Slots.size())
    {
      rehash(Slots.empty() ? 16 : 2 * Slots.size());
    }
    std::size_t i = slotOf(key);
    while (Slots[i].first != EmptyKey)
    {
      if (Slots[i].first == key)
      {
        return { Slots[i].second, false };
      }
      i = (i + 1) & (Slots.size() - 1);
    }
    Slots[i] = { key, value };
    ++Count;
    return { Slots[i].second, true };
  }

  /// The value of @p key, default-constructed and inserted when absent.
  Value& operator[](std::uint64_t key) { return tryEmplace(key, Value{}).first; }

  /// The value of @p key, or nullptr.
  const Value* find(std::uint64_t key) const
  {
    if (Slots.empty() || key == EmptyKey)
    {
      return nullptr;
    }
    for (std::size_t i = slotOf(key);; i = (i + 1) & (Slots.size() - 1))
    {
      if (Slots[i].first == key)
      {
        return &Slots[i].second;
      }
      if (Slots[i].first == EmptyKey)
      {
        return nullptr;
      }
    }
  }
  Value* find(std::uint64_t key) { return const_cast<Value*>(static_cast<const EdgeMap&>(*this).find(key)); }

  /// Calls @p visit(key, value) for every entry, in the table's order.
  template <class Visit>
  void forEach(Visit&& visit)
  {
    for (auto& [key, value] : Slots)
    {
      if (key != EmptyKey)
      {
        visit(key, value);
      }
    }
  }

private:
  // Fibonacci hashing: the multiplication spreads consecutive vertex indices over the table.
  std::size_t slotOf(std::uint64_t key) const
  {
    return static_cast<std::size_t>((key * 0x9E3779B97F4A7C15ull) >> Shift);
  }

  void rehash(std::size_t capacity)
  {
    std::vector<std::pair<std::uint64_t, Value>> old(capacity, { EmptyKey, Value{} });
    old.swap(Slots);
    Shift = 64;
    for (std::size_t c = capacity; c > 1; c /= 2)
    {
      --Shift;
    }
    Count = 0;
    for (const auto& [key, value] : old)
    {
      if (key != EmptyKey)
      {
        tryEmplace(key, value);
      }
    }
  }

  std::vector<std::pair<std::uint64_t, Value>> Slots;
  std::size_t Count = 0;
  int Shift = 64;
};

} // namespace pss
