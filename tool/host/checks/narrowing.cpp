#include "host/checks/narrowing.h"
#include "host/checks/high_low.h"
#include "host/member_values.h"

#include <fmt/format.h>
#include <clang/AST/ExprCXX.h>
#include <clang/AST/ExprObjC.h>
#include <clang/ASTMatchers/ASTMatchers.h>
#include <clang/Lex/Lexer.h>

#include <algorithm>

namespace lwc::host {

using namespace clang;
using namespace clang::ast_matchers;

void register_narrowings(MatchFinder& finder, MatchFinder::MatchCallback* callback, const Tables& tables) {
  auto project = unless(isExpansionInSystemHeader());
  // A construction inside a cast is the cast's match.
  finder.addMatcher(cxxConstructExpr(project, unless(hasParent(explicitCastExpr()))).bind("narrowing"), callback);
  finder.addMatcher(explicitCastExpr(project).bind("narrowing"), callback);
  finder.addMatcher(implicitCastExpr(project, hasCastKind(CK_FloatingCast)).bind("narrowing"), callback);
  // A conversion helper: a free function from a double vector or matrix to its float twin (`ToFloat3(v)`).
  finder.addMatcher(callExpr(project, unless(cxxOperatorCallExpr()), unless(cxxMemberCallExpr()), argumentCountIs(1)).bind("narrowing"), callback);
  // A conversion operator (OpenSceneGraph's `Vec3d::operator Vec3f()`, implicit or in `osg::Vec3f(v)`).
  finder.addMatcher(cxxMemberCallExpr(project, callee(cxxConversionDecl()), unless(hasParent(explicitCastExpr())),
                                      unless(hasParent(implicitCastExpr(hasParent(explicitCastExpr())))))
                        .bind("narrowing"),
                    callback);
  // A compiler vector converted (`__builtin_convertvector(v, simd_float3)`, what Apple's `simd_float(v)` does).
  finder.addMatcher(convertVectorExpr(project).bind("narrowing"), callback);
  // A converting method: Eigen's `v.cast<float>()`.
  if (!tables.narrowing_methods.globs.empty()) {
    std::vector<StringRef> names(tables.narrowing_methods.globs.begin(), tables.narrowing_methods.globs.end());
    finder.addMatcher(cxxMemberCallExpr(project, callee(cxxMethodDecl(hasAnyName(names)))).bind("narrowing"), callback);
  }
}

bool narrowing_method_call(const Expr* e, const World& world) {
  auto* call = dyn_cast<CXXMemberCallExpr>(e);
  const CXXMethodDecl* method = call ? call->getMethodDecl() : nullptr;
  if (!method || !method->getIdentifier() || !world.tables().narrowing_methods.match(method->getName().str())) return false;
  const TemplateArgumentList* args = method->getTemplateSpecializationArgs();
  return args && args->size() >= 1 && args->get(0).getKind() == TemplateArgument::Type && world.scalar(args->get(0).getAsType()) == 'f';
}

namespace {

// The conversion inside `(float)X` or `static_cast<float>(X)` is the cast's match.
bool inside_explicit_cast(const Expr* e) {
  auto* implicit = dyn_cast<ImplicitCastExpr>(e);
  return implicit && implicit->isPartOfExplicitCast();
}

const Stmt* parent_of(ASTContext& context, const DynTypedNode& node, const Decl** decl = nullptr) {
  auto parents = context.getParents(node);
  if (parents.empty()) return nullptr;
  if (decl) *decl = parents[0].get<Decl>();
  return parents[0].get<Stmt>();
}

// The narrowed matrix is made into a 3x3 one on the spot (`glm::mat3(worldMatrix)` converts the
// dmat4 to a mat4 first): its rotation goes on, its translation does not.
bool made_linear(const Expr* narrowing, const World& world, ASTContext& context) {
  for (const Stmt* s = parent_of(context, DynTypedNode::create(*narrowing)); s; s = parent_of(context, DynTypedNode::create(*s))) {
    auto* e = dyn_cast<Expr>(s);
    if (!e || !isa<ImplicitCastExpr, MaterializeTemporaryExpr, CXXBindTemporaryExpr, ParenExpr, CXXConstructExpr, CXXFunctionalCastExpr>(e)) return false;
    if (world.is_linear_only(e->getType())) return true;
  }
  return false;
}

std::string where(const FieldDecl* field) {
  const RecordDecl* record = field->getParent();
  std::string of = record && record->getIdentifier() ? fmt::format(" of `{}`", record->getNameAsString()) : "";
  return fmt::format("`{}`{}", field->getNameAsString(), of);  // not `"`" + name`: GCC 12 warns of it, wrongly (-Wrestrict)
}

// What a member is to the GPU, in words ("" when nothing): a shader parameter when declared through
// one of the shader-parameter macros or in a struct named like a GPU block; else a member of a
// struct the unit uploads.
std::string gpu_member(const FieldDecl* field, ASTContext& context, const GpuSinks& sinks) {
  const SourceManager& sm = context.getSourceManager();
  for (SourceLocation at = field->getLocation(); at.isMacroID(); at = sm.getImmediateMacroCallerLoc(at))
    if (sinks.tables.gpu_macros.match(Lexer::getImmediateMacroName(at, sm, context.getLangOpts()).str())) return "shader parameter " + where(field);
  const RecordDecl* record = field->getParent();
  if (!record) return "";
  if (record->getIdentifier() && sinks.tables.gpu_structs.match(record->getName().str())) return "shader parameter " + where(field);
  return sinks.uploaded(record, context) ? "member " + where(field) + ", which this unit uploads" : "";
}

// The name an expression reads a pointer by: `frame.mapped`, `(char*)pData + offset`, `buffer->contents()`.
std::string pointer_name(const Expr* e) {
  for (;;) {
    e = e->IgnoreParenImpCasts();
    if (auto* c = dyn_cast<ExplicitCastExpr>(e)) e = c->getSubExpr();
    else if (auto* b = dyn_cast<BinaryOperator>(e); b && b->isAdditiveOp()) e = b->getLHS();
    else if (auto* smart = dyn_cast<CXXOperatorCallExpr>(e); smart && smart->getOperator() == OO_Arrow) e = smart->getArg(0);  // ptr<T>
    else break;
  }
  const NamedDecl* named = nullptr;
  if (auto* ref = dyn_cast<DeclRefExpr>(e)) named = ref->getDecl();
  else if (auto* member = dyn_cast<MemberExpr>(e)) named = member->getMemberDecl();
  else if (auto* call = dyn_cast<CallExpr>(e)) named = call->getDirectCallee();
  return named && named->getIdentifier() ? named->getName().str() : "";
}

// The struct an argument passes by address: `&globals`, `&objects[i]`, `vertices.data()` of a
// container of them (an address call of the tables on a template of the struct).
const RecordDecl* addressed_record(const Expr* e, const Tables& tables) {
  e = e->IgnoreParenImpCasts();
  if (auto* c = dyn_cast<ExplicitCastExpr>(e)) e = c->getSubExpr()->IgnoreParenImpCasts();
  if (auto* call = dyn_cast<CXXMemberCallExpr>(e); call && call->getMethodDecl() && call->getMethodDecl()->getIdentifier() &&
                                                    tables.address_calls.match(call->getMethodDecl()->getName().str())) {
    auto* container = dyn_cast_or_null<ClassTemplateSpecializationDecl>(call->getObjectType()->getAsCXXRecordDecl());
    if (!container || container->getTemplateArgs().size() == 0 || container->getTemplateArgs()[0].getKind() != TemplateArgument::Type) return nullptr;
    return container->getTemplateArgs()[0].getAsType()->getAsRecordDecl();
  }
  auto* address = dyn_cast<UnaryOperator>(e);
  if (!address || address->getOpcode() != UO_AddrOf) return nullptr;
  return address->getSubExpr()->getType()->getAsRecordDecl();
}

struct Sink {
  std::string what, field;
  bool gpu = true;  // false: a member of a struct the GPU does not read (scene data on the CPU)
  std::string through = "";  // the local it went through, if any
  const FieldDecl* decl = nullptr;  // the member, when stored in one
  std::vector<std::string> names = {};  // what an upload call calls the value: its uniform object, a string naming it
};

// What an upload call names the value it sends: the uniform object it is a method of
// (`worldDir->set(v)`) and the strings among its arguments (`setMat4("modelView", m)`).
std::vector<std::string> upload_names(const CallExpr* call) {
  std::vector<std::string> names;
  if (auto* member = dyn_cast<CXXMemberCallExpr>(call)) names.push_back(pointer_name(member->getImplicitObjectArgument()));
  for (const Expr* arg : call->arguments())
    if (auto* text = dyn_cast<StringLiteral>(arg->IgnoreParenImpCasts()); text && text->isOrdinary()) names.push_back(text->getString().str());
  return names;
}

// The GPU member an assignment's left side names.
std::optional<Sink> assigned_to(const Expr* lhs, ASTContext& context, const GpuSinks& sinks) {
  lhs = lhs->IgnoreParenImpCasts();
  if (auto* sub = dyn_cast<ArraySubscriptExpr>(lhs)) lhs = sub->getBase()->IgnoreParenImpCasts();
  if (auto* op = dyn_cast<CXXOperatorCallExpr>(lhs); op && op->getOperator() == OO_Subscript) lhs = op->getArg(0)->IgnoreParenImpCasts();
  auto* member = dyn_cast<MemberExpr>(lhs);
  if (!member) return std::nullopt;
  // `Params.Position.X = ...`: the component of a GPU member.
  if (auto* inner = dyn_cast<MemberExpr>(member->getBase()->IgnoreParenImpCasts()))
    if (auto* outer = dyn_cast<FieldDecl>(inner->getMemberDecl()))
      if (std::string gpu = gpu_member(outer, context, sinks); !gpu.empty()) return Sink{gpu, outer->getNameAsString()};
  auto* field = dyn_cast<FieldDecl>(member->getMemberDecl());
  if (!field) return std::nullopt;
  std::string gpu = gpu_member(field, context, sinks);
  if (gpu.empty()) return Sink{"member " + where(field), field->getNameAsString(), false, "", field};
  return Sink{gpu, field->getNameAsString(), true, "", field};
}

std::optional<Sink> sink_of(const Expr* e, ASTContext& context, const GpuSinks& sinks, int hops);

// Where a local's value goes: the first use of it that reaches a sink.
std::optional<Sink> through_local(const VarDecl* var, const Expr* from, ASTContext& context, const GpuSinks& sinks, int hops) {
  if (hops > 0 || !var->isLocalVarDecl()) return std::nullopt;
  const Stmt* body = nullptr;
  for (DynTypedNode node = DynTypedNode::create(*from);;) {
    auto parents = context.getParents(node);
    if (parents.empty()) return std::nullopt;
    node = parents[0];
    if (auto* f = node.get<FunctionDecl>()) {
      body = f->getBody();
      break;
    }
    if (auto* l = node.get<LambdaExpr>()) {
      body = l->getBody();
      break;
    }
  }
  if (!body) return std::nullopt;
  for (const BoundNodes& use : match(findAll(declRefExpr(to(varDecl(equalsNode(var)))).bind("use")), *body, context))
    if (auto sink = sink_of(use.getNodeAs<Expr>("use"), context, sinks, hops + 1)) {
      sink->what += " through `" + var->getNameAsString() + "`";
      sink->through = var->getNameAsString();
      return sink;
    }
  return std::nullopt;
}

std::optional<Sink> sink_of(const Expr* e, ASTContext& context, const GpuSinks& sinks, int hops) {
  const Tables& tables = sinks.tables;
  const Stmt* current = e;
  for (int step = 0; step < 16; ++step) {
    const Decl* decl = nullptr;
    const Stmt* parent = parent_of(context, DynTypedNode::create(*current), &decl);
    if (!parent) {
      if (auto* var = dyn_cast_or_null<VarDecl>(decl)) return through_local(var, e, context, sinks, hops);
      return std::nullopt;
    }
    if (auto* construct = dyn_cast<CXXConstructExpr>(parent)) {
      const CXXRecordDecl* record = construct->getConstructor()->getParent();
      if (record->getIdentifier() && tables.upload_constructors.match(record->getName().str()))
        return Sink{"the upload `" + record->getNameAsString() + "(...)`", ""};
    }
    if (isa<ParenExpr, ImplicitCastExpr, MaterializeTemporaryExpr, CXXBindTemporaryExpr, ExprWithCleanups, CXXFunctionalCastExpr,
            CXXConstructExpr, ExplicitCastExpr>(parent)) {
      current = parent;
      continue;
    }
    if (auto* unary = dyn_cast<UnaryOperator>(parent); unary && (unary->getOpcode() == UO_AddrOf || unary->getOpcode() == UO_Minus)) {
      current = parent;
      continue;
    }
    if (auto* bin = dyn_cast<BinaryOperator>(parent)) {
      if (bin->isAssignmentOp()) return bin->getRHS() == current ? assigned_to(bin->getLHS(), context, sinks) : std::nullopt;
      if (bin->isMultiplicativeOp() || bin->isAdditiveOp()) {
        current = parent;
        continue;
      }
      return std::nullopt;
    }
    if (auto* op = dyn_cast<CXXOperatorCallExpr>(parent)) {
      if (op->isAssignmentOp()) return op->getNumArgs() == 2 && op->getArg(1) == current ? assigned_to(op->getArg(0), context, sinks) : std::nullopt;
      OverloadedOperatorKind o = op->getOperator();
      if (o == OO_Plus || o == OO_Minus || o == OO_Star || o == OO_Slash) {
        current = parent;
        continue;
      }
      return std::nullopt;
    }
    if (auto* call = dyn_cast<CallExpr>(parent)) {
      const FunctionDecl* callee = call->getDirectCallee();
      std::string name = callee && callee->getIdentifier() ? callee->getName().str() : "";
      if (name.empty()) return std::nullopt;
      if (auto* method = dyn_cast<CXXMethodDecl>(callee); method && method->getParent()->getIdentifier())
        for (const auto& [methods, classes] : tables.upload_methods)
          if (methods.match(name) && classes.match(method->getParent()->getName().str()))
            return Sink{"the upload `" + method->getParent()->getNameAsString() + "::" + name + "`", "", true, "", nullptr, upload_names(call)};
      if (tables.upload_calls.match(name)) return Sink{"the upload call `" + name + "`", "", true, "", nullptr, upload_names(call)};
      if (tables.address_calls.match(name)) {
        current = parent;
        continue;
      }
      return std::nullopt;
    }
    if (auto* list = dyn_cast<InitListExpr>(parent)) {
      const RecordDecl* record = list->getType()->getAsRecordDecl();
      if (!record) return std::nullopt;
      unsigned index = 0;
      for (; index < list->getNumInits() && list->getInit(index) != current; ++index) {
      }
      unsigned at = 0;
      for (const FieldDecl* field : record->fields())
        if (at++ == index) {
          std::string gpu = gpu_member(field, context, sinks);
          return gpu.empty() ? std::nullopt : std::optional<Sink>(Sink{gpu, field->getNameAsString()});
        }
      return std::nullopt;
    }
    return std::nullopt;
  }
  return std::nullopt;
}

}  // namespace

std::optional<Upload> find_upload(const MatchFinder::MatchResult& match, const GpuSinks& sinks) {
  const Tables& tables = sinks.tables;
  const Expr* narrowing = match.Nodes.getNodeAs<Expr>("narrowing");
  if (!narrowing || inside_explicit_cast(narrowing)) return std::nullopt;
  ASTContext& context = *match.Context;
  World world(tables, context);
  // The type the value becomes, for its shape: a method's result is an expression of its own
  // (Eigen's CwiseUnaryOp), so the value's own type stands for it.
  QualType narrowed = narrowing->getType();
  bool by_method = narrowing_method_call(narrowing, world);
  if (!by_method && world.scalar(narrowed) != 'f') return std::nullopt;
  // `FVector3f(V)`, `static_cast<float>(X)`, `(float)X`, an implicit conversion; a cast to a
  // class type holds the construction that converts.
  const Expr* converted = narrowing;
  if (auto* cast = dyn_cast<CastExpr>(narrowing)) converted = cast->getSubExpr()->IgnoreImplicit();
  const Expr* value = converted;
  if (by_method) {
    value = cast<CXXMemberCallExpr>(narrowing)->getImplicitObjectArgument()->IgnoreImpCasts();  // not its base class (DenseBase)
    narrowed = value->getType();
  } else if (auto* conversion = dyn_cast<CXXMemberCallExpr>(converted); conversion && isa_and_nonnull<CXXConversionDecl>(conversion->getMethodDecl())) {
    value = conversion->getImplicitObjectArgument();
  } else if (auto* call = dyn_cast<CallExpr>(converted); call && converted == narrowing) {
    const FunctionDecl* callee = call->getDirectCallee();
    // Same shape in and out (a vector to a vector, not a length), and a name that does not say
    // it makes the value relative (`ToCameraRelative(P)`).
    if (!callee || !callee->getIdentifier() || call->getNumArgs() != 1 || isa<CXXMemberCallExpr, CXXOperatorCallExpr>(call) ||
        tables.position_not.match(callee->getName().str()) ||
        call->getType()->isBuiltinType() != call->getArg(0)->getType()->isBuiltinType())
      return std::nullopt;
    value = call->getArg(0);
  } else if (auto* vector = dyn_cast<ConvertVectorExpr>(converted)) {
    value = vector->getSrcExpr();
  } else if (auto* construct = dyn_cast<CXXConstructExpr>(converted)) {
    if (construct->getNumArgs() == 0 || construct->getConstructor()->isCopyOrMoveConstructor()) return std::nullopt;
    value = construct->getArg(0);
  } else if (converted == narrowing) {
    return std::nullopt;
  }
  if (!value || world.scalar(value->IgnoreParenImpCasts()->getType()) != 'd') return std::nullopt;
  Value what = world.classify(value);
  if (what.kind != Kind::position && what.kind != Kind::matrix && what.kind != Kind::model_view) return std::nullopt;
  if (world.exact_in_float(value) || world.named_in_float(what)) return std::nullopt;
  // A vector built from a matrix, or the reverse, is no narrowing of either; a 3x3 matrix made from
  // a world matrix keeps its rotation, not its translation.
  if ((what.kind != Kind::position) != world.is_matrix_type(narrowed) || world.is_linear_only(narrowed) ||
      made_linear(narrowing, world, context))
    return std::nullopt;
  std::optional<Sink> sink = sink_of(narrowing, context, sinks, 0);
  if (!sink) return std::nullopt;
  // The halves of a high/low split are narrowed on purpose (lwc-host-broken-split checks them).
  auto half = [&](const std::string& name) { return tables.high_names.match(name) || tables.low_names.match(name); };
  if (half(sink->field) || half(sink->through) || (sink->decl && writes_low_half(sink->decl, narrowing, context, tables))) return std::nullopt;
  // Where the value goes says it is no world value (`worldDir->set(...)`, a member `LightDirection`,
  // `setMat4("modelView", ...)`): the value's own name was trusted too far on the way.
  // A model-view product is camera-relative and goes by such names.
  sink->names.push_back(sink->field);
  const Names& said_not = tables.not_world(what.kind != Kind::position);
  if (what.kind != Kind::model_view &&
      std::any_of(sink->names.begin(), sink->names.end(), [&](const std::string& n) { return !n.empty() && said_not.match(n); }))
    return std::nullopt;
  bool vertex = sink->gpu && sink->decl && sinks.vertex_layout(sink->decl->getParent(), context);
  return Upload{narrowing, value, what, World::type_name(narrowed), sink->what, sink->field, sink->gpu, vertex};
}

bool GpuSinks::uploaded(const RecordDecl* record, ASTContext& context) const {
  if (!uploaded_) {
    uploaded_.emplace();
    for (const BoundNodes& b : match(findAll(callExpr(unless(isExpansionInSystemHeader())).bind("call")), context)) {
      const CallExpr* call = b.getNodeAs<CallExpr>("call");
      const FunctionDecl* callee = call->getDirectCallee();
      if (!callee || !callee->getIdentifier()) continue;
      std::string name = callee->getName().str();
      if (tables.copy_calls.match(name) && call->getNumArgs() >= 2 && tables.mapped_pointers.match(pointer_name(call->getArg(0)))) {
        if (const RecordDecl* r = addressed_record(call->getArg(1), tables)) uploaded_->insert(r->getCanonicalDecl());
      } else if (tables.upload_calls.match(name)) {
        for (const Expr* arg : call->arguments())
          if (const RecordDecl* r = addressed_record(arg, tables)) uploaded_->insert(r->getCanonicalDecl());
      }
    }
    // Objective-C: a message named by its first part (`[encoder setFragmentBytes:&light length:... atIndex:0]`).
    for (const BoundNodes& b : match(findAll(objcMessageExpr(unless(isExpansionInSystemHeader())).bind("message")), context)) {
      const ObjCMessageExpr* message = b.getNodeAs<ObjCMessageExpr>("message");
      if (message->getSelector().isNull() || !tables.upload_calls.match(message->getSelector().getNameForSlot(0).str())) continue;
      for (const Expr* arg : message->arguments())
        if (const RecordDecl* r = addressed_record(arg, tables)) uploaded_->insert(r->getCanonicalDecl());
    }
  }
  return uploaded_->count(record->getCanonicalDecl()) > 0;
}

bool GpuSinks::vertex_layout(const RecordDecl* record, ASTContext& context) const {
  if (!strides_) {
    strides_.emplace();
    auto sizes = match(findAll(unaryExprOrTypeTraitExpr(ofKind(UETT_SizeOf), unless(isExpansionInSystemHeader())).bind("size")), context);
    for (const BoundNodes& b : sizes) {
      const auto* size = b.getNodeAs<UnaryExprOrTypeTraitExpr>("size");
      const RecordDecl* sized = size->getTypeOfArgument()->getAsRecordDecl();
      if (!sized) continue;
      // Up through conversions (`(GLsizei)sizeof(V)`) to what takes the size.
      const Stmt* current = size;
      const Stmt* parent = parent_of(context, DynTypedNode::create(*current));
      while (parent && isa<ImplicitCastExpr, ParenExpr, ExplicitCastExpr>(parent)) current = parent, parent = parent_of(context, DynTypedNode::create(*parent));
      const NamedDecl* takes = nullptr;  // the call, or the member the size is stored in
      bool call = false;
      if (auto* c = dyn_cast_or_null<CallExpr>(parent); c && c->getCallee() != current) takes = c->getDirectCallee(), call = true;
      else if (auto* bin = dyn_cast_or_null<BinaryOperator>(parent); bin && bin->getOpcode() == BO_Assign && bin->getRHS() == current) {
        if (auto* m = dyn_cast<MemberExpr>(bin->getLHS()->IgnoreParenImpCasts())) takes = m->getMemberDecl();
      } else if (auto* construct = dyn_cast_or_null<CXXConstructExpr>(parent)) {  // Vulkan-Hpp: `VertexInputBindingDescription(0, sizeof(V))`
        for (unsigned i = 0; i < construct->getNumArgs() && i < construct->getConstructor()->getNumParams(); ++i)
          if (construct->getArg(i) == current) takes = construct->getConstructor()->getParamDecl(i);
      } else if (auto* list = dyn_cast_or_null<InitListExpr>(parent)) {  // `{0, sizeof(V), ...}`
        // The parents are the list as written, whose elements are not yet converted to the members' types.
        if (list->isSyntacticForm() && list->getSemanticForm()) list = list->getSemanticForm();
        unsigned index = 0;
        if (const RecordDecl* r = list->getType()->getAsRecordDecl())
          for (const FieldDecl* field : r->fields())
            if (index < list->getNumInits() && list->getInit(index++)->IgnoreParenImpCasts() == cast<Expr>(current)->IgnoreParenImpCasts()) takes = field;
      }
      if (!takes || !takes->getIdentifier()) continue;
      if ((call ? tables.stride_calls : tables.stride_members).match(takes->getName().str())) strides_->insert(sized->getCanonicalDecl());
    }
  }
  return strides_->count(record->getCanonicalDecl()) > 0;
}

Finding* report_upload(const Upload& up, const MatchFinder::MatchResult& match, const RuleInfo& rule, Reporter& out, const Tables& tables,
                       const std::string& port, Vars& vars) {
  World world(tables, *match.Context);
  vars = {{"narrowing", world.text(up.narrowing->getSourceRange())}, {"type", up.narrowing_type}, {"value", world.text(up.value.expr->getSourceRange())},
          {"sink", up.sink}, {"field", up.field.empty() ? "the uploaded value" : "`" + up.field + "`"}};
  Finding* finding = out.report(rule, *match.SourceManager, match.Context->getLangOpts(), up.narrowing->getSourceRange(), vars, name_rested_on(up.value));
  if (finding && !up.field.empty()) finding->facts = {{"shader-parameter", up.field}, {"port", port}};
  return finding;
}

std::optional<CameraInScope> camera_in_scope(const Expr* e, ASTContext& context, const Tables& tables) {
  const FunctionDecl* function = enclosing_function(e, context);
  if (!function) return std::nullopt;
  std::vector<const VarDecl*> candidates(function->param_begin(), function->param_end());
  if (function->getBody())
    for (const BoundNodes& b : match(findAll(varDecl().bind("v")), *function->getBody(), context)) {
      const VarDecl* v = b.getNodeAs<VarDecl>("v");
      if (context.getSourceManager().isBeforeInTranslationUnit(v->getLocation(), e->getBeginLoc())) candidates.push_back(v);
    }
  for (const VarDecl* v : candidates) {
    if (!v->getIdentifier()) continue;
    std::string type = World::type_name(v->getType());
    for (const Tables::View& view : tables.views) {
      if (!view.types.match(type)) continue;
      bool pointer = v->getType().getNonReferenceType()->isPointerType();
      std::string code = view.code;
      std::string name = v->getNameAsString() + (pointer ? "->" : ".");
      if (size_t at = code.find("{view}."); at != std::string::npos) code.replace(at, 7, name);
      return CameraInScope{code, view.subtract};
    }
  }
  return std::nullopt;
}

}  // namespace lwc::host
