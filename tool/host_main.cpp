// lwcport-host: the lwcport program with `lwcport host` built in (Clang's LibTooling linked).
#include <iostream>
#include <string>
#include <vector>

#include "cli/commands.h"

namespace lwc {
int run_host(const Options& o, std::ostream& out, std::ostream& err);
}

int main(int argc, char** argv) {
  lwc::host_command = lwc::run_host;
  std::vector<std::string> args(argv + 1, argv + argc);
  return lwc::run_cli(args, std::cout, std::cerr);
}
