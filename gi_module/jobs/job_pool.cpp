#include "dyngi/gi/job_pool.h"

#include <tbb/blocked_range.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>

namespace dyngi::gi {

void parallelFor(size_t begin, size_t end, size_t grain, const std::function<void(size_t, size_t)>& body, unsigned maxThreads) {
  if (end <= begin) return;
  auto run = [&] {
    tbb::parallel_for(tbb::blocked_range<size_t>(begin, end, std::max<size_t>(1, grain)),
                      [&](const tbb::blocked_range<size_t>& r) { body(r.begin(), r.end()); });
  };
  if (maxThreads == 0 || maxThreads >= jobThreads()) {
    run();
  } else {
    tbb::task_arena arena{static_cast<int>(maxThreads)};
    arena.execute(run);
  }
}

unsigned jobThreads() { return unsigned(std::max(1, tbb::info::default_concurrency())); }

}  // namespace dyngi::gi
