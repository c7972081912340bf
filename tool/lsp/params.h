#pragma once
// The members of a message's params that a method needs, read with an error in plain words when
// one is missing or of another type ("`textDocument.uri` must be a string, not a number"); and any
// failure said in words for the client, never a library's own message.
#include <climits>
#include <exception>
#include <stdexcept>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

namespace lwc::lsp {

using nlohmann::json;

// The params are not what the method needs (JSON-RPC's invalid params).
struct BadParams : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// The member at a dotted path of `object` ("textDocument.uri"; an array's items by number:
// "contentChanges.0.text"); BadParams when it is missing.
const json& member(const json& object, std::string_view path);
std::string string_member(const json& object, std::string_view path);
long integer_member(const json& object, std::string_view path);

// An optional member: `otherwise` when it is missing (or null); BadParams when it is of another type.
std::string string_member_or(const json& object, std::string_view path, const std::string& otherwise);
long integer_member_or(const json& object, std::string_view path, long otherwise);
bool bool_member_or(const json& object, std::string_view path, bool otherwise);

// What went wrong, for the client and the log: our own errors as they are; a library's (JSON
// access, the standard library's checks) as plain words without its internals.
std::string plain_words(const std::exception& e);

}  // namespace lwc::lsp
