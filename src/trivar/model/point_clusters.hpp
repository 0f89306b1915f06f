#pragma once
// Points of a model merged within a distance (the V-points of gluing and of trimmed cells): two points closer
// than the tolerance are one, and so, transitively, are chains of such points.
#include <array>
#include <vector>

namespace trivar {

// Per point: its cluster, numbered in the order of the clusters' first points. O(n log n) plus the pairs
// within the tolerance along x.
std::vector<int> cluster_points(const std::vector<std::array<double, 3>>& points, double tolerance);

}  // namespace trivar
