#pragma once
// Memory a cell needs, estimated before the first cell so that an in-range but enormous setting
// (an 8192^2 viewport over 8192^2 textures, a cell complex at grid 32 and resolution 1024, six
// heightfield faces at 8192^2) is refused up front, naming the setting and the estimate, rather
// than exhausting the machine an hour in.
#include <cstddef>
#include <string>
#include <vector>

#include "config/config.h"
#include "run/cells.h"

namespace rl {

struct MemoryEstimate {
  double bytes = 0;
  std::string what;  // the largest part, in words
};

// The peak of one cell: the technique's and the truth's G-buffers and the render targets
// (about 300 bytes a pixel), the relief map on the CPU and the GPU (about 100 bytes a texel,
// per heightfield face), and a cell complex's domain-face maps (about 20 bytes a texel, an
// upper bound on the faces a surface can cross: 6 N^2 cells with 3 faces each) and its mesh
// after `subdivide` (about 120 bytes a triangle, 4^k times the file's), a generated curved
// base's triangles with the truth's prisms (about 3 KB each at its `segments`), and
// scene_shadows' map (36 bytes a texel with its op counts). An upper bound in the common case,
// not a measurement.
MemoryEstimate estimate_cell_memory(const SweepConfig& config, const Cell& cell);

// The machine's physical memory in bytes (0 when unknown).
double physical_memory_bytes();

// What this process may actually use: the least of the machine's memory, its address-space
// limit (RLIMIT_AS) and its cgroup's memory limit, and which of them that is, in words.
struct MemoryLimit {
  double bytes = 0;  // 0 when unknown
  std::string what;  // "this machine has", ...
};
MemoryLimit usable_memory();

// Throws ConfigError naming the scene, the viewport and texture resolution, the estimate and
// the memory this process may use when a cell would need more.
void refuse_cells_beyond_memory(const SweepConfig& config, const std::vector<Cell>& cells);

}  // namespace rl
