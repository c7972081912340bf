#pragma once
#include <map>
#include <string>

#include <clang/ASTMatchers/ASTMatchFinder.h>

#include "host/world.h"

namespace lwc::host {

// What a project's code gives a member that the host rules judge by its name (`view`, `position`):
// counted over every unit of a run, for the findings that rest on that name alone. A member given
// only values that hold no world translation (`cu.view = glm::lookAt(origin, ...)` in the camera's
// unit) is not what its name says, whatever the unit that uploads it can see.
struct GivenValues {
  unsigned world = 0;      // a world position or world matrix, known without trusting a name
  unsigned not_world = 0;  // camera-relative, or a matrix with no translation (anything else says nothing)
  // The project shows the member holding values with no world translation, and never one with it.
  bool overturn_name() const { return not_world > 0 && world == 0; }
};
using MemberValues = std::map<std::string, GivenValues>;  // by member_key

// How members are told apart across units: `CameraUniforms::view`.
std::string member_key(const clang::FieldDecl* field);
// The member a value's kind rests on by name alone, or "" (a local, a parameter, a call of the tables).
std::string name_rested_on(const Value& value);

// Counts the plain assignments (`out.view = view;`) and constructor initialisers (`view(v)`) of
// members judged by name, in the files a run reports on.
class MemberValueCollector : public clang::ast_matchers::MatchFinder::MatchCallback {
 public:
  explicit MemberValueCollector(const Tables& tables) : tables_(tables) {}
  void register_matchers(clang::ast_matchers::MatchFinder& finder);
  void run(const clang::ast_matchers::MatchFinder::MatchResult& match) override;
  MemberValues values;

 private:
  const Tables& tables_;
};

}  // namespace lwc::host
