#pragma once
// The GI module's CPU work (Embree visibility, the path tracer, the benchmarks' batches) runs on one
// persistent pool of worker threads: oneTBB's (installed with Embree, which uses it too), so no call
// spawns or joins threads of its own and Embree and dyngi share the cores instead of oversubscribing.
#include <cstddef>
#include <functional>

namespace dyngi::gi {

// Calls body(b, e) over [begin, end) cut into chunks of about `grain`, on the pool's workers and the
// calling thread; returns when every chunk is done. `maxThreads` > 0 limits the threads used.
void parallelFor(size_t begin, size_t end, size_t grain, const std::function<void(size_t b, size_t e)>& body,
                 unsigned maxThreads = 0);

// The threads parallelFor uses at most (for reports such as "cpu (N threads)").
unsigned jobThreads();

}  // namespace dyngi::gi
