#pragma once
// Cells and functions of one level of a tensor hierarchy as 64-bit keys: the per-direction indices packed with
// the last direction most significant, so sorting keys orders them lexicographically, u fastest (the order of
// a tensor spline's control points).
#include <cstdint>

#include "trivar/core/box.hpp"

namespace trivar {

using CellKey = std::uint64_t;

template <int D>
inline constexpr int kKeyBits = D == 2 ? 32 : 21;

template <int D>
inline CellKey pack_key(const Ints<D>& i) {
  CellKey key = 0;
  for (int k = D - 1; k >= 0; --k) key = (key << kKeyBits<D>) | static_cast<CellKey>(i[k]);
  return key;
}

template <int D>
inline Ints<D> unpack_key(CellKey key) {
  Ints<D> i;
  constexpr CellKey mask = (CellKey{1} << kKeyBits<D>) - 1;
  for (int k = 0; k < D; ++k, key >>= kKeyBits<D>) i[k] = static_cast<int>(key & mask);
  return i;
}

}  // namespace trivar
