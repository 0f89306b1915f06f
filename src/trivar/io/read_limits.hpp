#pragma once
// Limits the text readers check before they allocate: counts and degrees beyond them are not splines anyone
// writes and would only exhaust memory.

namespace trivar::io {

inline constexpr long kMaxCount = 100'000'000;
inline constexpr long kMaxDegree = 64;

}  // namespace trivar::io
