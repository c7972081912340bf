// lwc-host-fast-math: reassociation allowed where error-free transformations run: a fast-math
// flag in the compile command of a unit that splits positions into high/low floats or runs a
// TwoSum, and Metal shader compilation with fast math left on (its default) or turned on.
#include <clang/AST/ExprCXX.h>
#include <clang/ASTMatchers/ASTMatchers.h>

#include "host/check.h"

namespace lwc::host {

using namespace clang;
using namespace clang::ast_matchers;

namespace {

class FastMath : public Check {
 public:
  FastMath(const RuleInfo& rule, const Tables& tables, Reporter& out) : Check(rule, tables, out) {
    auto names = [&](const char* key) {
      Names n;
      for (const auto& g : rule.data.at(key)) n.globs.push_back(g.get<std::string>());
      return n;
    };
    error_free_ = names("error-free-functions");
    metal_switches_ = names("metal-switches");
    // The fast-math flag in effect: the last of the unit's flags that turn it on or off.
    const nlohmann::json& flags = rule.data.at("flags");
    const nlohmann::json& resets = rule.data.at("resets");
    for (const std::string& arg : out.command) {
      if (flags.contains(arg)) flag_ = arg;
      for (const auto& r : resets)
        if (arg == r.get<std::string>()) flag_.clear();
    }
  }

  void register_matchers(MatchFinder& finder) override {
    auto project = unless(isExpansionInSystemHeader());
    std::vector<llvm::StringRef> switches(metal_switches_.globs.begin(), metal_switches_.globs.end());  // plain names
    if (flag_.empty()) {
      // Without a fast-math flag only metal-cpp's switches can be at fault.
      finder.addMatcher(callExpr(project, callee(functionDecl(hasAnyName(llvm::ArrayRef<llvm::StringRef>(switches))).bind("callee"))).bind("call"), this);
      return;
    }
    // Where the unit splits or sums error-free: a call to such a function, or a low part
    // computed from a high one (`lo = (float)(x - hi)`).
    finder.addMatcher(callExpr(project, callee(functionDecl().bind("callee"))).bind("call"), this);
    finder.addMatcher(binaryOperator(project, hasOperatorName("-")).bind("minus"), this);
  }

  void run(const MatchFinder::MatchResult& match) override {
    const SourceManager& sm = *match.SourceManager;
    const LangOptions& lang = match.Context->getLangOpts();
    if (auto* call = match.Nodes.getNodeAs<CallExpr>("call")) {
      const auto* callee = match.Nodes.getNodeAs<FunctionDecl>("callee");
      std::string name = callee->getIdentifier() ? callee->getName().str() : "";
      if (name.empty()) return;
      // metal-cpp: setFastMathEnabled(true), setMathMode(MTL::MathModeFast) (2; 0 is safe, 1 relaxed).
      Expr::EvalResult value;
      if (metal_switches_.match(name) && call->getNumArgs() == 1 && call->getArg(0)->EvaluateAsInt(value, *match.Context)) {
        bool fast = name == "setMathMode" ? value.Val.getInt() == 2 : value.Val.getInt() != 0;
        if (fast) out_.report(rule_, sm, lang, call->getSourceRange(), {{"what", expand(rule_.data.at("forms").at("metal").get<std::string>(), {{"call", name}})}});
        return;
      }
      if (error_free_.match(name)) split_site(match, call);
      return;
    }
    if (auto* minus = match.Nodes.getNodeAs<BinaryOperator>("minus")) {
      auto* ref = dyn_cast<DeclRefExpr>(strip(minus->getRHS()));
      if (ref && ref->getDecl()->getIdentifier() && tables_.high_names.match(ref->getDecl()->getName().str())) split_site(match, minus);
    }
  }

 private:
  // The first split or error-free site of a unit compiled with fast math is where it is reported.
  void split_site(const MatchFinder::MatchResult& match, const Expr* at) {
    if (reported_ || flag_.empty()) return;
    reported_ = true;
    std::string form = expand(rule_.data.at("forms").at("flag").get<std::string>(), {{"flag", flag_}, {"reset", rule_.data.at("flags").at(flag_).get<std::string>()}});
    out_.report(rule_, *match.SourceManager, match.Context->getLangOpts(), at->getSourceRange(), {{"what", form}});
  }

  Names error_free_, metal_switches_;
  std::string flag_;  // "" when fast math is off for this unit
  bool reported_ = false;
};

}  // namespace

std::unique_ptr<Check> make_fast_math(const RuleInfo& rule, const Tables& tables, Reporter& out) {
  return std::make_unique<FastMath>(rule, tables, out);
}

}  // namespace lwc::host
