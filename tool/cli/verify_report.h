#pragma once
// How `lwcport verify` prints what it measured: a text table for people, JSON for tools.
#include <ostream>
#include <string>

#include <vector>

#include "verify/harness.h"
#include "verify/library_accuracy.h"
#include "verify/probes.h"

namespace lwc {

// "0", "1.02u^2", "0.98u": a relative error in the unit that reads best.
std::string format_relative_error(double relative);

void print_library_text(std::ostream& out, const std::string& device, const DriverProbes& probes,
                        const LibraryAccuracy& accuracy, size_t inputs);
void print_library_json(std::ostream& out, const std::string& device, const DriverProbes& probes,
                        const LibraryAccuracy& accuracy, size_t inputs);

// `wall_seconds`: the whole run, for the time split (functions per second; glslang, pipelines
// and JIT, dispatches). `explain`: each function's inputs, their roles and how they are filled.
void print_functions_text(std::ostream& out, const std::string& device, const DriverProbes& probes,
                          const std::vector<FunctionResult>& results, double wall_seconds, bool explain = false);
void print_functions_json(std::ostream& out, const std::string& device, const DriverProbes& probes,
                          const std::vector<FunctionResult>& results, double wall_seconds);

}  // namespace lwc
