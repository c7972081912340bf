// lwc-host-broken-split: a high/low split of a world value that loses the low part: the
// subtraction done in float (`lo = (float)x - hi`), a split of a value already float, or the two
// halves swapped where they are stored.
#include <clang/AST/ExprCXX.h>
#include <clang/ASTMatchers/ASTMatchers.h>
#include <clang/Lex/Lexer.h>

#include <cstring>

#include "host/check.h"

namespace lwc::host {

using namespace clang;
using namespace clang::ast_matchers;

namespace {

// The name an expression reads (a variable or a member), "" for anything else.
std::string name_of(const Expr* e) {
  e = strip(e);
  if (auto* ref = dyn_cast<DeclRefExpr>(e)) return ref->getDecl()->getIdentifier() ? ref->getDecl()->getName().str() : "";
  if (auto* member = dyn_cast<MemberExpr>(e))
    return member->getMemberDecl()->getIdentifier() ? member->getMemberDecl()->getName().str() : "";
  return "";
}

// A subtraction, as written or as an overloaded operator: its two sides.
bool subtraction(const Expr* e, const Expr*& left, const Expr*& right) {
  e = strip(e);
  if (auto* bin = dyn_cast<BinaryOperator>(e); bin && bin->getOpcode() == BO_Sub) {
    left = bin->getLHS(), right = bin->getRHS();
    return true;
  }
  if (auto* op = dyn_cast<CXXOperatorCallExpr>(e); op && op->getOperator() == OO_Minus && op->getNumArgs() == 2) {
    left = op->getArg(0), right = op->getArg(1);
    return true;
  }
  return false;
}

// What a narrowing converts: `(float)X`, `float(X)`, `static_cast<float>(X)`, `FVector3f(X)`.
const Expr* narrowed_from(const Expr* e, const World& world) {
  e = e->IgnoreParens();
  const Expr* inner = nullptr;
  if (auto* cast = dyn_cast<ExplicitCastExpr>(e)) inner = cast->getSubExpr()->IgnoreImplicit();
  else if (auto* implicit = dyn_cast<ImplicitCastExpr>(e); implicit && implicit->getCastKind() == CK_FloatingCast) inner = implicit->getSubExpr();
  else inner = e;
  if (auto* construct = dyn_cast<CXXConstructExpr>(inner); construct && construct->getNumArgs() >= 1) inner = construct->getArg(0);
  if (inner == e || world.scalar(inner->IgnoreParenImpCasts()->getType()) != 'd') return nullptr;
  return inner;
}

// The name without its high or low ending: `PositionHigh` and `PositionLow` share `Position`.
std::string stem(const std::string& name) {
  for (const char* end : {"HighPart", "LowPart", "_high", "_low", "High", "Low", "_hi", "_lo", "high", "low", "Hi", "Lo", "hi", "lo"})
    if (name.size() >= std::strlen(end) && name.compare(name.size() - std::strlen(end), std::string::npos, end) == 0)
      return name.substr(0, name.size() - std::strlen(end));
  return name;
}

// The variable a local was initialised by reading, through casts (`hi = (float)v` reads `v`).
std::string initialised_from(const Expr* e) {
  auto* ref = dyn_cast<DeclRefExpr>(strip(e));
  auto* var = ref ? dyn_cast<VarDecl>(ref->getDecl()) : nullptr;
  if (!var || !var->getInit()) return "";
  const Expr* init = strip(var->getInit());
  if (auto* cast = dyn_cast<ExplicitCastExpr>(init)) init = strip(cast->getSubExpr());
  if (auto* construct = dyn_cast<CXXConstructExpr>(init); construct && construct->getNumArgs() == 1) init = strip(construct->getArg(0));
  return name_of(init);
}

// A local made by narrowing a double (`hx = (float)x`): the name of what it narrows, "" otherwise.
std::string narrowed_source(const Expr* e, const World& world) {
  auto* ref = dyn_cast<DeclRefExpr>(strip(e));
  auto* var = ref ? dyn_cast<VarDecl>(ref->getDecl()) : nullptr;
  const Expr* from = var && var->getInit() ? narrowed_from(strip(var->getInit()), world) : nullptr;
  const Expr *left = nullptr, *right = nullptr;
  return from && !subtraction(from, left, right) ? name_of(from) : "";
}

// The name that says which half a store is: the first high or low name along `cb.PositionLow.y`.
std::string half_name(const Expr* e, const Tables& tables) {
  for (e = strip(e); e;) {
    std::string name = name_of(e);
    if (tables.high_names.match(name) || tables.low_names.match(name)) return name;
    if (auto* member = dyn_cast<MemberExpr>(e)) e = strip(member->getBase());
    else if (auto* sub = dyn_cast<ArraySubscriptExpr>(e)) e = strip(sub->getBase());
    else break;
  }
  return name_of(e);
}

// A local made as one half of a split: a high part narrowed from a double, or a low part that
// subtracts a high one.
bool made_as_half(const Expr* e, const World& world) {
  auto* ref = dyn_cast<DeclRefExpr>(strip(e));
  auto* var = ref ? dyn_cast<VarDecl>(ref->getDecl()) : nullptr;
  if (!var || !var->getInit()) return false;
  const Expr* init = strip(var->getInit());
  if (const Expr* from = narrowed_from(init, world)) {
    const Expr *left = nullptr, *right = nullptr;
    if (!subtraction(from, left, right)) return true;  // `hi = (float)x`
    init = from;
  }
  const Expr *left = nullptr, *right = nullptr;
  return subtraction(init, left, right) && world.tables().high_names.match(name_of(right));
}

class BrokenSplit : public Check {
 public:
  using Check::Check;
  void register_matchers(MatchFinder& finder) override {
    auto project = unless(isExpansionInSystemHeader());
    finder.addMatcher(varDecl(project, hasInitializer(expr().bind("value"))).bind("var"), this);
    finder.addMatcher(binaryOperator(project, isAssignmentOperator()).bind("assign"), this);
    finder.addMatcher(cxxOperatorCallExpr(project, isAssignmentOperator()).bind("assign"), this);
  }

