// Work on many independent items (a crowd's pairs) in parallel, whose error is still the one a loop in
// order would give: the lowest item's that failed, whatever the threads and the order they ran in.
#pragma once

#include <cstddef>
#include <exception>
#include <vector>

#include <tbb/parallel_for.h>

namespace stirrup::rig {

// Calls f(i) for every i in [0, n) in parallel (in the calling thread's TBB arena), every item to the
// end, then rethrows the exception of the lowest i that threw, if any.
template <typename F>
void parallelForFirstError(std::size_t n, const F& f) {
  std::vector<std::exception_ptr> errors(n);
  tbb::parallel_for(std::size_t(0), n, [&](std::size_t i) {
    try {
      f(i);
    } catch (...) {
      errors[i] = std::current_exception();
    }
  });
  for (const std::exception_ptr& e : errors)
    if (e) std::rethrow_exception(e);
}

}  // namespace stirrup::rig
