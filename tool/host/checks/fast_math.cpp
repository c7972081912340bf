// lwc-host-fast-math: reassociation allowed where error-free transformations run: a fast-math
// flag in the compile command of a unit that splits positions into high/low floats or runs a
// TwoSum, and Metal shader compilation with fast math left on (its default) or turned on, in
// metal-cpp (C++) and in Objective-C.
#include <clang/AST/ExprCXX.h>
#include <clang/AST/ExprObjC.h>
#include <clang/AST/ParentMapContext.h>
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
    metal_compiles_ = names("metal-compile-calls");
    metal_options_ = names("metal-options-types");
    metal_fresh_ = names("metal-fresh-calls");
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
    std::vector<llvm::StringRef> compiles(metal_compiles_.globs.begin(), metal_compiles_.globs.end());
    finder.addMatcher(cxxMemberCallExpr(project, callee(cxxMethodDecl(hasAnyName(llvm::ArrayRef<llvm::StringRef>(compiles))))).bind("compile"), this);
    // Objective-C: `[device newLibraryWithSource:...]`, `[options setFastMathEnabled:YES]`, and a
    // property set (`options.mathMode = ...`), which Clang also gives as its setter's message.
    finder.addMatcher(objcMessageExpr(project).bind("message"), this);
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
    if (in_template_pattern(match.Nodes)) return;
    const SourceManager& sm = *match.SourceManager;
    const LangOptions& lang = match.Context->getLangOpts();
    if (auto* compile = match.Nodes.getNodeAs<CXXMemberCallExpr>("compile")) {
      if (auto form = default_options(*compile, *match.Context))
        out_.report(rule_, sm, lang, compile->getSourceRange(), {{"what", this->form(*form, compile->getMethodDecl()->getName().str(), false)}});
      return;
    }
    if (auto* message = match.Nodes.getNodeAs<ObjCMessageExpr>("message")) {
      objc_message(*message, match);
      return;
    }
    if (auto* call = match.Nodes.getNodeAs<CallExpr>("call")) {
      const auto* callee = match.Nodes.getNodeAs<FunctionDecl>("callee");
      std::string name = callee->getIdentifier() ? callee->getName().str() : "";
      if (name.empty()) return;
      // metal-cpp: setFastMathEnabled(true), setMathMode(MTL::MathModeFast or MathModeRelaxed).
      if (metal_switches_.match(name)) {
        std::optional<bool> fast = switch_is_fast(*call, *match.Context);
        if (fast && *fast) out_.report(rule_, sm, lang, call->getSourceRange(), {{"what", form("metal", name, false)}});
        return;
      }
      if (error_free_.match(name)) split_site(match, call);
      return;
    }
    if (auto* minus = match.Nodes.getNodeAs<BinaryOperator>("minus")) {
      // The high part taken from the value: a variable or a member (`P.High`), or an element of one.
      const Expr* rhs = strip(minus->getRHS());
      if (auto* element = dyn_cast<ArraySubscriptExpr>(rhs)) rhs = strip(element->getBase());
      const NamedDecl* high = nullptr;
      if (auto* ref = dyn_cast<DeclRefExpr>(rhs)) high = ref->getDecl();
      else if (auto* member = dyn_cast<MemberExpr>(rhs)) high = member->getMemberDecl();
      if (high && high->getIdentifier() && tables_.high_names.match(high->getName().str())) split_site(match, minus);
    }
  }

 private:
  // A Metal form's message, with the safe setting spelled for metal-cpp or for Objective-C.
  std::string form(const std::string& key, const std::string& call, bool objc) const {
    return expand(rule_.data.at("forms").at(key).get<std::string>(), {{"call", call}, {"safe", rule_.data.at("safe-settings").at(objc ? "objc" : "c++").get<std::string>()}});
  }

  // An Objective-C message: a switch set to fast math (sent, or a property set), or a compile
  // with default options.
  void objc_message(const ObjCMessageExpr& message, const MatchFinder::MatchResult& match) {
    if (message.getSelector().isNull()) return;
    std::string name = message.getSelector().getNameForSlot(0).str();
    ASTContext& context = *match.Context;
    if (metal_switches_.match(name)) {
      Expr::EvalResult value;
      if (message.getNumArgs() != 1 || !unwrapped(message.getArg(0))->EvaluateAsInt(value, context) || value.Val.getInt() == 0) return;
      // A property set (`options.fastMathEnabled = YES`) is reported as written, by its property's name.
      SourceRange range = message.getSourceRange();
      if (message.isImplicit())
        for (const auto& parent : context.getParents(message))
          if (auto* pseudo = parent.get<PseudoObjectExpr>()) {
            range = pseudo->getSyntacticForm()->getSourceRange();
            if (auto* set = dyn_cast<BinaryOperator>(pseudo->getSyntacticForm()))
              if (auto* property = dyn_cast<ObjCPropertyRefExpr>(set->getLHS()->IgnoreParens()); property && property->isExplicitProperty())
                name = property->getExplicitProperty()->getName().str();
          }
      out_.report(rule_, *match.SourceManager, context.getLangOpts(), range, {{"what", form("metal", name, true)}});
      return;
    }
    if (!metal_compiles_.match(name) || !message.getMethodDecl()) return;
    const ObjCMethodDecl* method = message.getMethodDecl();
    for (unsigned i = 0; i < message.getNumArgs() && i < method->param_size(); ++i) {
      QualType type = method->parameters()[i]->getType();
      if (!type->isObjCObjectPointerType() || !metal_options_.match(World::type_name(type->getPointeeType()))) continue;
      const Expr* options = message.getArg(i)->IgnoreParenImpCasts();
      std::optional<std::string> found;
      if (options->isNullPointerConstant(context, Expr::NPC_ValueDependentIsNotNull)) found = "metal-no-options";
      auto* ref = dyn_cast<DeclRefExpr>(options);
      auto* var = ref ? dyn_cast<VarDecl>(ref->getDecl()) : nullptr;
      if (var && var->isLocalVarDecl() && made_here_objc(var->getInit()) && left_fast_objc(*var, message, context)) found = "metal-default";
      if (found) out_.report(rule_, *match.SourceManager, context.getLangOpts(), message.getSourceRange(), {{"what", form(*found, name, true)}});
      return;
    }
  }

  // Through conversions and the opaque values of a property set, to the expression as written.
  static const Expr* unwrapped(const Expr* e) {
    for (;;) {
      e = e->IgnoreParenImpCasts();
      if (auto* opaque = dyn_cast<OpaqueValueExpr>(e); opaque && opaque->getSourceExpr()) e = opaque->getSourceExpr();
      else return e;
    }
  }

  // `[[MTLCompileOptions alloc] init]`, `[MTLCompileOptions new]`: messages that start at a fresh allocation.
  bool made_here_objc(const Expr* init) const {
    for (auto* message = dyn_cast_or_null<ObjCMessageExpr>(init ? init->IgnoreParenImpCasts() : nullptr); message;) {
      if (!message->getSelector().isNull() && metal_fresh_.match(message->getSelector().getNameForSlot(0).str())) return true;
      message = message->getReceiverKind() == ObjCMessageExpr::Instance ? dyn_cast<ObjCMessageExpr>(message->getInstanceReceiver()->IgnoreParenImpCasts()) : nullptr;
    }
    return false;
  }

  // Whether the options' function leaves fast math at its default: every use is a message to
  // them or a property of theirs other than a switch, or the compile. Any other use (handed to a
  // function, stored) may set them elsewhere: not judged.
  bool left_fast_objc(const VarDecl& var, const ObjCMessageExpr& compile, ASTContext& context) const {
    const FunctionDecl* function = enclosing_function(&compile, context);
    if (!function || !function->getBody()) return false;
    for (const auto& bound : match(findAll(declRefExpr(to(varDecl(equalsNode(&var)))).bind("ref")), *function->getBody(), context)) {
      const Stmt* use = bound.getNodeAs<DeclRefExpr>("ref");
      auto parents = context.getParents(*use);
      while (!parents.empty() && (parents[0].get<ImplicitCastExpr>() || parents[0].get<OpaqueValueExpr>())) {
        use = parents[0].get<Stmt>();
        parents = context.getParents(parents[0]);
      }
      bool accounted = false;
      for (const auto& parent : parents) {
        if (auto* message = parent.get<ObjCMessageExpr>()) {
          std::string name = message->getSelector().isNull() ? "" : message->getSelector().getNameForSlot(0).str();
          if (message->getReceiverKind() == ObjCMessageExpr::Instance && message->getInstanceReceiver() == use) {
            if (metal_switches_.match(name)) return false;  // a switch decides (and is reported itself when fast)
            accounted = true;
          } else if (message == &compile || metal_compiles_.match(name)) {
            accounted = true;
          }
        } else if (auto* pseudo = parent.get<PseudoObjectExpr>()) {
          // A property of theirs, read or set: a set is also its setter's message, to them.
          for (const Expr* semantic : pseudo->semantics())
            if (auto* setter = dyn_cast<ObjCMessageExpr>(semantic); setter && !setter->getSelector().isNull() &&
                                                                    setter->getReceiverKind() == ObjCMessageExpr::Instance &&
                                                                    metal_switches_.match(setter->getSelector().getNameForSlot(0).str()))
              if (auto* receiver = dyn_cast<DeclRefExpr>(unwrapped(setter->getInstanceReceiver())); receiver && receiver->getDecl() == &var) return false;
          accounted = true;
        } else if (parent.get<ObjCPropertyRefExpr>()) {
          accounted = true;
        }
      }
      if (!accounted) return false;
    }
    return true;
  }

  // Whether a metal-cpp switch turns reassociation on: setFastMathEnabled(true), or setMathMode
  // with anything but MathModeSafe (0): MathModeRelaxed (1) keeps Inf and NaN but reassociates
  // like MathModeFast (2). Unknown when the argument is not a constant.
  static std::optional<bool> switch_is_fast(const CallExpr& call, ASTContext& context) {
    Expr::EvalResult value;
    if (call.getNumArgs() != 1 || !call.getArg(0)->EvaluateAsInt(value, context)) return std::nullopt;
    return value.Val.getInt() != 0;
  }

  // Metal source compiled (`device->newLibrary(source, options, &error)`) with fast math left at
  // its default: no options ("metal-no-options"), or options made here (`CompileOptions::alloc()->init()`)
  // that nothing turns to safe math ("metal-default"). Options from elsewhere, or handed to other
  // code that may set them, are not judged.
  std::optional<std::string> default_options(const CXXMemberCallExpr& compile, ASTContext& context) const {
    const CXXMethodDecl* method = compile.getMethodDecl();
    for (unsigned i = 0; i < compile.getNumArgs() && i < method->getNumParams(); ++i) {
      QualType type = method->getParamDecl(i)->getType();
      if (!type->isPointerType() || !metal_options_.match(World::type_name(type->getPointeeType()))) continue;
      const Expr* options = compile.getArg(i)->IgnoreParenImpCasts();
      if (options->isNullPointerConstant(context, Expr::NPC_ValueDependentIsNotNull)) return "metal-no-options";
      auto* ref = dyn_cast<DeclRefExpr>(options);
      auto* var = ref ? dyn_cast<VarDecl>(ref->getDecl()) : nullptr;
      if (!var || !var->isLocalVarDecl() || !made_here(var->getInit())) return std::nullopt;
      return left_fast(*var, compile, context) ? std::optional<std::string>("metal-default") : std::nullopt;
    }
    return std::nullopt;
  }

  // `MTL::CompileOptions::alloc()->init()`: a call chain that starts at a fresh allocation.
  bool made_here(const Expr* init) const {
    for (auto* call = dyn_cast_or_null<CallExpr>(init ? init->IgnoreParenImpCasts() : nullptr); call;) {
      const FunctionDecl* callee = call->getDirectCallee();
      if (callee && callee->getIdentifier() && metal_fresh_.match(callee->getName().str())) return true;
      auto* member = dyn_cast<CXXMemberCallExpr>(call);
      call = member ? dyn_cast<CallExpr>(member->getImplicitObjectArgument()->IgnoreParenImpCasts()) : nullptr;
    }
    return false;
  }

  // Whether the options' function leaves fast math at its default: every use is a method of
  // theirs other than a switch (`release()`), or a compile call. Any other use (handed to a
  // function, stored) may set them elsewhere: not judged.
  bool left_fast(const VarDecl& var, const CXXMemberCallExpr& compile, ASTContext& context) const {
    const FunctionDecl* function = enclosing_function(&compile, context);
    if (!function || !function->getBody()) return false;
    auto refs = match(findAll(declRefExpr(to(varDecl(equalsNode(&var)))).bind("ref")), *function->getBody(), context);
    for (const auto& bound : refs) {
      auto* ref = bound.getNodeAs<DeclRefExpr>("ref");
      clang::DynTypedNode node = clang::DynTypedNode::create(*ref);
      auto parents = context.getParents(node);
      while (!parents.empty() && parents[0].get<ImplicitCastExpr>()) parents = context.getParents(parents[0]);
      if (parents.empty()) return false;
      if (auto* member = parents[0].get<MemberExpr>()) {
        auto* call = context.getParents(*member).empty() ? nullptr : context.getParents(*member)[0].get<CXXMemberCallExpr>();
        if (!call) return false;
        // A switch decides (and is reported itself when it turns fast math on).
        const CXXMethodDecl* method = call->getMethodDecl();
        if (method && method->getIdentifier() && metal_switches_.match(method->getName().str())) return false;
        continue;
      }
      auto* call = parents[0].get<CXXMemberCallExpr>();
      const CXXMethodDecl* method = call ? call->getMethodDecl() : nullptr;
      if (!method || !method->getIdentifier() || !metal_compiles_.match(method->getName().str())) return false;
    }
    return true;
  }

  // The first split or error-free site of a unit compiled with fast math is where it is reported.
  void split_site(const MatchFinder::MatchResult& match, const Expr* at) {
    if (reported_ || flag_.empty()) return;
    reported_ = true;
    std::string form = expand(rule_.data.at("forms").at("flag").get<std::string>(), {{"flag", flag_}, {"reset", rule_.data.at("flags").at(flag_).get<std::string>()}});
    out_.report(rule_, *match.SourceManager, match.Context->getLangOpts(), at->getSourceRange(), {{"what", form}});
  }

  Names error_free_, metal_switches_, metal_compiles_, metal_options_, metal_fresh_;
  std::string flag_;  // "" when fast math is off for this unit
  bool reported_ = false;
};

}  // namespace

std::unique_ptr<Check> make_fast_math(const RuleInfo& rule, const Tables& tables, Reporter& out) {
  return std::make_unique<FastMath>(rule, tables, out);
}

}  // namespace lwc::host
