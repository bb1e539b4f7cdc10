// Runs body(i) for i in [0, n) on a TBB arena of num_threads threads (0: all cores). Internal to the library.
#pragma once

#include <algorithm>
#include <cstddef>

#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

namespace rockfit::fitting {

template <class Body>
void ParallelFor(std::size_t n, int num_threads, const Body& body) {
  // More threads than cores only makes TBB warn; 0 means all cores.
  const int cores = tbb::info::default_concurrency();
  tbb::task_arena arena(num_threads > 0 ? std::min(num_threads, cores) : cores);
  arena.execute([&] { tbb::parallel_for(std::size_t{0}, n, [&](std::size_t i) { body(i); }); });
}

}  // namespace rockfit::fitting
