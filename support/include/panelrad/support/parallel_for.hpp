#pragma once
// A parallel loop over independent indices whose failure report does not depend on the thread
// count or the schedule: of all indices whose body throws, the lowest one's exception is rethrown.
#include <exception>
#include <type_traits>

namespace panelrad {

/// Runs body(k) for k in [0, count) in parallel (OpenMP, dynamic schedule of `chunk` indices);
/// when some bodies throw, rethrows the exception of the lowest failing k once the loop is done
/// (deterministic whatever the thread count). Every index is visited: a failure does not cancel
/// the others, so the bodies must be independent of each other.
template <class I, class Body>
void parallel_for(I count, Body&& body, int chunk = 256) {
  static_assert(std::is_integral_v<I>, "parallel_for: the index must be an integer");
  std::exception_ptr failure;
  I failed = count;
#pragma omp parallel for schedule(dynamic, chunk)
  for (I k = 0; k < count; ++k) {
    try {
      body(k);
    } catch (...) {
#pragma omp critical(panelrad_parallel_for_failure)
      if (k < failed) {
        failed = k;
        failure = std::current_exception();
      }
    }
  }
  if (failure) std::rethrow_exception(failure);
}

}  // namespace panelrad
