#pragma once
#include "options.h"

namespace dyngi::sample {

// Exit codes: 0 success, 1 runtime failure (Vulkan, I/O), 2 bad input (options, scene file).
int runApp(const Options& options);

}  // namespace dyngi::sample
