#pragma once
// What the fast operator's files (fast_operator*.cpp) share: the block of rows of the coverings'
// lists, the chunk of the light parallel loops, and the rows held.
#include <panelrad/operator/fast_operator.hpp>

#include <utility>

namespace panelrad {

constexpr geometry::Index kRowBlock = 256;  // rows per block of the parallel covering traversal
// With V, the levels from a collocation point up to the cluster whose points share the sight of
// each root (cluster_sight.hpp): 16 points, a multiple of which divides kRowBlock.
constexpr int kSightLevels = 2;
// Indices per chunk of the loops whose bodies take nanoseconds (copies, frames). Every parallel
// loop of setup and product is scheduled dynamically: a virtual machine's processors do not run at
// one speed (a host's other tenants share their cores), and a static split waits for the slower.
constexpr geometry::Index kLightChunk = 8192;

/// [begin, end) of `rows`, end = -1 read as n; std::invalid_argument unless 0 <= begin <= end <= n.
std::pair<geometry::Index, geometry::Index> resolve_rows(const RowRange& rows, geometry::Index n);

}  // namespace panelrad
