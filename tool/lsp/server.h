#pragma once
// `lwcport lsp`: the language server face (LSP 3.17, JSON-RPC 2.0 over stdio). Thin over the same
// engine as the command line: a document's options come from its project (tool/project), its
// findings from analyze(), published as diagnostics with the document's version.
#include <istream>
#include <ostream>
#include <string>

namespace lwc {

struct ServerOptions {
  std::string log_file;  // every message's method and time, each analysis and error ("" for none)
};

// Serves one client until `exit` or the end of `in`; the process's exit code (0 after a
// `shutdown`, 1 otherwise, as the protocol asks).
int run_language_server(std::istream& in, std::ostream& out, const ServerOptions& options = {});

}  // namespace lwc
