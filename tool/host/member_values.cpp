#include "host/member_values.h"

#include <clang/AST/DeclCXX.h>
#include <clang/AST/ExprCXX.h>
#include <clang/ASTMatchers/ASTMatchers.h>

namespace lwc::host {

using namespace clang;
using namespace clang::ast_matchers;

std::string member_key(const FieldDecl* field) {
  const RecordDecl* record = field->getParent();
  if (!record || !field->getIdentifier()) return "";
  return record->getQualifiedNameAsString() + "::" + field->getName().str();
}

std::string name_rested_on(const Value& value) {
  auto* field = dyn_cast_or_null<FieldDecl>(value.named);
  return field ? member_key(field) : "";
}

void MemberValueCollector::register_matchers(MatchFinder& finder) {
  auto project = unless(isExpansionInSystemHeader());
  auto to_member = memberExpr(member(fieldDecl().bind("field")));
  finder.addMatcher(binaryOperator(project, hasOperatorName("="), hasLHS(ignoringParenImpCasts(to_member)), hasRHS(expr().bind("value"))), this);
  finder.addMatcher(cxxOperatorCallExpr(project, hasOverloadedOperatorName("="), argumentCountIs(2), hasArgument(0, ignoringParenImpCasts(to_member)),
                                        hasArgument(1, expr().bind("value"))),
                    this);
  finder.addMatcher(cxxConstructorDecl(project, forEachConstructorInitializer(
                                                    cxxCtorInitializer(forField(fieldDecl().bind("field")), withInitializer(expr().bind("value"))))),
                    this);
}

void MemberValueCollector::run(const MatchFinder::MatchResult& match) {
  const auto* field = match.Nodes.getNodeAs<FieldDecl>("field");
  const auto* value = match.Nodes.getNodeAs<Expr>("value");
  if (in_template_pattern(match.Nodes)) return;
  World world(tables_, *match.Context);
  Value named = world.by_name(field, field->getType(), value);
  if (named.kind == Kind::none) return;
  Value given = world.given(value);
  GivenValues& counts = values[member_key(field)];
  // A model-view product is camera-relative too: the translations cancelled in double.
  if (given.kind == Kind::relative || given.kind == Kind::model_view) ++counts.not_world;
  else if (given.kind == named.kind && !given.named) ++counts.world;
}

}  // namespace lwc::host
