#include "fix/diff.h"

#include <fmt/format.h>

#include <algorithm>
#include <vector>

namespace lwc {

namespace {

// Lines with their endings, so the last line's missing newline is visible.
std::vector<std::string_view> split_lines(std::string_view text) {
  std::vector<std::string_view> lines;
  size_t at = 0;
  while (at < text.size()) {
    size_t nl = text.find('\n', at);
    size_t end = nl == std::string_view::npos ? text.size() : nl + 1;
    lines.push_back(text.substr(at, end - at));
    at = end;
  }
  return lines;
}

enum class Op { keep, remove, add };

// Myers' O(ND) shortest edit script over lines. Fixes change few lines, so D is small and
// keeping each round's frontier costs little.
std::vector<Op> edit_script(const std::vector<std::string_view>& a, const std::vector<std::string_view>& b) {
  const int n = static_cast<int>(a.size()), m = static_cast<int>(b.size()), max = n + m;
  std::vector<int> v(2 * max + 2, 0);
  std::vector<std::vector<int>> trace;
  int offset = max + 1;
  int found_d = 0;
  for (int d = 0; d <= max; ++d) {
    trace.push_back(v);
    bool done = false;
    for (int k = -d; k <= d; k += 2) {
      int x = (k == -d || (k != d && v[offset + k - 1] < v[offset + k + 1])) ? v[offset + k + 1] : v[offset + k - 1] + 1;
      int y = x - k;
      while (x < n && y < m && a[x] == b[y]) ++x, ++y;
      v[offset + k] = x;
      if (x >= n && y >= m) {
        done = true;
        break;
      }
    }
    if (done) {
      found_d = d;
      break;
    }
  }
  // Walk back through the saved frontiers.
  std::vector<Op> ops;
  int x = n, y = m;
  for (int d = found_d; d > 0; --d) {
    const std::vector<int>& pv = trace[d];
    int k = x - y;
    int prev_k = (k == -d || (k != d && pv[offset + k - 1] < pv[offset + k + 1])) ? k + 1 : k - 1;
    int prev_x = pv[offset + prev_k], prev_y = prev_x - prev_k;
    while (x > prev_x && y > prev_y) ops.push_back(Op::keep), --x, --y;
    ops.push_back(x == prev_x ? Op::add : Op::remove);
    x = prev_x, y = prev_y;
  }
  while (x > 0 && y > 0) ops.push_back(Op::keep), --x, --y;
  std::reverse(ops.begin(), ops.end());
  return ops;
}

void put_line(std::string& out, char mark, std::string_view line) {
  out += mark;
  out.append(line);
  if (line.empty() || line.back() != '\n') out += "\n\\ No newline at end of file\n";
}

}  // namespace

std::string unified_diff(std::string_view path, std::string_view before, std::string_view after, int context) {
  if (before == after) return "";
  auto a = split_lines(before), b = split_lines(after);
  std::vector<Op> ops = edit_script(a, b);
  std::string out = fmt::format("--- a/{}\n+++ b/{}\n", path, path);
  // Group changes into hunks: a change closer than 2*context lines to the previous one joins it.
  size_t i = 0;
  int ai = 0, bi = 0;  // line numbers (0-based) at ops[i]
  while (i < ops.size()) {
    if (ops[i] == Op::keep) {
      ++i, ++ai, ++bi;
      continue;
    }
    // Start of a hunk: back up `context` kept lines.
    size_t start = i;
    int back = 0;
    while (start > 0 && back < context && ops[start - 1] == Op::keep) --start, ++back;
    int a0 = ai - back, b0 = bi - back;
    size_t end = i;
    int ae = ai, be = bi;
    for (;;) {
      while (end < ops.size() && ops[end] != Op::keep) {
        if (ops[end] == Op::remove) ++ae;
        else ++be;
        ++end;
      }
      size_t run = end;
      while (run < ops.size() && ops[run] == Op::keep) ++run;
      if (run < ops.size() && static_cast<int>(run - end) <= 2 * context) {
        ae += static_cast<int>(run - end), be += static_cast<int>(run - end);
        end = run;
        continue;
      }
      int tail = std::min<int>(context, static_cast<int>(run - end));
      end += tail, ae += tail, be += tail;
      break;
    }
    auto range = [](int from, int count) {
      return count == 1 ? fmt::format("{}", from + 1) : fmt::format("{},{}", count ? from + 1 : from, count);
    };
    out += fmt::format("@@ -{} +{} @@\n", range(a0, ae - a0), range(b0, be - b0));
    int x = a0, y = b0;
    for (size_t k = start; k < end; ++k) {
      if (ops[k] == Op::keep) put_line(out, ' ', a[x++]), ++y;
      else if (ops[k] == Op::remove) put_line(out, '-', a[x++]);
      else put_line(out, '+', b[y++]);
    }
    i = end, ai = ae, bi = be;
  }
  return out;
}

}  // namespace lwc