  void run(const MatchFinder::MatchResult& match) override {
    if (in_template_pattern(match.Nodes)) return;
    World world(tables_, *match.Context);
    std::string target;
    const Expr* value = nullptr;
    QualType type;
    if (auto* var = match.Nodes.getNodeAs<VarDecl>("var")) {
      target = var->getIdentifier() ? var->getName().str() : "";
      value = match.Nodes.getNodeAs<Expr>("value");
      type = var->getType();
    } else if (auto* bin = match.Nodes.getNodeAs<BinaryOperator>("assign")) {
      if (bin->getOpcode() != BO_Assign) return;
      target = half_name(bin->getLHS(), tables_), value = bin->getRHS(), type = bin->getLHS()->getType();
    } else if (auto* op = match.Nodes.getNodeAs<CXXOperatorCallExpr>("assign")) {
      if (op->getOperator() != OO_Equal || op->getNumArgs() != 2) return;
      target = half_name(op->getArg(0), tables_), value = op->getArg(1), type = op->getArg(0)->getType();
    }
    bool member_target = false;
    if (auto* bin = match.Nodes.getNodeAs<BinaryOperator>("assign")) member_target = isa<MemberExpr>(bin->getLHS()->IgnoreParenImpCasts());
    if (auto* op = match.Nodes.getNodeAs<CXXOperatorCallExpr>("assign")) member_target = isa<MemberExpr>(op->getArg(0)->IgnoreParenImpCasts());
    if (target.empty() || !value || world.scalar(type) != 'f') return;
    bool low = tables_.low_names.match(target), high = tables_.high_names.match(target);
    // Swapped: a high part stored from the low one of the same value, or the reverse.
    std::string source = name_of(value);
    bool opposite = (low && tables_.high_names.match(source)) || (high && tables_.low_names.match(source));
    if (member_target && !source.empty() && opposite && (stem(source) == stem(target) || made_as_half(value, world))) {
      report(match, value, "swapped", {{"target", target}, {"source", source}});
      return;
    }
    if (high) return;
    const Expr *left = nullptr, *right = nullptr;
    const Expr* inner = strip(value);
    if (const Expr* from = narrowed_from(inner, world)) inner = from;  // `(float)(x - hi)`: its subtraction
    if (!subtraction(inner, left, right)) return;
    // The halves by their names (`PositionLow = .. - PositionHigh`), or by how the subtracted one
    // was made, whatever they are called (`lx = (float)x - hx` with `hx = (float)x`).
    bool named = low && tables_.high_names.match(name_of(right));
    std::string high_from = named ? "" : narrowed_source(right, world);
    if (!named && high_from.empty() && initialised_from(right).empty()) return;
    // In double: `x - hi` with x double (hi promoted), narrowed afterwards. Right.
    if (world.scalar(strip(inner)->getType()) == 'd') return;
    std::string high_name = name_of(right);
    if (const Expr* x = narrowed_from(left, world)) {
      if (!named && name_of(x) != high_from) return;  // two values narrowed, not one split
      // `(float)x - hi`: x rounded first, so the difference is the rounding of a rounding.
      Finding* f = report(match, inner, "narrowed-first", {{"target", target}, {"high", high_name}, {"value", world.text(x->getSourceRange())}});
      if (f && x->getType()->isBuiltinType()) {
        std::string type_text = World::type_name(type);
        std::string text = "(" + type_text + ")(" + world.text(x->getSourceRange()) + " - " + world.text(right->getSourceRange()) + ")";
        const SourceManager& sm = *match.SourceManager;
        out_.fix(*f, rule_, "subtract-in-double", {{"target", target}, {"rewrite", text}},
                 {{CharSourceRange::getTokenRange(strip(inner)->getSourceRange()), text}}, sm, match.Context->getLangOpts());
      } else if (f) {
        f->withheld.push_back("subtract-in-double: only for scalars (a vector needs its high part widened back to double)");
      }
      return;
    }
    // `hi = (float)v; lo = v - hi` with v float: hi is v, and the low part is always zero. (Other
    // float subtractions, Veltkamp's `a - (c - (c - a))` among them, are exact arithmetic, not this.)
    if (world.scalar(strip(left)->getType()) != 'f' || name_of(left).empty() || initialised_from(right) != name_of(left)) return;
    report(match, inner, "already-float", {{"target", target}, {"high", high_name}, {"value", world.text(left->getSourceRange())}});
  }

 private:
  Finding* report(const MatchFinder::MatchResult& match, const Expr* at, const std::string& form, Vars vars) {
    vars["what"] = rule_.data.at("forms").at(form).get<std::string>();
    for (auto& [key, text] : vars)
      if (key != "what") vars["what"] = expand(vars["what"], {{key, text}});
    return out_.report(rule_, *match.SourceManager, match.Context->getLangOpts(), at->getSourceRange(), vars);
  }
};

}  // namespace

std::unique_ptr<Check> make_broken_split(const RuleInfo& rule, const Tables& tables, Reporter& out) {
  return std::make_unique<BrokenSplit>(rule, tables, out);
}

}  // namespace lwc::host
