// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SplatSortKey.h
 * @brief floats as unsigned integers of the same order, for sorts by depth that compare
 * integers (std::sort on 64-bit keys, parallel and radix sorts).
 */
#ifndef SplatSortKey_h
#define SplatSortKey_h

#include <cstdint>
#include <cstring>

namespace splat
{
/**
 * A float's bits as an unsigned key of the same order (negative floats included).
 */
inline std::uint32_t SortKey(float value)
{
  std::uint32_t bits;
  std::memcpy(&bits, &value, sizeof(bits));
  return bits & 0x80000000u ? ~bits : bits | 0x80000000u;
}

/**
 * A depth as a sort key in the high half and an index in the low half: sorting such keys
 * orders the items front to back, equal depths by index (std::stable_sort's order by depth).
 */
inline std::uint64_t DepthOrderKey(float depth, std::uint32_t index)
{
  return static_cast<std::uint64_t>(SortKey(depth)) << 32 | index;
}

/// The index that DepthOrderKey put in the key's low half.
inline std::uint32_t IndexOfKey(std::uint64_t key)
{
  return static_cast<std::uint32_t>(key);
}
}

#endif
