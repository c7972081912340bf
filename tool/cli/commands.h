#pragma once
#include <iosfwd>
#include <string>
#include <vector>

namespace lwc {

// `lwcport ARGS...`: returns the exit code (0 clean, 1 findings at or above --fail-on, 2 usage
// or fatal error). Output goes to out, errors to err.
int run_cli(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);

}  // namespace lwc
