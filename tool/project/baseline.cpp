#include "project/baseline.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <tuple>

#include "project/files.h"

namespace lwc {

namespace fs = std::filesystem;

std::string normalised_text(std::string_view text) {
  std::string out;
  bool blank = false;
  for (char c : text) {
    if (c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v') {
      blank = true;
      continue;
    }
    if (blank && !out.empty()) out += ' ';
    blank = false;
    out += c;
  }
  return out;
}

namespace {

// FNV-1a, 64 bits: stable across machines and versions, which is all a fingerprint needs.
uint64_t fnv1a(std::string_view bytes, uint64_t h = 0xcbf29ce484222325ull) {
  for (unsigned char c : bytes) h = (h ^ c) * 0x100000001b3ull;
  return h;
}

}  // namespace

std::vector<Fingerprinted> fingerprint_all(const std::vector<std::pair<std::string, std::string>>& findings) {
  std::map<std::pair<std::string, std::string>, int> seen;
  std::vector<Fingerprinted> out;
  for (const auto& [rule, text] : findings) {
    int occurrence = seen[{rule, text}]++;
    uint64_t h = fnv1a(rule);
    h = fnv1a(std::string_view("\0", 1), h);
    h = fnv1a(text, h);
    h = fnv1a(std::string_view("\0", 1), h);
    h = fnv1a(std::to_string(occurrence), h);
    out.push_back({rule, text, occurrence, fmt::format("{:016x}", h)});
  }
  return out;
}

namespace {

// UTF-8 to UTF-16 code units as a browser's (and Node's) decoder reads it: each maximal invalid
// subpart becomes one U+FFFD.
std::vector<uint16_t> utf16_units(std::string_view text) {
  std::vector<uint16_t> out;
  out.reserve(text.size());
  size_t i = 0;
  while (i < text.size()) {
    unsigned char b = static_cast<unsigned char>(text[i]);
    if (b < 0x80) {
      out.push_back(b);
      ++i;
      continue;
    }
    int need = 0;
    uint32_t cp = 0;
    unsigned char lower = 0x80, upper = 0xBF;
    if (b >= 0xC2 && b <= 0xDF) need = 1, cp = b & 0x1F;
    else if (b >= 0xE0 && b <= 0xEF) {
      need = 2, cp = b & 0x0F;
      if (b == 0xE0) lower = 0xA0;
      if (b == 0xED) upper = 0x9F;
    } else if (b >= 0xF0 && b <= 0xF4) {
      need = 3, cp = b & 0x07;
      if (b == 0xF0) lower = 0x90;
      if (b == 0xF4) upper = 0x8F;
    } else {
      out.push_back(0xFFFD);
      ++i;
      continue;
    }
    size_t j = i + 1;
    bool ok = true;
    for (int k = 0; k < need; ++k, ++j) {
      if (j >= text.size()) { ok = false; break; }
      unsigned char c = static_cast<unsigned char>(text[j]);
      if (c < lower || c > upper) { ok = false; break; }
      lower = 0x80, upper = 0xBF;
      cp = (cp << 6) | (c & 0x3F);
    }
    if (!ok) {
      out.push_back(0xFFFD);
      i = j;  // the valid prefix is one replacement; the offending byte is read again
      continue;
    }
    if (cp >= 0x10000) {
      cp -= 0x10000;
      out.push_back(static_cast<uint16_t>(0xD800 + (cp >> 10)));
      out.push_back(static_cast<uint16_t>(0xDC00 + (cp & 0x3FF)));
    } else {
      out.push_back(static_cast<uint16_t>(cp));
    }
    i = j;
  }
  return out;
}

}  // namespace

std::vector<std::string> line_hashes(std::string_view text) {
  constexpr int kBlock = 100;
  constexpr uint64_t kMod = 37;
  constexpr uint32_t kEnd = 65535;  // what the action feeds after the last character
  uint64_t first_mod = 1;
  for (int i = 0; i < kBlock; ++i) first_mod *= kMod;
  uint32_t window[kBlock] = {};
  int line_at[kBlock];
  std::fill(std::begin(line_at), std::end(line_at), -1);
  uint64_t hash = 0;
  int index = 0, line = 0;
  bool line_start = true, after_cr = false;
  std::map<uint64_t, int> counts;
  std::vector<std::string> out;
  auto emit = [&] {
    int n = ++counts[hash];
    if (static_cast<size_t>(line_at[index]) > out.size()) out.resize(line_at[index]);
    out[line_at[index] - 1] = fmt::format("{:x}:{}", hash, n);
    line_at[index] = -1;
  };
  auto update = [&](uint32_t c) {
    uint32_t begin = window[index];
    window[index] = c;
    hash = kMod * hash + c - first_mod * begin;  // wraps modulo 2^64, as the action's 64-bit Long does
    index = (index + 1) % kBlock;
  };
  auto take = [&](uint32_t c) {
    if (c == ' ' || c == '\t' || (after_cr && c == '\n')) {
      after_cr = false;
      return;
    }
    after_cr = c == '\r';
    if (c == '\r') c = '\n';
    if (line_at[index] != -1) emit();
    if (line_start) {
      line_start = false;
      line_at[index] = ++line;
    }
    if (c == '\n') line_start = true;
    update(c);
  };
  for (uint16_t u : utf16_units(text)) take(u);
  take(kEnd);
  for (int i = 0; i < kBlock; ++i) {
    if (line_at[index] != -1) emit();
    update(0);
  }
  return out;
}

Baseline Baseline::at(const fs::path& file) {
  Baseline b;
  b.file_ = fs::absolute(file).lexically_normal();
  b.dir_ = b.file_.parent_path();
  return b;
}

Baseline Baseline::read(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw std::runtime_error(file.string() + ": cannot read the baseline");
  std::stringstream text;
  text << in.rdbuf();
  auto fail = [&](const std::string& why) { throw std::runtime_error(fmt::format("{}: not a lwcport baseline: {}", file.string(), why)); };
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(text.str());
  } catch (const nlohmann::json::parse_error& e) {
    fail(fmt::format("invalid JSON at byte {}", e.byte));
  }
  if (!j.is_object() || j.value("lwcport-baseline", 0) != 1 || !j.contains("findings") || !j.at("findings").is_array())
    fail("expected {\"lwcport-baseline\": 1, \"findings\": [...]}");
  Baseline b = at(file);
  for (const auto& e : j.at("findings")) {
    if (!e.is_object() || !e.contains("path") || !e.contains("rule") || !e.contains("fingerprint") || !e.at("path").is_string() ||
        !e.at("rule").is_string() || !e.at("fingerprint").is_string())
      fail("each finding needs \"path\", \"rule\" and \"fingerprint\" strings");
    Entry entry{e.at("path"), {e.at("rule"), e.value("text", ""), e.value("occurrence", 0), e.at("fingerprint")}};
    b.by_key_[{entry.path, entry.finding.fingerprint}].push_back(b.entries_.size());
    b.entries_.push_back(std::move(entry));
  }
  b.used_.assign(b.entries_.size(), false);
  return b;
}

