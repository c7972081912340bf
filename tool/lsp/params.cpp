#include "lsp/params.h"

#include <fmt/format.h>

#include "lsp/transport.h"

namespace lwc::lsp {
namespace {

// The member at `path`, or none.
const json* find(const json& object, std::string_view path) {
  const json* at = &object;
  for (size_t begin = 0;;) {
    size_t dot = path.find('.', begin);
    std::string key(path.substr(begin, dot == std::string_view::npos ? std::string_view::npos : dot - begin));
    if (at->is_array() && !key.empty() && key.find_first_not_of("0123456789") == std::string::npos && key.size() < 10) {
      size_t index = std::stoul(key);
      if (index >= at->size()) return nullptr;
      at = &(*at)[index];
    } else {
      if (!at->is_object()) return nullptr;
      auto it = at->find(key);
      if (it == at->end()) return nullptr;
      at = &*it;
    }
    if (dot == std::string_view::npos) return at;
    begin = dot + 1;
  }
}

[[noreturn]] void wrong_type(std::string_view path, const char* wanted, const json& value) {
  throw BadParams(fmt::format("`{}` must be {}, not {}", path, wanted, type_in_words(value)));
}

}  // namespace

const json& member(const json& object, std::string_view path) {
  const json* found = find(object, path);
  if (found) return *found;
  // Said of the first part that is missing: "`position` is missing", not "`position.line` ...".
  std::string_view missing = path;
  for (size_t dot = path.find('.'); dot != std::string_view::npos; dot = path.find('.', dot + 1))
    if (!find(object, path.substr(0, dot))) {
      missing = path.substr(0, dot);
      break;
    }
  throw BadParams(fmt::format("`{}` is missing", missing));
}

std::string string_member(const json& object, std::string_view path) {
  const json& value = member(object, path);
  if (!value.is_string()) wrong_type(path, "a string", value);
  return value.get<std::string>();
}

long integer_member(const json& object, std::string_view path) {
  const json& value = member(object, path);
  if (!value.is_number_integer()) wrong_type(path, "an integer", value);
  // Clamped: positions and versions past a long's range mean "the end" as much as its largest value.
  if (value.is_number_unsigned() && value.get<unsigned long long>() > static_cast<unsigned long long>(LONG_MAX)) return LONG_MAX;
  return value.get<long>();
}

std::string string_member_or(const json& object, std::string_view path, const std::string& otherwise) {
  const json* found = find(object, path);
  return !found || found->is_null() ? otherwise : string_member(object, path);
}

long integer_member_or(const json& object, std::string_view path, long otherwise) {
  const json* found = find(object, path);
  return !found || found->is_null() ? otherwise : integer_member(object, path);
}

bool bool_member_or(const json& object, std::string_view path, bool otherwise) {
  const json* found = find(object, path);
  if (!found || found->is_null()) return otherwise;
  if (!found->is_boolean()) wrong_type(path, "true or false", *found);
  return found->get<bool>();
}

std::string plain_words(const std::exception& e) {
  if (dynamic_cast<const json::exception*>(&e)) return "the parameters do not have the members or types the method needs";
  if (dynamic_cast<const std::bad_alloc*>(&e)) return "there was not enough memory";
  // Our own errors are runtime errors that say what is wrong; any other is a bug in lwcport.
  if (dynamic_cast<const std::runtime_error*>(&e)) return e.what();
  return "an internal error in lwcport (please report it)";
}

}  // namespace lwc::lsp
