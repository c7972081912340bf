#pragma once
#include <filesystem>
#include <string>
#include <string_view>

namespace lwc {

// A path percent-encoded as a URI reference allows (SARIF locations, the editor's file: URIs).
std::string uri_encode(std::string_view path);
// A file: URI's path (or any URI's text) with its %XX escapes decoded.
std::filesystem::path path_of_uri(std::string_view uri);

}  // namespace lwc
