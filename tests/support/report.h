#pragma once
// Figures a test measures beside its assertions (per-region ratios, leak percentages, timings): printed
// only for a report (DYNGI_REPORT=1, as scripts/quality_report.sh sets it), so a test run's log holds
// its verdicts and failures, and docs/QUALITY.md's tables come from one place.
#include <cstdarg>
#include <cstdio>
#include <cstdlib>

namespace dyngi::test {

inline bool reporting() {
  static const bool on = [] {
    const char* v = std::getenv("DYNGI_REPORT");
    return v && *v && *v != '0';
  }();
  return on;
}

// printf to stdout when reporting.
__attribute__((format(printf, 1, 2))) inline void report(const char* format, ...) {
  if (!reporting()) return;
  va_list args;
  va_start(args, format);
  std::vprintf(format, args);
  va_end(args);
}

}  // namespace dyngi::test