std::string Baseline::write(const fs::path& file, std::vector<Entry> entries) {
  std::sort(entries.begin(), entries.end(), [](const Entry& a, const Entry& b) {
    return std::tie(a.path, a.finding.rule, a.finding.text, a.finding.occurrence) <
           std::tie(b.path, b.finding.rule, b.finding.text, b.finding.occurrence);
  });
  nlohmann::ordered_json list = nlohmann::ordered_json::array();
  for (const Entry& e : entries) {
    // The text is for people reading the file; a long one is cut (the fingerprint holds all of it).
    std::string text = e.finding.text.size() > 120 ? e.finding.text.substr(0, 117) + "..." : e.finding.text;
    list.push_back({{"path", e.path}, {"rule", e.finding.rule}, {"text", text}, {"occurrence", e.finding.occurrence},
                    {"fingerprint", e.finding.fingerprint}});
  }
  nlohmann::ordered_json doc = {{"lwcport-baseline", 1}, {"findings", list}};
  std::string body = doc.dump(1, ' ', false, nlohmann::ordered_json::error_handler_t::replace) + "\n";
  std::error_code ec;
  if (file.has_parent_path()) fs::create_directories(file.parent_path(), ec);
  if (!fs::exists(file, ec)) return create_file(file, body);
  // Read and closed before the write: a file open anywhere, here too, is not replaced.
  return replace_file(file, read_file(file, SIZE_MAX).text, body);
}

std::string Baseline::key(const fs::path& file) const {
  std::error_code ec;
  return fs::absolute(file, ec).lexically_normal().lexically_relative(dir_).generic_string();
}

bool Baseline::take(const std::string& path, const std::string& fingerprint) {
  auto it = by_key_.find({path, fingerprint});
  if (it == by_key_.end()) return false;
  for (size_t i : it->second)
    if (!used_[i]) return used_[i] = true;
  return false;
}

bool Baseline::is_stale(size_t i, const std::set<std::string>& seen) const {
  std::error_code ec;
  return !used_[i] && (seen.count(entries_[i].path) || !fs::exists(dir_ / entries_[i].path, ec));
}

std::vector<Baseline::Entry> Baseline::stale(const std::set<std::string>& seen) const {
  std::vector<Entry> out;
  for (size_t i = 0; i < entries_.size(); ++i)
    if (is_stale(i, seen)) out.push_back(entries_[i]);
  return out;
}

std::vector<Baseline::Entry> Baseline::pruned(const std::set<std::string>& seen) const {
  std::vector<Entry> out;
  for (size_t i = 0; i < entries_.size(); ++i)
    if (!is_stale(i, seen)) out.push_back(entries_[i]);
  return out;
}

}  // namespace lwc
