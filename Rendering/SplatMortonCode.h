// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SplatMortonCode.h
 * @brief the bit interleaving of Morton codes (the order of a Z curve), for sorts that keep
 * nearby points near one another in memory.
 */
#ifndef SplatMortonCode_h
#define SplatMortonCode_h

#include <cstdint>

namespace splat
{
/// The low 21 bits of x, bit i moved to bit 3 i: one axis of a 63-bit Morton code.
inline std::uint64_t SpreadBits(std::uint64_t x)
{
  x &= 0x1fffff;
  x = (x | x << 32) & 0x1f00000000ffffULL;
  x = (x | x << 16) & 0x1f0000ff0000ffULL;
  x = (x | x << 8) & 0x100f00f00f00f00fULL;
  x = (x | x << 4) & 0x10c30c30c30c30c3ULL;
  x = (x | x << 2) & 0x1249249249249249ULL;
  return x;
}
}

#endif
