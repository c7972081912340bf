#include "host/world.h"

#include <clang/AST/DeclCXX.h>
#include <clang/AST/DeclTemplate.h>
#include <clang/AST/ExprCXX.h>
#include <clang/AST/ExprObjC.h>
#include <clang/AST/ParentMapContext.h>
#include <clang/ASTMatchers/ASTMatchFinder.h>
#include <clang/ASTMatchers/ASTMatchers.h>
#include <clang/Lex/Lexer.h>

#include <algorithm>
#include <optional>

#include "rules/rule.h"
#include "world/pattern.h"

namespace lwc::host {

using namespace clang;

bool Names::match(std::string_view name) const {
  return std::any_of(globs.begin(), globs.end(), [&](const std::string& g) { return glob_match(g, name); });
}

namespace {

// A list at `path` (keys separated by '/') of the built-in tables, and the same list of the additions.
Names names_at(const nlohmann::json& builtin, const nlohmann::json& additions, const std::string& path) {
  Names out;
  auto add = [&](const nlohmann::json& root) {
    const nlohmann::json* at = &root;
    for (size_t from = 0; from <= path.size();) {
      size_t slash = std::min(path.find('/', from), path.size());
      std::string key = path.substr(from, slash - from);
      if (!at->is_object() || !at->contains(key)) return;
      at = &at->at(key);
      from = slash + 1;
    }
    if (!at->is_array()) throw std::runtime_error("host." + path + " must be a list of names");
    for (const auto& g : *at) out.globs.push_back(g.get<std::string>());
  };
  add(builtin);
  add(additions);
  return out;
}

Names alternatives(const std::string& globs) {
  Names out;
  for (size_t from = 0; from <= globs.size();) {
    size_t bar = std::min(globs.find('|', from), globs.size());
    out.globs.push_back(globs.substr(from, bar - from));
    from = bar + 1;
  }
  return out;
}

}  // namespace

Tables Tables::load(const nlohmann::json& additions) {
  const nlohmann::json& b = host_world_data();
  Tables t;
  auto n = [&](const char* path) { return names_at(b, additions, path); };
  t.position_calls = n("world-positions/calls");
  t.position_names = n("world-positions/names");
  t.position_not = n("world-positions/not-names");
  t.position_from_matrix = n("world-positions/from-matrix-calls");
  t.matrix_calls = n("world-matrices/calls");
  t.matrix_names = n("world-matrices/names");
  t.matrix_not = n("world-matrices/not-names");
  t.matrix_keep = n("world-matrices/keep-calls");
  t.matrix_inverse = n("world-matrices/inverse-calls");
  t.from_world_calls = n("world-matrices/from-world-calls");
  t.from_world_names = n("world-matrices/from-world-names");
  t.transform_calls = n("world-matrices/transform-position-calls");
  t.inverse_transform_calls = n("world-matrices/inverse-transform-position-calls");
  t.look_at_calls = n("world-matrices/look-at-calls");
  t.translate_calls = n("world-matrices/translate-calls");
  t.compose_calls = n("world-matrices/compose-calls");
  t.offset_calls = n("camera-offsets/calls");
  t.offset_names = n("camera-offsets/names");
  t.double_scalars = n("double-scalars");
  t.float_scalars = n("float-scalars");
  t.matrix_types = n("matrix-types");
  t.linear_matrix_types = n("linear-matrix-types");
  t.row_vector_types = n("row-vector-matrix-types");
  t.gpu_macros = n("gpu-struct-macros");
  t.gpu_structs = n("gpu-struct-names");
  t.upload_calls = n("upload-calls");
  t.address_calls = n("address-calls");
  t.copy_calls = n("copy-calls");
  t.mapped_pointers = n("mapped-pointers");
  t.narrowing_methods = n("narrowing-methods");
  t.upload_constructors = n("upload-constructors");
  t.stride_calls = n("vertex-strides/calls");
  t.stride_members = n("vertex-strides/members");
  t.high_names = n("splits/high-names");
  t.low_names = n("splits/low-names");
  for (const nlohmann::json* root : {&b, &additions}) {
    if (root->contains("world-positions") && root->at("world-positions").contains("members-of"))
      for (const auto& m : root->at("world-positions").at("members-of"))
        t.position_members.emplace_back(m.at("member").get<std::string>(), alternatives(m.at("type").get<std::string>()));
    if (root->contains("upload-methods"))
      for (const auto& m : root->at("upload-methods"))
        t.upload_methods.emplace_back(alternatives(m.at("method").get<std::string>()), alternatives(m.at("class").get<std::string>()));
    if (root->contains("views"))
      for (const auto& v : root->at("views")) {
        bool origin = v.contains("camera-origin");
        t.views.push_back({alternatives(v.at("type").get<std::string>()), v.at(origin ? "camera-origin" : "preview-translation").get<std::string>(), origin});
      }
  }
  return t;
}

const Expr* strip(const Expr* e) {
  while (e) {
    const Expr* next = e->IgnoreParenImpCasts();
    if (auto* c = dyn_cast<ExprWithCleanups>(next)) next = c->getSubExpr();
    else if (auto* m = dyn_cast<MaterializeTemporaryExpr>(next)) next = m->getSubExpr();
    else if (auto* b = dyn_cast<CXXBindTemporaryExpr>(next)) next = b->getSubExpr();
    else if (auto* k = dyn_cast<CXXConstructExpr>(next); k && k->getNumArgs() == 1 && k->getConstructor()->isCopyOrMoveConstructor())
      next = k->getArg(0);
    if (next == e) return e;
    e = next;
  }
  return e;
}

std::string World::type_name(QualType type) {
  if (type.isNull()) return "";  // a parenthesised initialiser in a template's pattern has no type
  type = type.getNonReferenceType();
  if (type->isPointerType()) type = type->getPointeeType();
  type = type.getCanonicalType().getUnqualifiedType();
  if (auto* record = type->getAsCXXRecordDecl()) return record->getNameAsString();
  if (auto* builtin = type->getAs<BuiltinType>()) return builtin->getName(PrintingPolicy(LangOptions())).str();
  return type.getAsString();
}

char World::scalar(QualType type) const {
  for (int depth = 0; depth < 6 && !type.isNull(); ++depth) {
    type = type.getNonReferenceType().getCanonicalType();
    if (auto* array = dyn_cast<ConstantArrayType>(type.getTypePtr())) {
      type = array->getElementType();
      continue;
    }
    // A vector of the compiler's own (Apple's simd_double3, an ext_vector_type).
    if (auto* vector = type->getAs<VectorType>()) {
      type = vector->getElementType();
      continue;
    }
    if (auto* builtin = type->getAs<BuiltinType>()) {
      if (builtin->getKind() == BuiltinType::Double || builtin->getKind() == BuiltinType::LongDouble) return 'd';
      if (builtin->getKind() == BuiltinType::Float || builtin->getKind() == BuiltinType::Half || builtin->getKind() == BuiltinType::Float16)
        return 'f';
      return 0;
    }
    const RecordDecl* record = type->getAsRecordDecl();  // a C struct too
    if (!record || !record->getDefinition()) {
      std::string name = type_name(type);
      return tables_.double_scalars.match(name) ? 'd' : tables_.float_scalars.match(name) ? 'f' : 0;
    }
    std::string name = record->getNameAsString();
    if (tables_.double_scalars.match(name)) return 'd';
    if (tables_.float_scalars.match(name)) return 'f';
    // A template over its scalar (UE's TVector<double>, glm's vec<3, double>, Eigen's Matrix<double, 3, 1>).
    if (auto* spec = dyn_cast<ClassTemplateSpecializationDecl>(record)) {
      bool found = false;
      for (const TemplateArgument& arg : spec->getTemplateArgs().asArray())
        if (arg.getKind() == TemplateArgument::Type) {
          type = arg.getAsType();
          found = true;
          break;
        }
      if (found) continue;
    }
    // Else its first data member (a struct of doubles, a matrix of double rows).
    auto field = record->getDefinition()->field_begin();
    if (field == record->getDefinition()->field_end()) return 0;
    type = field->getType();
  }
  return 0;
}

std::vector<int64_t> template_numbers(QualType type) {
  std::vector<int64_t> numbers;
  if (type.isNull()) return numbers;
  if (auto* spec = dyn_cast_or_null<ClassTemplateSpecializationDecl>(type.getNonReferenceType()->getAsCXXRecordDecl()))
    for (const TemplateArgument& a : spec->getTemplateArgs().asArray())
      if (a.getKind() == TemplateArgument::Integral) numbers.push_back(a.getAsIntegral().getExtValue());
  return numbers;
}

bool World::is_matrix_type(QualType type) const {
  // Eigen's Matrix<double, 3, 1> is a vector: a template whose first two numbers are extents, one of them 1.
  std::vector<int64_t> extents = template_numbers(type);
  if (extents.size() >= 2 && (extents[0] == 1 || extents[1] == 1)) return false;
  return tables_.matrix_types.match(type_name(type));
}

int World::components(QualType type) {
  // What a pointer points to (`origin->x` of a game object reached by pointer); a C struct is a record too.
  if (type.isNull()) return -1;
  type = type.getNonReferenceType();
  if (type->isPointerType()) type = type->getPointeeType();
  if (auto* vector = type->getAs<VectorType>()) return int(vector->getNumElements());
  const RecordDecl* record = type->getAsRecordDecl();
  if (!record || !record->getDefinition()) return -1;
  std::vector<int64_t> extents = template_numbers(type);
  if (extents.size() >= 2 && (extents[0] == 1 || extents[1] == 1)) return int(extents[0] * extents[1]);
  if (!extents.empty()) return int(extents[0]);
  return numbers_in(record->getDefinition());
}

int World::numbers_in(const RecordDecl* record) {
  int count = 0;
  for (const FieldDecl* field : record->fields()) {
    QualType t = field->getType().getCanonicalType();
    int n = 1;
    if (auto* array = dyn_cast<ConstantArrayType>(t.getTypePtr())) {
      n = int(array->getSize().getSExtValue());
      t = array->getElementType();
    }
    // UE 5's `union { struct { T X, Y; }; T XY[2]; }`: the members of an anonymous struct are the
    // record's own; those of a union all view the same numbers, so its first one counts.
    if (field->isAnonymousStructOrUnion()) n = numbers_in(t->getAsRecordDecl());
    else if (t->isRecordType() || t->isVectorType()) return -1;
    else if (!t->isRealFloatingType()) return 0;
    if (n <= 0) return n;
    count += n;
    if (record->isUnion()) break;
  }
  return count == 0 ? -1 : count;
}

bool World::may_hold_position(QualType type) {
  int n = components(type);
  return n < 0 || n == 3 || n == 4;
}

bool World::is_linear_only(QualType type) const {
  if (type.isNull()) return false;
  if (tables_.linear_matrix_types.match(type_name(type))) return true;  // glm 0.9.8's tmat3x3, OSG's Matrix3
  if (!is_matrix_type(type)) return false;
  std::vector<int64_t> extents = template_numbers(type);
  if (extents.size() >= 2) return extents[0] <= 3 && extents[1] <= 3;
  const CXXRecordDecl* record = type.getNonReferenceType()->getAsCXXRecordDecl();
  int n = record && record->hasDefinition() ? numbers_in(record->getDefinition()) : -1;
  return n > 0 && n <= 9;
}

std::vector<APValue> World::constant_parts(const Expr* e) const {
  e = strip(e);
  // Through members (glm's `x` is a member of an anonymous union) to the object.
  while (auto* member = dyn_cast<MemberExpr>(e)) {
    if (isa<CXXMethodDecl>(member->getMemberDecl())) return {};
    e = strip(member->getBase());
  }
  if (auto* ref = dyn_cast<DeclRefExpr>(e)) {
    auto* var = dyn_cast<VarDecl>(ref->getDecl());
    if (!var || !var->isLocalVarDecl() || !var->getInit() || changed(var)) return {};
    e = strip(var->getInit());
  }
  if (auto* cast = dyn_cast<CXXFunctionalCastExpr>(e)) e = strip(cast->getSubExpr());
  std::vector<const Expr*> parts;
  if (auto* construct = dyn_cast<CXXConstructExpr>(e)) parts.assign(construct->arg_begin(), construct->arg_end());
  else if (auto* list = dyn_cast<InitListExpr>(e)) parts.assign(list->inits().begin(), list->inits().end());
  else parts.push_back(e);
  std::vector<APValue> values;
  for (const Expr* part : parts) {
    Expr::EvalResult result;
    if (part->isValueDependent() || !part->EvaluateAsRValue(result, context_) || result.HasSideEffects ||
        !(result.Val.isInt() || result.Val.isFloat()))
      return {};
    values.push_back(result.Val);
  }
  return values;
}

bool World::exact_in_float(const Expr* e) const {
  std::vector<APValue> parts = constant_parts(e);
  for (const APValue& part : parts) {
    llvm::APFloat as_float(llvm::APFloat::IEEEsingle());
    llvm::APFloat::opStatus status;
    bool lost = false;
    if (part.isInt()) status = as_float.convertFromAPInt(part.getInt(), part.getInt().isSigned(), llvm::APFloat::rmNearestTiesToEven);
    else status = (as_float = part.getFloat()).convert(llvm::APFloat::IEEEsingle(), llvm::APFloat::rmNearestTiesToEven, &lost);
    if (status != llvm::APFloat::opOK || lost) return false;
  }
  return !parts.empty();
}

bool World::is_origin(const Expr* e) const {
  std::vector<APValue> parts = constant_parts(e);
  return !parts.empty() && std::all_of(parts.begin(), parts.end(), [](const APValue& v) { return v.isInt() ? v.getInt().isZero() : v.getFloat().isZero(); });
}

bool World::is_row_vector(QualType type) const { return tables_.row_vector_types.match(type_name(type)); }

std::string World::text(SourceRange range) const { return source_text(range, context_); }

std::string source_text(CharSourceRange range, ASTContext& context) {
  CharSourceRange file = Lexer::makeFileCharRange(range, context.getSourceManager(), context.getLangOpts());
  return file.isInvalid() ? "" : Lexer::getSourceText(file, context.getSourceManager(), context.getLangOpts()).str();
}

std::string source_text(SourceRange range, ASTContext& context) { return source_text(CharSourceRange::getTokenRange(range), context); }

const FunctionDecl* enclosing_function(const Stmt* s, ASTContext& context) {
  for (clang::DynTypedNode node = clang::DynTypedNode::create(*s);;) {
    auto parents = context.getParents(node);
    if (parents.empty()) return nullptr;
    node = parents[0];
    if (auto* f = node.get<FunctionDecl>()) return f;
  }
}

Value World::by_name(const NamedDecl* decl, QualType type, const Expr* e) const {
  if (!decl || !decl->getIdentifier()) return {};
  std::string name = decl->getName().str();
  if (tables_.offset_names.match(name)) return {Kind::camera_offset, e, false, false, decl};
  if (is_matrix_type(type)) {
    if (tables_.matrix_not.match(name)) return {};
    if (tables_.matrix_names.match(name)) return {Kind::matrix, e, false, false, decl};
    if (tables_.from_world_names.match(name)) return {Kind::matrix, e, true, false, decl};
    return {};
  }
  // A lone number named as a position is a position on some axis (a scroll wheel's, a slider's, a
  // time line's); a world position's component is reached through its vector (`position.x`). Two
  // numbers named as a position are a point on a screen or a canvas (a pointer's `pos`), and a
  // record that is no vector is a record (a GPS fix with its speed and satellite count).
  if (type.getNonReferenceType()->isArithmeticType() || !may_hold_position(type)) return {};
  if (tables_.position_names.match(name) && !tables_.position_not.match(name)) return {Kind::position, e, false, false, decl};
  return {};
}

Value World::transformed(Value matrix, const Expr* point, bool inverse, const Expr* e) const {
  if (matrix.kind != Kind::matrix || !point->getType()->isRecordType()) return {};
  // Into the world from another frame: a world position, unless the point is a direction (w = 0).
  if (matrix.from_world == inverse) return is_direction(point) ? Value{} : derived(Kind::position, e, matrix);
  return derived(Kind::relative, e, matrix);  // out of the world: view space, or an object's own frame
}

bool World::names_a_value(const Expr* e) {
  e = strip(e);
  return isa<DeclRefExpr, MemberExpr, ArraySubscriptExpr>(e) || (isa<CallExpr>(e) && !isa<CXXOperatorCallExpr>(e));
}

bool World::is_direction(const Expr* point) {
  auto* construct = dyn_cast<CXXConstructExpr>(strip(point));
  if (auto* cast = dyn_cast<CXXFunctionalCastExpr>(strip(point))) construct = dyn_cast<CXXConstructExpr>(strip(cast->getSubExpr()));
  if (!construct || construct->getNumArgs() < 2) return false;
  const Expr* w = strip(construct->getArg(construct->getNumArgs() - 1));
  if (auto* f = dyn_cast<FloatingLiteral>(w)) return f->getValue().isZero();
  if (auto* i = dyn_cast<IntegerLiteral>(w)) return i->getValue().isZero();
  return false;
}

bool World::is_transform(const Expr* e) const {
  for (e = strip(e); e;) {
    if (auto* cast = dyn_cast<CXXFunctionalCastExpr>(e)) e = strip(cast->getSubExpr());
    else if (auto* c = dyn_cast<CXXConstructExpr>(e); c && c->getNumArgs() == 1 && !isa<CXXTemporaryObjectExpr>(e)) e = strip(c->getArg(0));
    else break;
  }
  if (auto* op = dyn_cast_or_null<CXXOperatorCallExpr>(e); op && op->getOperator() == OO_Star && op->getNumArgs() == 2)
    for (int i : {0, 1})
      if (is_matrix_type(op->getArg(i)->getType()) && !is_matrix_type(op->getArg(1 - i)->getType()))
        return op->getArg(1 - i)->getType()->isRecordType();
  if (auto* call = dyn_cast_or_null<CXXMemberCallExpr>(e); call && call->getMethodDecl() && call->getMethodDecl()->getIdentifier()) {
    std::string name = call->getMethodDecl()->getName().str();
    return tables_.transform_calls.match(name) || tables_.inverse_transform_calls.match(name);
  }
  return false;
}

bool World::builds_matrix(const Expr* e) const {
  auto* call = dyn_cast_or_null<CallExpr>(strip(e));
  const FunctionDecl* callee = call && !isa<CXXMemberCallExpr, CXXOperatorCallExpr>(call) ? call->getDirectCallee() : nullptr;
  if (!callee || !callee->getIdentifier() || !is_matrix_type(call->getType())) return false;
  std::string name = callee->getName().str();
  if (tables_.translate_calls.match(name) || tables_.look_at_calls.match(name)) return true;
  return tables_.compose_calls.match(name) && call->getNumArgs() >= 2 && (is_identity(call->getArg(0)) || builds_matrix(call->getArg(0)));
}

namespace {

// A change to what `target` matches, in `body`: an assignment (a plain `=` only with `plain`), a
// mutating method called for its effect as `v.normalize();`, its address taken, a pass by
// non-const reference.
bool changes(const ast_matchers::internal::Matcher<Expr>& target, bool plain, const Stmt& body, ASTContext& context) {
  using namespace clang::ast_matchers;
  auto assigned = plain ? binaryOperator(isAssignmentOperator(), hasLHS(target)) : binaryOperator(isAssignmentOperator(), unless(hasOperatorName("=")), hasLHS(target));
  auto operator_assigned = plain ? cxxOperatorCallExpr(isAssignmentOperator(), hasArgument(0, target))
                                 : cxxOperatorCallExpr(isAssignmentOperator(), unless(hasOverloadedOperatorName("=")), hasArgument(0, target));
  auto change = stmt(anyOf(assigned, operator_assigned, cxxMemberCallExpr(on(target), callee(cxxMethodDecl(unless(isConst()))), hasParent(compoundStmt())),
                           unaryOperator(hasOperatorName("&"), hasUnaryOperand(target)),
                           callExpr(forEachArgumentWithParam(target, parmVarDecl(hasType(lValueReferenceType(pointee(unless(isConstQualified())))))))));
  return !match(findAll(change.bind("change")), body, context).empty();
}

}  // namespace

bool World::changed(const VarDecl* var) const {
  using namespace clang::ast_matchers;
  auto* function = dyn_cast<FunctionDecl>(var->getDeclContext());
  if (var->getType().isConstQualified() || !function || !function->getBody()) return false;
  return changes(ignoringParenImpCasts(declRefExpr(to(varDecl(equalsNode(var))))), true, *function->getBody(), context_);
}

bool World::changed_in_place(const MemberExpr* use) const {
  using namespace clang::ast_matchers;
  auto* object = dyn_cast<DeclRefExpr>(use->getBase()->IgnoreParenImpCasts());
  const FunctionDecl* function = object ? enclosing_function(use, context_) : nullptr;
  if (!function || !function->getBody()) return false;
  // A plain `=` keeps what the name says: the member is given a value, not changed from one.
  auto same = ignoringParenImpCasts(memberExpr(member(equalsNode(use->getMemberDecl())),
                                               hasObjectExpression(ignoringParenImpCasts(declRefExpr(to(equalsNode(object->getDecl())))))));
  return changes(same, false, *function->getBody(), context_);
}

const Expr* World::assigned_before(const VarDecl* var, const Expr* use) const {
  using namespace clang::ast_matchers;
  auto ref = ignoringParenImpCasts(declRefExpr(to(varDecl(equalsNode(var)))));
  auto may_change = [&](const Stmt* s) { return changes(ref, true, *s, context_); };
  DynTypedNode child = DynTypedNode::create(*use);
  for (;;) {
    auto parents = context_.getParents(child);
    if (parents.empty() || parents[0].get<Decl>()) return nullptr;  // the function (or a lambda) reached
    DynTypedNode parent = parents[0];
    if (auto* block = parent.get<CompoundStmt>()) {
      const Stmt* at = child.get<Stmt>();
      auto it = std::find(block->body_begin(), block->body_end(), at);
      while (it != block->body_begin()) {
        const Stmt* s = *--it;
        if (auto* full = dyn_cast<ExprWithCleanups>(s)) s = full->getSubExpr();
        const Expr *lhs = nullptr, *rhs = nullptr;
        if (auto* bin = dyn_cast<BinaryOperator>(s); bin && bin->getOpcode() == BO_Assign) lhs = bin->getLHS(), rhs = bin->getRHS();
        if (auto* op = dyn_cast<CXXOperatorCallExpr>(s); op && op->getOperator() == OO_Equal && op->getNumArgs() == 2)
          lhs = op->getArg(0), rhs = op->getArg(1);
        if (auto* target = lhs ? dyn_cast<DeclRefExpr>(lhs->IgnoreParenImpCasts()) : nullptr; target && target->getDecl() == var) return rhs;
        if (may_change(s)) return nullptr;
      }
    }
    // Out of a loop the assignment was not found in: a change later in its body reaches the use on the next round.
    if (auto* loop = parent.get<Stmt>(); loop && isa<ForStmt, WhileStmt, DoStmt, CXXForRangeStmt>(loop) && may_change(loop)) return nullptr;
    child = parent;
  }
}

bool World::drops_translation(const Expr* e) const {
  for (e = strip(e); e;) {
    if (is_linear_only(e->getType())) return true;
    if (auto* cast = dyn_cast<CXXFunctionalCastExpr>(e)) e = strip(cast->getSubExpr());
    else if (auto* c = dyn_cast<CXXConstructExpr>(e); c && c->getNumArgs() == 1) e = strip(c->getArg(0));
    else return false;
  }
  return false;
}

bool World::named_in_float(const Value& v) const {
  QualType type;
  if (auto* decl = dyn_cast_or_null<ValueDecl>(v.named)) type = decl->getType();
  else if (auto* property = dyn_cast_or_null<ObjCPropertyDecl>(v.named)) type = property->getType();
  else return false;
  type = type.getNonReferenceType();
  if (type->isPointerType()) type = type->getPointeeType();
  return scalar(type) == 'f';
}

Value World::product(const Value& a, const Value& b, bool both_matrices, bool row, const Expr* e) const {
  // FTranslationMatrix(-PreViewTranslation) * WorldToClip: translated already.
  if ((a.kind == Kind::camera_offset && b.kind == Kind::matrix) || (a.kind == Kind::matrix && b.kind == Kind::camera_offset))
    return {Kind::relative, e};
  if (a.kind == Kind::matrix && b.kind == Kind::matrix && a.from_world != b.from_world) return derived(Kind::model_view, e, a.named ? a : b);
  if (a.kind == Kind::model_view || b.kind == Kind::model_view) return derived(Kind::model_view, e, a.kind == Kind::model_view ? a : b);
  // A world-to-view matrix after a matrix the tables do not know (`view * M` for glm or Eigen,
  // `M * View` for UE): M hands it world positions, so M is a model matrix and the product is
  // camera-relative. Not known well enough to call it camera-dependent either.
  // A matrix the tables do not know, acting after a world matrix, takes world positions in: it
  // may be the camera's (`cameraTransform * model`, `c_model * model`), which cancels the
  // translation, so nothing is known of the product.
  if (both_matrices) {
    const Value& first = row ? a : b;
    const Value& then = row ? b : a;
    if (then.kind == Kind::matrix && then.from_world && first.kind == Kind::none) return {Kind::relative, e};
    if (first.kind == Kind::matrix && !first.from_world && then.kind == Kind::none) return {};
  }
  Value kept = a.kind == Kind::matrix ? a : b.kind == Kind::matrix ? b : Value{};
  if (kept.kind != Kind::none) kept.expr = e;
  return kept;
}

bool World::negated(const Expr* e) {
  e = strip(e);
  if (auto* unary = dyn_cast<UnaryOperator>(e)) return unary->getOpcode() == UO_Minus;
  auto* op = dyn_cast<CXXOperatorCallExpr>(e);
  return op && op->getOperator() == OO_Minus && op->getNumArgs() == 1;
}

bool World::is_identity(const Expr* e) const {
  e = strip(e);
  if (auto* cast = dyn_cast<CXXFunctionalCastExpr>(e)) e = strip(cast->getSubExpr());
  if (!is_matrix_type(e->getType())) return false;
  if (auto* construct = dyn_cast<CXXConstructExpr>(e); construct && construct->getNumArgs() == 0) return true;
  std::vector<APValue> parts = constant_parts(e);
  return parts.size() == 1 && (parts[0].isInt() ? parts[0].getInt() == 1 : parts[0].getFloat().isExactlyValue(1.0));
}

Value World::given(const Expr* value) const {
  if (!typed(value)) return {};
  return drops_translation(value) ? Value{Kind::relative, value} : classify(value);
}

bool World::typed(const Expr* e) { return e && !e->getType().isNull() && !e->isTypeDependent(); }

bool in_template_pattern(const ast_matchers::BoundNodes& nodes) {
  for (const auto& [id, node] : nodes.getMap()) {
    if (auto* e = node.get<Expr>(); e && (e->isInstantiationDependent() || e->getType().isNull())) return true;
    if (auto* v = node.get<ValueDecl>(); v && (v->getType().isNull() || v->getType()->isDependentType())) return true;
  }
  return false;
}

Value World::classify(const Expr* e, int depth) const {
  e = strip(e);
  if (!typed(e)) return {};  // a template's pattern: its instantiations are classified
  // Every step counts (a cast, a member, a local's initialiser), so real chains of locals take
  // ten or more; the products and sums on the way branch, so the limit also bounds the work.
  constexpr int max_steps = 12;
  if (depth > max_steps) return {Kind::none, nullptr, false, true};
  // A conversion to another vector or matrix type keeps what the value is (FVector(FVector3f), glm::dvec3(v)),
  // but one to a 3x3 matrix keeps no translation.
  if (isa<CXXFunctionalCastExpr, CXXConstructExpr>(e) && is_linear_only(e->getType())) return {};
  if (auto* cast = dyn_cast<CXXFunctionalCastExpr>(e)) return classify(cast->getSubExpr(), depth + 1);
  if (auto* construct = dyn_cast<CXXConstructExpr>(e); construct && construct->getNumArgs() >= 1 && !isa<CXXTemporaryObjectExpr>(e))
    return construct->getNumArgs() == 1 ? classify(construct->getArg(0), depth + 1) : Value{};
  if (auto* op = dyn_cast<CXXOperatorCallExpr>(e)) {
    OverloadedOperatorKind o = op->getOperator();
    if ((o == OO_Plus || o == OO_Minus || o == OO_Star) && op->getNumArgs() == 2) {
      Value a = classify(op->getArg(0), depth + 1), b = classify(op->getArg(1), depth + 1);
      // A factor not followed to its end may be the one that cancels the other's translation
      // (`Correction() * view * model` seen only as `... * model`): nothing is known of the product.
      if (o == OO_Star && (a.cut || b.cut)) return {Kind::none, nullptr, false, true};
      // A product keeps the world translation of its world matrix (model * view is camera-relative:
      // the translations cancel in double).
      if (o == OO_Star) {
        // A matrix applied to a vector (`M * p`, OSG's `p * M`): the point in the matrix's target frame.
        bool a_matrix = is_matrix_type(op->getArg(0)->getType()), b_matrix = is_matrix_type(op->getArg(1)->getType());
        const Expr* point = a_matrix ? op->getArg(1) : op->getArg(0);
        if (a_matrix != b_matrix && point->getType()->isRecordType()) return transformed(a_matrix ? a : b, point, false, e);
        return product(a, b, a_matrix && b_matrix, is_row_vector(op->getArg(0)->getType()), e);
      }
      if (a.kind == Kind::position && b.kind == Kind::position && o == OO_Minus) return {Kind::relative, e};
      if (a.kind == Kind::position && b.kind == Kind::position && negated(op->getArg(0)) != negated(op->getArg(1))) return {Kind::relative, e};  // -eye + p
      if ((a.kind == Kind::position && b.kind == Kind::camera_offset) || (a.kind == Kind::camera_offset && b.kind == Kind::position))
        return {Kind::relative, e};
      if (a.kind == Kind::position && o == OO_Minus && b.kind == Kind::none && names_a_value(op->getArg(1))) return {};
      if (a.kind == Kind::position) return derived(Kind::position, e, a);
      if (b.kind == Kind::position && o == OO_Plus) return derived(Kind::position, e, b);
      return {};
    }
    if (o == OO_Minus && op->getNumArgs() == 1) return classify(op->getArg(0), depth + 1);  // -PreViewTranslation
    if (o == OO_Subscript && op->getNumArgs() == 2) {
      Value base = classify(op->getArg(0), depth + 1);
      return base.kind == Kind::position ? derived(Kind::position, e, base) : Value{};
    }
    return {};
  }
  if (auto* bin = dyn_cast<BinaryOperator>(e)) {
    if (bin->getOpcode() != BO_Add && bin->getOpcode() != BO_Sub) return {};
    // `x - hi`: the low part of a split, small by construction.
    if (bin->getOpcode() == BO_Sub)
      if (auto* ref = dyn_cast<DeclRefExpr>(strip(bin->getRHS())); ref && ref->getDecl()->getIdentifier() &&
                                                                   tables_.high_names.match(ref->getDecl()->getName().str()))
        return {Kind::relative, e};
    Value a = classify(bin->getLHS(), depth + 1), b = classify(bin->getRHS(), depth + 1);
    if (a.kind == Kind::position && b.kind == Kind::position && bin->getOpcode() == BO_Sub) return {Kind::relative, e};
    if (a.kind == Kind::position && b.kind == Kind::position && negated(bin->getLHS()) != negated(bin->getRHS())) return {Kind::relative, e};
    if ((a.kind == Kind::position && b.kind == Kind::camera_offset) || (a.kind == Kind::camera_offset && b.kind == Kind::position))
      return {Kind::relative, e};
    if (a.kind == Kind::position && bin->getOpcode() == BO_Sub && b.kind == Kind::none && names_a_value(bin->getRHS())) return {};
    if (a.kind == Kind::position) return derived(Kind::position, e, a);
    if (b.kind == Kind::position && bin->getOpcode() == BO_Add) return derived(Kind::position, e, b);
    return {};
  }
  if (auto* unary = dyn_cast<UnaryOperator>(e); unary && unary->getOpcode() == UO_Minus) return classify(unary->getSubExpr(), depth + 1);
  // An Objective-C property read (`sun.position`): judged by the property's name, as a member is.
  if (auto* pseudo = dyn_cast<PseudoObjectExpr>(e))
    if (auto* property = dyn_cast<ObjCPropertyRefExpr>(pseudo->getSyntacticForm()->IgnoreParens()); property && property->isExplicitProperty())
      return by_name(property->getExplicitProperty(), pseudo->getType(), e);
  if (auto* cond = dyn_cast<ConditionalOperator>(e)) {
    Value a = classify(cond->getTrueExpr(), depth + 1);
    return a.kind != Kind::none ? a : classify(cond->getFalseExpr(), depth + 1);
  }
  if (auto* call = dyn_cast<CallExpr>(e)) {
    const FunctionDecl* callee = call->getDirectCallee();
    if (!callee || !callee->getIdentifier()) return {};
    std::string name = callee->getName().str();
    if (tables_.offset_calls.match(name)) return {Kind::camera_offset, e};
    if (tables_.position_calls.match(name) && !is_matrix_type(call->getType()) && may_hold_position(call->getType())) return {Kind::position, e};
    if (tables_.matrix_calls.match(name) && is_matrix_type(call->getType())) return {Kind::matrix, e};
    if (tables_.from_world_calls.match(name) && is_matrix_type(call->getType())) return {Kind::matrix, e, true};
    // A view from the eye: at the origin it holds a rotation only (a camera-relative renderer's view);
    // from a world position, the world translation.
    if (tables_.look_at_calls.match(name) && is_matrix_type(call->getType()) && call->getNumArgs() >= 2 && !isa<CXXMemberCallExpr>(call)) {
      if (is_origin(call->getArg(0))) return {Kind::relative, e};
      Value eye = classify(call->getArg(0), depth + 1);
      return eye.kind == Kind::position ? derived(Kind::matrix, e, eye, true) : Value{};
    }
    // glm::translate(M, v): a move by v, then M. By a world position it places something in the
    // world; by a negated one (`-cameraPosition`) it moves the world into the camera's frame, a
    // world-to-view matrix. rotate(M, ...) and scale(M, ...) keep M's translation.
    if (!isa<CXXMemberCallExpr>(call) && is_matrix_type(call->getType())) {
      unsigned n = call->getNumArgs();
      if (tables_.translate_calls.match(name) && (n == 1 || n == 2)) {
        const Expr* by = call->getArg(n - 1);
        Value v = classify(by, depth + 1);
        Value move = v.kind == Kind::position   ? derived(Kind::matrix, e, v, negated(by))
                     : v.kind == Kind::relative ? Value{Kind::relative, e}
                                                : Value{Kind::none, nullptr, false, v.cut};
        if (n == 1 || is_identity(call->getArg(0))) return move;
        Value before = classify(call->getArg(0), depth + 1);
        if (before.cut || move.cut) return {Kind::none, nullptr, false, true};
        return product(before, move, true, is_row_vector(call->getType()), e);
      }
      if (tables_.compose_calls.match(name) && n >= 2 && is_matrix_type(call->getArg(0)->getType())) {
        Value m = classify(call->getArg(0), depth + 1);
        if (m.kind != Kind::none) m.expr = e;
        return m;
      }
    }
    if (auto* member = dyn_cast<CXXMemberCallExpr>(call)) {
      Value object = classify(member->getImplicitObjectArgument(), depth + 1);
      if (object.kind == Kind::matrix && tables_.position_from_matrix.match(name)) return derived(Kind::position, e, object);
      if (object.kind == Kind::matrix && tables_.matrix_keep.match(name)) return derived(Kind::matrix, e, object, object.from_world);
      if (object.kind == Kind::matrix && tables_.matrix_inverse.match(name)) return derived(Kind::matrix, e, object, !object.from_world);
      if (tables_.transform_calls.match(name) || tables_.inverse_transform_calls.match(name))  // M.TransformPosition(p)
        return call->getNumArgs() == 1 ? transformed(object, call->getArg(0), tables_.inverse_transform_calls.match(name), e) : Value{};
    } else if (call->getNumArgs() == 1 && (tables_.matrix_keep.match(name) || tables_.matrix_inverse.match(name))) {  // glm::inverse(M)
      Value arg = classify(call->getArg(0), depth + 1);
      if (arg.kind == Kind::matrix) return derived(Kind::matrix, e, arg, arg.from_world != tables_.matrix_inverse.match(name));
    }
    return {};
  }
  if (auto* member = dyn_cast<MemberExpr>(e)) {
    const ValueDecl* decl = member->getMemberDecl();
    std::string name = decl->getIdentifier() ? decl->getName().str() : "";
    Value base = classify(member->getBase(), depth + 1);
    // A component of a position is a position (its X is as large as it is); of the offset, the offset.
    if ((base.kind == Kind::position || base.kind == Kind::camera_offset) && !isa<CXXMethodDecl>(decl)) return derived(base.kind, e, base);
    std::string base_type = type_name(member->getBase()->getType());
    for (const auto& [m, types] : tables_.position_members)
      if (m == name && types.match(base_type)) return {Kind::position, e};
    if (changed_in_place(member)) return {};
    return by_name(decl, member->getType(), e);
  }
  if (auto* ref = dyn_cast<DeclRefExpr>(e)) {
    const ValueDecl* decl = ref->getDecl();
    // A local initialised by a matrix applied to a point: the matrix says which frame it is in, not
    // its name (`cameraPosition = inverse(globeTransform) * eye` is the eye in the globe's frame).
    auto* var = dyn_cast<VarDecl>(decl);
    std::optional<bool> was_changed;  // whether the function changes the variable: a walk of its function, made once
    auto is_changed = [&] { return was_changed ? *was_changed : *(was_changed = changed(var)); };
    auto holds_initialiser = [&] { return var && var->isLocalVarDecl() && var->getInit() && !is_changed(); };
    // A name that says local, relative or translated is the author's word that it was made so
    // (perhaps after its initialiser): not followed, unless a matrix applied to a point says the frame.
    std::string name = decl->getIdentifier() ? decl->getName().str() : "";
    bool said_not = tables_.not_world(is_matrix_type(ref->getType())).match(name);
    // What a local was initialised with, where it says something, says more than its name (`view =
    // glm::lookAt(origin, ...)` holds a rotation only, `pos = body - eye` a difference).
    bool transform = var && var->getInit() && is_transform(var->getInit());
    if ((!said_not || transform) && holds_initialiser()) {
      if (drops_translation(var->getInit())) return {};
      Value init = classify(var->getInit(), depth + 1);
      if (init.kind != Kind::none) init.expr = e;
      // A matrix built on the spot (`glm::translate(glm::dmat4(1.0), v)`) is what it was built
      // from, whatever the local's name says.
      if (init.kind != Kind::none || transform || builds_matrix(var->getInit())) return init;
    }
    if (said_not) return {};
    Value named = by_name(decl, ref->getType(), e);
    // A name says what a variable was made to hold; a plain `=` before the use may say otherwise
    // (`view = glm::mat4(glm::mat3(view))` keeps the rotation only, `pos = pos - eye`).
    if (named.kind != Kind::none && var && (var->isLocalVarDecl() || isa<ParmVarDecl>(var)) && is_changed())
      if (const Expr* value = assigned_before(var, ref)) {
        if (drops_translation(value)) return {};
        Value assigned = classify(value, depth + 1);
        if (assigned.kind != Kind::none) {
          assigned.expr = e;
          return assigned;
        }
      }
    return named;
  }
  if (auto* sub = dyn_cast<ArraySubscriptExpr>(e)) {
    Value base = classify(sub->getBase(), depth + 1);
    return base.kind == Kind::position ? derived(Kind::position, e, base) : Value{};
  }
  return {};
}

}  // namespace lwc::host
