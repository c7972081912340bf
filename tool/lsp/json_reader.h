#pragma once
// The JSON of one client message, read as RFC 8259 says, but for text that is not UTF-8: a
// document's bytes reach the server as the client holds them, and are analysed as `lint` reads
// the same bytes in a file (nlohmann's parser refuses both forms below).
//  - Raw bytes that are not UTF-8 inside a string are kept as they are.
//  - An escaped lone surrogate (valid JSON) from U+DC80 to U+DCFF is the byte 0x80 to 0xFF it
//    stands for (the "surrogate escape" by which a client carries bytes it could not decode);
//    any other lone surrogate becomes its three-byte generalised UTF-8 form (ED A0 80 for
//    \ud800), which is no UTF-8 either. Both are counted as one UTF-16 unit (lsp/positions.h).
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

namespace lwc::lsp {

struct JsonRead {
  nlohmann::json value;
  std::string error;  // what is wrong with the text, in plain words, and where ("" when read)
};

// Values nest at most this deep (no message of the protocol nests near it): a bound on the stack.
constexpr int kMaxJsonDepth = 200;

JsonRead read_json(std::string_view text);

}  // namespace lwc::lsp
