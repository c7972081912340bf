#include "lsp/json_reader.h"

#include <fmt/format.h>

namespace lwc::lsp {
namespace {

using nlohmann::json;

// UTF-8 (or, for a lone surrogate, generalised UTF-8) bytes of a code point.
void append_code_point(std::string& out, uint32_t cp) {
  if (cp < 0x80) {
    out += static_cast<char>(cp);
  } else if (cp < 0x800) {
    out += static_cast<char>(0xC0 | (cp >> 6));
    out += static_cast<char>(0x80 | (cp & 0x3F));
  } else if (cp < 0x10000) {
    out += static_cast<char>(0xE0 | (cp >> 12));
    out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (cp & 0x3F));
  } else {
    out += static_cast<char>(0xF0 | (cp >> 18));
    out += static_cast<char>(0x80 | ((cp >> 12) & 0x3F));
    out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (cp & 0x3F));
  }
}

class Reader {
 public:
  explicit Reader(std::string_view text) : text_(text) {}

  JsonRead read() {
    JsonRead r;
    try {
      skip_space();
      r.value = value(0);
      skip_space();
      if (at_ < text_.size()) fail("more text after the value");
    } catch (const Failure& f) {
      r.value = json();
      r.error = f.what;
    }
    return r;
  }

 private:
  struct Failure {
    std::string what;
  };

  [[noreturn]] void fail(const std::string& what) const { throw Failure{fmt::format("{} at byte {}", what, at_)}; }

  // The byte at the reading position, as words for an error.
  std::string found() const {
    if (at_ >= text_.size()) return "the end of the text";
    unsigned char c = static_cast<unsigned char>(text_[at_]);
    return c >= 0x20 && c < 0x7F ? fmt::format("'{}'", static_cast<char>(c)) : fmt::format("the byte 0x{:02X}", c);
  }

  void skip_space() {
    while (at_ < text_.size() && (text_[at_] == ' ' || text_[at_] == '\t' || text_[at_] == '\n' || text_[at_] == '\r')) ++at_;
  }

  bool next_is(char c) const { return at_ < text_.size() && text_[at_] == c; }

  // The next byte past spaces is `c` (the end of an object or array): it is read.
  bool closes(char c) {
    skip_space();
    if (!next_is(c)) return false;
    ++at_;
    return true;
  }

  void expect(char c, const char* what) {
    if (!next_is(c)) fail(fmt::format("{} expected, found {}", what, found()));
    ++at_;
  }

  bool literal(std::string_view word) {
    if (text_.substr(at_, word.size()) != word) return false;
    at_ += word.size();
    return true;
  }

  json value(int depth) {
    if (depth >= kMaxJsonDepth) fail(fmt::format("values nested deeper than {} levels", kMaxJsonDepth));
    if (at_ >= text_.size()) fail("a value expected, found the end of the text");
    char c = text_[at_];
    if (c == '{') return object(depth);
    if (c == '[') return array(depth);
    if (c == '"') return string();
    if (c == '-' || (c >= '0' && c <= '9')) return number();
    if (literal("true")) return true;
    if (literal("false")) return false;
    if (literal("null")) return nullptr;
    fail(fmt::format("a value expected, found {}", found()));
  }

  json object(int depth) {
    ++at_;
    json out = json::object();
    if (closes('}')) return out;
    for (;;) {
      skip_space();
      if (!next_is('"')) fail(fmt::format("a member name (a string) expected, found {}", found()));
      std::string key = string();
      skip_space();
      expect(':', "':' after a member name");
      skip_space();
      out[key] = value(depth + 1);
      if (closes('}')) return out;
      expect(',', "',' or '}' in an object");
    }
  }

  json array(int depth) {
    ++at_;
    json out = json::array();
    if (closes(']')) return out;
    for (;;) {
      skip_space();
      out.push_back(value(depth + 1));
      if (closes(']')) return out;
      expect(',', "',' or ']' in an array");
    }
  }

  uint32_t hex4() {
    uint32_t v = 0;
    for (int i = 0; i < 4; ++i, ++at_) {
      char c = at_ < text_.size() ? text_[at_] : '\0';
      int digit = c >= '0' && c <= '9' ? c - '0' : c >= 'a' && c <= 'f' ? c - 'a' + 10 : c >= 'A' && c <= 'F' ? c - 'A' + 10 : -1;
      if (digit < 0) fail(fmt::format("four hexadecimal digits expected after \\u, found {}", found()));
      v = v * 16 + static_cast<uint32_t>(digit);
    }
    return v;
  }

  std::string string() {
    ++at_;
    std::string out;
    for (;;) {
      size_t run = at_;  // the bytes up to the next quote, escape or control character are copied as they are
      while (run < text_.size() && text_[run] != '"' && text_[run] != '\\' && static_cast<unsigned char>(text_[run]) >= 0x20) ++run;
      out.append(text_, at_, run - at_);
      at_ = run;
      if (at_ >= text_.size()) fail("a string that does not end");
      char c = text_[at_];
      if (c == '"') {
        ++at_;
        return out;
      }
      if (c != '\\') fail(fmt::format("a control character ({}) inside a string", found()));
      ++at_;
      char e = at_ < text_.size() ? text_[at_] : '\0';
      const std::string_view simple = "\"\\/bfnrt", meaning = "\"\\/\b\f\n\r\t";
      if (size_t k = simple.find(e); e != '\0' && k != std::string_view::npos) {
        out += meaning[k];
        ++at_;
        continue;
      }
      if (e != 'u') fail(fmt::format("an escape JSON does not have (a backslash, then {})", found()));
      ++at_;
      uint32_t cp = hex4();
      bool high = cp >= 0xD800 && cp <= 0xDBFF;
      if (high && text_.substr(at_, 2) == "\\u") {
        size_t back = at_;
        at_ += 2;
        uint32_t low = hex4();
        if (low >= 0xDC00 && low <= 0xDFFF) {
          append_code_point(out, 0x10000 + ((cp - 0xD800) << 10) + (low - 0xDC00));
          continue;
        }
        at_ = back;  // a lone high surrogate; the escape after it is read on its own
      }
      if (cp >= 0xDC80 && cp <= 0xDCFF) out += static_cast<char>(cp - 0xDC00);  // an escaped byte
      else append_code_point(out, cp);
    }
  }

  // Numbers as JSON writes them; their value as nlohmann reads them (integers stay integers).
  json number() {
    size_t begin = at_;
    auto digits = [&] {
      size_t from = at_;
      while (at_ < text_.size() && text_[at_] >= '0' && text_[at_] <= '9') ++at_;
      return at_ > from;
    };
    if (next_is('-')) ++at_;
    if (next_is('0')) ++at_;
    else if (!digits()) fail(fmt::format("a digit expected, found {}", found()));
    if (next_is('.')) {
      ++at_;
      if (!digits()) fail(fmt::format("a digit expected after '.', found {}", found()));
    }
    if (next_is('e') || next_is('E')) {
      ++at_;
      if (next_is('+') || next_is('-')) ++at_;
      if (!digits()) fail(fmt::format("a digit expected in an exponent, found {}", found()));
    }
    json n = json::parse(text_.substr(begin, at_ - begin), nullptr, false);
    if (n.is_discarded()) {
      at_ = begin;
      fail("a number too large to hold");
    }
    return n;
  }

  std::string_view text_;
  size_t at_ = 0;
};

}  // namespace

JsonRead read_json(std::string_view text) { return Reader(text).read(); }

}  // namespace lwc::lsp
