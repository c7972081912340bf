#pragma once
#include <string>
#include <string_view>
#include <vector>

namespace lwc {

// One segment of an expression's path: `GetPrimitiveData(Id).LocalToWorld` is
// [{GetPrimitiveData, call}, {LocalToWorld}].
struct PathSegment {
  std::string name;
  bool call = false;
};
using Path = std::vector<PathSegment>;

// A dotted path pattern from rule data: segments split on `.` (outside parentheses), each with
// `|` alternatives; an alternative may use `*` and `?` globs and end in `(..)` for a call.
class PathPattern {
 public:
  explicit PathPattern(std::string_view text);
  bool matches(const Path& path) const;
  bool matches_name(std::string_view name) const;  // a one-segment pattern against a bare name
  const std::string& text() const { return text_; }
  // Why no path can match the pattern (an empty name, a character no name has, a call written
  // other than `(..)`), or "" when one can.
  std::string problem() const;

 private:
  struct Alternative {
    std::string glob;
    bool call = false;
  };
  std::string text_;
  std::vector<std::vector<Alternative>> segments_;
};

bool glob_match(std::string_view glob, std::string_view text);

}  // namespace lwc
