#pragma once
// Counts heap allocations made by the benchmark binary: it defines malloc, calloc, realloc
// and the aligned allocators over glibc's own (allocation_counter.cc), so every allocation
// is seen, whether by operator new, Eigen, PCL or FLANN.

#include <cstddef>

namespace contour_reg::bench {

/// Allocations made so far.
std::size_t allocationCount();

}  // namespace contour_reg::bench
