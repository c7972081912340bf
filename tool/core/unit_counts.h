#pragma once
#include <cstddef>

namespace lwc {

// What became of a run's C++ translation units (`lwcport host`), for its summaries.
struct UnitCounts {
  size_t analysed = 0;  // compiled, and every check ran
  size_t failed = 0;    // Clang could not compile them: findings in what it could read are reported
  size_t crashed = 0;   // the analysis crashed or ran out of time: nothing from them is reported
  size_t skipped = 0;   // not on disk (a source the build generates): not run
};

}  // namespace lwc
