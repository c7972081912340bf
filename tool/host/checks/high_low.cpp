#include "host/checks/high_low.h"

#include <clang/AST/ExprCXX.h>
#include <clang/AST/QualTypeNames.h>
#include <clang/AST/RecordLayout.h>
#include <clang/ASTMatchers/ASTMatchers.h>
#include <clang/Lex/Lexer.h>
#include <fmt/format.h>
#include <llvm/Support/Path.h>

namespace lwc::host {

using namespace clang;
using namespace clang::ast_matchers;

namespace {

// `Object.Member = <narrowing>;` as a statement of its own in a block.
struct Assignment {
  const Expr* expr;          // the whole assignment (the `;` follows it)
  const MemberExpr* member;  // its left side
  const FieldDecl* field;
};

std::optional<Assignment> assignment_statement(const Expr* narrowing, ASTContext& context) {
  const Stmt* current = narrowing;
  const Expr* assign = nullptr;
  const Expr* lhs = nullptr;
  while (!assign) {
    auto parents = context.getParents(*current);
    const Stmt* parent = parents.empty() ? nullptr : parents[0].get<Stmt>();
    if (!parent) return std::nullopt;
    if (isa<ImplicitCastExpr, MaterializeTemporaryExpr, CXXBindTemporaryExpr, ParenExpr>(parent)) {
      current = parent;
    } else if (auto* bin = dyn_cast<BinaryOperator>(parent); bin && bin->getOpcode() == BO_Assign && bin->getRHS() == current) {
      assign = bin, lhs = bin->getLHS();
    } else if (auto* op = dyn_cast<CXXOperatorCallExpr>(parent); op && op->getOperator() == OO_Equal && op->getNumArgs() == 2 && op->getArg(1) == current) {
      assign = op, lhs = op->getArg(0);
    } else {
      return std::nullopt;
    }
  }
  const Stmt* statement = assign;
  auto parents = context.getParents(*statement);
  if (!parents.empty() && parents[0].get<ExprWithCleanups>()) statement = parents[0].get<ExprWithCleanups>(), parents = context.getParents(*statement);
  if (parents.empty() || !parents[0].get<CompoundStmt>()) return std::nullopt;
  auto* member = dyn_cast<MemberExpr>(lhs->IgnoreParenImpCasts());
  auto* field = member ? dyn_cast<FieldDecl>(member->getMemberDecl()) : nullptr;
  if (!field) return std::nullopt;
  return Assignment{assign, member, field};
}

// The blanks before `at` on its line, or nullopt when something else comes first.
std::optional<std::string> indent_of(SourceLocation at, const SourceManager& sm) {
  auto [file, offset] = sm.getDecomposedLoc(sm.getExpansionLoc(at));
  StringRef text = sm.getBufferData(file);
  size_t start = text.rfind('\n', offset);  // looks before `offset` only
  start = start == StringRef::npos ? 0 : start + 1;
  StringRef before = text.slice(start, offset);
  if (before.find_first_not_of(" \t") != StringRef::npos) return std::nullopt;
  return before.str();
}

bool declared(ASTContext& context, const char* name) { return !context.getTranslationUnitDecl()->lookup(&context.Idents.get(name)).empty(); }

// A name the function does not use yet, for a new local.
bool unused_name(const std::string& name, const FunctionDecl* function, ASTContext& context) {
  if (!function->getBody() || declared(context, name.c_str())) return false;
  return match(findAll(namedDecl(hasName(name))), *function->getBody(), context).empty() &&
         std::none_of(function->param_begin(), function->param_end(), [&](const ParmVarDecl* p) { return p->getName() == name; });
}

const FieldDecl* field_named(const RecordDecl* record, const std::string& name) {
  for (const FieldDecl* f : record->fields())
    if (f->getName() == name) return f;
  return nullptr;
}

// The spelling of a type that compiles anywhere in the unit (`glm::vec3`, `double`).
std::string spelled(QualType type, ASTContext& context) {
  PrintingPolicy policy(context.getLangOpts());
  policy.SuppressScope = false;
  return TypeName::getFullyQualifiedName(type.getNonReferenceType().getUnqualifiedType(), context, policy);
}

// The type of `value` as the code names it. An element of a container is typed by the library's
// member typedefs (`std::vector<glm::dvec3>::const_reference`, spelled out through its allocator
// traits); the container's declaration names the element as written (`glm::dvec3`).
std::string spelled_type_of(const Expr* value, ASTContext& context) {
  QualType type = value->getType();
  const Expr* container = nullptr;
  if (auto* op = dyn_cast<CXXOperatorCallExpr>(strip(value)); op && op->getOperator() == OO_Subscript) container = op->getArg(0);
  else if (auto* call = dyn_cast<CXXMemberCallExpr>(strip(value))) container = call->getImplicitObjectArgument();
  const ValueDecl* decl = nullptr;
  if (auto* ref = dyn_cast_or_null<DeclRefExpr>(container ? strip(container) : nullptr)) decl = ref->getDecl();
  else if (auto* member = dyn_cast_or_null<MemberExpr>(container ? strip(container) : nullptr)) decl = member->getMemberDecl();
  if (decl)
    if (auto* written = decl->getType().getNonReferenceType()->getAs<TemplateSpecializationType>();
        written && !written->template_arguments().empty() && written->template_arguments()[0].getKind() == TemplateArgument::Type) {
      QualType element = written->template_arguments()[0].getAsType();
      if (context.hasSameUnqualifiedType(element, type.getNonReferenceType())) type = element;
    }
  return spelled(type, context);
}

// The new member's declaration beside `field`: after its shader-parameter macro (members of those
// structs are bound by name), or at the end of a plain struct: a vertex layout (attributes are read
// at their own offsets), or a block whose members end on a 16-byte row.
std::variant<Reporter::Change, std::string> declare(const FieldDecl* field, const std::string& type, const std::string& name, bool vertex,
                                                    ASTContext& context) {
  const SourceManager& sm = context.getSourceManager();
  const LangOptions& lang = context.getLangOpts();
  const RecordDecl* record = field->getParent();
  std::string struct_name = record->getIdentifier() ? "`" + record->getNameAsString() + "`" : "the struct";
  if (field->getLocation().isMacroID()) {
    CharSourceRange call = sm.getExpansionRange(field->getLocation());
    std::string text = source_text(call, context);
    size_t open = text.find('('), comma = text.rfind(',');
    if (open == std::string::npos || comma == std::string::npos || text.find(',', open) != comma || text.back() != ')')
      return "`" + text.substr(0, open) + "` declares " + struct_name + "'s member with more than a type and a name; add the low half by hand";
    std::string macro = text.substr(0, open);
    SourceLocation end = Lexer::getLocForEndOfToken(call.getEnd(), 0, sm, lang);
    std::string indent = indent_of(call.getBegin(), sm).value_or("\t");
    std::string written_type = type.empty() ? StringRef(text).slice(open + 1, comma).trim().str() : type;
    return Reporter::Change{CharSourceRange::getCharRange(end, end), "\n" + indent + macro + "(" + written_type + ", " + name + ")"};
  }
  if (record->isInvalidDecl() || record->isDependentType()) return struct_name + " has no fixed layout";
  // C++ puts the new member right after the last one (in its tail padding, if any); std140 and
  // cbuffer packing put a 3- or 4-vector at the next 16-byte row. They agree when the last
  // member ends on a row.
  const FieldDecl* last = nullptr;
  for (const FieldDecl* f : record->fields()) last = f;
  if (!last || last->isBitField()) return struct_name + " does not end with a plain member";
  int64_t end = static_cast<int64_t>(context.getASTRecordLayout(record).getFieldOffset(last->getFieldIndex()) / 8) +
                context.getTypeSizeInChars(last->getType()).getQuantity();
  if (end % 16 != 0 && !vertex)
    return fmt::format("{}'s members end at byte {}, not on a 16-byte row: a member added at the end would not sit at the same offset "
                       "as in the shader's block (were it a vertex layout, its stride given as `sizeof` would say so)",
                       struct_name, end);
  SourceLocation brace = record->getBraceRange().getEnd();
  if (brace.isMacroID()) return struct_name + " ends inside a macro";
  std::string indent = indent_of(field->getBeginLoc(), sm).value_or("  ");
  std::string declaration = (type.empty() ? spelled(field->getType(), context) : type) + " " + name + ";";
  if (std::optional<std::string> closing = indent_of(brace, sm)) {
    SourceLocation line = brace.getLocWithOffset(-static_cast<int>(closing->size()));
    return Reporter::Change{CharSourceRange::getCharRange(line, line), indent + declaration + "\n"};
  }
  return Reporter::Change{CharSourceRange::getCharRange(brace, brace), declaration + " "};
}

// Whether evaluating `e` twice is the same as once: names, members, subscripts (a container's
// `operator[]` too) with such indices, dereferences, constants.
bool repeatable(const Expr* e, ASTContext& context) {
  e = e->IgnoreParenImpCasts();
  if (isa<DeclRefExpr, CXXThisExpr, IntegerLiteral>(e)) return true;
  if (auto* m = dyn_cast<MemberExpr>(e)) return repeatable(m->getBase(), context);
  if (auto* a = dyn_cast<ArraySubscriptExpr>(e)) return repeatable(a->getBase(), context) && repeatable(a->getIdx(), context);
  if (auto* u = dyn_cast<UnaryOperator>(e); u && u->getOpcode() == UO_Deref) return repeatable(u->getSubExpr(), context);
  if (auto* op = dyn_cast<CXXOperatorCallExpr>(e); op && op->getOperator() == OO_Subscript && op->getNumArgs() == 2)
    return repeatable(op->getArg(0), context) && repeatable(op->getArg(1), context);
  return !e->HasSideEffects(context);
}

// UE 5.4's DoubleFloat type for a narrowed UE type, when the unit declares it.
const char* df_type(QualType narrowed, ASTContext& context) {
  const char* name = nullptr;
  if (narrowed->isBuiltinType()) name = "FDFScalar";
  else if (const RecordDecl* r = narrowed->getAsRecordDecl(); r && r->getIdentifier()) {
    StringRef record = r->getName();
    name = record == "TVector" ? "FDFVector3" : record == "TVector2" ? "FDFVector2" : record == "TVector4" ? "FDFVector4" : nullptr;
  }
  return name && declared(context, name) ? name : nullptr;
}

// Whether a value of `type` can be made from its float twin (`static_cast<glm::dvec3>(v)`).
bool widens_from_float(QualType type) {
  if (type->isBuiltinType()) return true;
  const CXXRecordDecl* record = type->getAsCXXRecordDecl();
  if (!record || !record->hasDefinition()) return false;
  for (const Decl* d : record->decls()) {
    const CXXConstructorDecl* ctor = dyn_cast<CXXConstructorDecl>(d);
    if (auto* t = dyn_cast<FunctionTemplateDecl>(d)) ctor = dyn_cast<CXXConstructorDecl>(t->getTemplatedDecl());
    if (ctor && !ctor->isCopyOrMoveConstructor() && ctor->getNumParams() >= 1 && ctor->getMinRequiredArguments() <= 1) return true;
  }
  return false;
}

// A 4x4 double matrix of a library whose columns the split can be written with: glm's
// `mat<4, 4, T>` (column 3 is `m[3]`) or Eigen's `Matrix<T, 4, 4>` (`m.col(3)`).
enum class ColumnMatrix { none, glm, eigen };

ColumnMatrix column_matrix(QualType type) {
  auto* spec = dyn_cast_or_null<ClassTemplateSpecializationDecl>(type.getNonReferenceType()->getAsCXXRecordDecl());
  auto* ns = spec ? dyn_cast<NamespaceDecl>(spec->getEnclosingNamespaceContext()) : nullptr;
  if (!ns || !ns->getIdentifier()) return ColumnMatrix::none;
  std::vector<int64_t> extents = template_numbers(type);
  if (extents.size() < 2 || extents[0] != 4 || extents[1] != 4) return ColumnMatrix::none;
  if (ns->getName() == "glm" && spec->getName() == "mat") return ColumnMatrix::glm;
  if (ns->getName() == "Eigen" && spec->getName() == "Matrix") return ColumnMatrix::eigen;
  return ColumnMatrix::none;
}

// `ns::name` when the namespace of `like`'s type declares the type `name` (`glm::vec3`,
// `Eigen::Vector3f`), and, with `same`, names `like`'s own type by it (`glm::dmat4`); else "".
std::string library_type(QualType like, const char* name, ASTContext& context, bool same = false) {
  const CXXRecordDecl* record = like.getNonReferenceType()->getAsCXXRecordDecl();
  auto* ns = record ? dyn_cast<NamespaceDecl>(record->getEnclosingNamespaceContext()) : nullptr;
  if (!ns) return "";
  for (const NamedDecl* d : ns->lookup(&context.Idents.get(name)))
    if (auto* type = dyn_cast<TypeDecl>(d)) {
      if (same && !context.hasSameUnqualifiedType(context.getTypeDeclType(type), like.getNonReferenceType())) continue;
      return ns->getNameAsString() + "::" + name;
    }
  return "";
}

// The split of a glm or Eigen local-to-world matrix, written out: the new member takes the float
// nearest the translation (the high half, as UE's PostTranslation), the matrix uploaded is a copy
// with that subtracted from its translation column in double (exact: what is left is small), and
// the shader joins them as `MakeDFMatrix(PostTranslation, M)`. "" when done, else why not.
std::string column_split(const Upload& up, const Assignment& at, const std::string& name, const std::string& low, const std::string& indent,
                         const std::string& object, const FunctionDecl* function, ASTContext& context, HighLowFix& fix, std::string& type_of_low) {
  ColumnMatrix library = column_matrix(up.value_expr->getType());
  if (library == ColumnMatrix::none)
    return "a matrix outside glm and Eigen is split with UE 5.4's `FDFMatrix`, which this unit does not declare; split its translation by hand";
  type_of_low = library_type(up.value_expr->getType(), library == ColumnMatrix::glm ? "vec3" : "Vector3f", context);
  if (type_of_low.empty()) return std::string("the unit does not declare the float 3-vector the translation's high half needs");
  std::string local = name + "Relative";
  if (!unused_name(local, function, context)) return "`" + local + "` is taken";
  std::string wide = library_type(up.value_expr->getType(), library == ColumnMatrix::glm ? "dmat4" : "Matrix4d", context, true);
  if (wide.empty()) wide = spelled_type_of(up.value_expr, context);
  std::string high = object + low;
  std::string column = library == ColumnMatrix::glm ? local + "[3]" : local + ".col(3).head<3>()";
  std::string take = library == ColumnMatrix::glm ? type_of_low + "(" + column + ")" : column + ".cast<float>()";
  std::string give = library == ColumnMatrix::glm ? wide + "::col_type(" + high + ", 0.0)" : high + ".cast<double>()";
  SourceLocation begin = context.getSourceManager().getExpansionLoc(at.expr->getBeginLoc());
  fix.changes.push_back({CharSourceRange::getCharRange(begin, begin), wide + " " + local + " = " + source_text(up.value_expr->getSourceRange(), context) +
                                                                          ";\n" + indent + high + " = " + take + ";\n" + indent + column + " -= " + give +
                                                                          ";\n" + indent});
  fix.changes.push_back({CharSourceRange::getTokenRange(up.value_expr->getSourceRange()), local});
  fix.form = "its translation's nearest float taken out in double";
  fix.read = "`MakeDFMatrix(" + low + ", " + name + ")` (as in `lwc_doublefloat`, the DoubleFloat library lwcport's shader fixes write)";
  return "";
}

}  // namespace

bool writes_low_half(const FieldDecl* field, const Expr* e, ASTContext& context, const Tables& tables) {
  const FunctionDecl* function = enclosing_function(e, context);
  if (!function || !function->getBody() || !field->getIdentifier()) return false;
  std::string name = field->getNameAsString();
  for (const FieldDecl* sibling : field->getParent()->fields()) {
    StringRef other = sibling->getName();
    if (sibling == field || !other.starts_with(name) || !tables.low_names.match(other.str()) || !tables.low_names.match(other.substr(name.size()).str()))
      continue;
    if (!match(findAll(memberExpr(member(equalsNode(sibling)))), *function->getBody(), context).empty()) return true;
  }
  return false;
}

std::variant<HighLowFix, std::string> high_low_fix(const Upload& up, ASTContext& context) {
  const SourceManager& sm = context.getSourceManager();
  const LangOptions& lang = context.getLangOpts();
  std::optional<Assignment> at = assignment_statement(up.narrowing, context);
  if (!at) return std::string("the narrowed value is not assigned to a member in a statement of its own");
  if (auto* construct = dyn_cast<CXXConstructExpr>(strip(up.narrowing)); construct && construct->getNumArgs() != 1)
    return "`" + source_text(up.narrowing->getSourceRange(), context).substr(0, source_text(up.narrowing->getSourceRange(), context).find('(')) +
           "(...)` packs the value with others; split it by hand";
  std::optional<std::string> indent = indent_of(at->expr->getBeginLoc(), sm);
  if (!indent || at->expr->getBeginLoc().isMacroID() || at->expr->getEndLoc().isMacroID())
    return std::string("the assignment does not start its line, or is inside a macro");
  const FunctionDecl* function = enclosing_function(up.narrowing, context);
  bool matrix = up.value.kind != Kind::position;
  std::string name = at->field->getNameAsString();
  std::string low = name + (matrix ? "PostTranslation" : name.find('_') != std::string::npos ? "_low" : "Low");

  const Expr* base = at->member->getBase();
  bool implicit_this = isa<CXXThisExpr>(base->IgnoreParenImpCasts()) && cast<CXXThisExpr>(base->IgnoreParenImpCasts())->isImplicit();
  std::string object = implicit_this ? "" : source_text(base->getSourceRange(), context) + (at->member->isArrow() ? "->" : ".");
  std::string target = source_text(at->member->getSourceRange(), context);
  std::string value = source_text(up.value_expr->getSourceRange(), context);
  if (object.empty() && !implicit_this) return std::string("the member's object could not be read");
  // The rewrite names the object twice: once for each half.
  if (!repeatable(base, context)) return "`" + object + "` calls a function, which the rewrite would call twice; keep the object in a local first";

  HighLowFix fix;
  fix.low = low;
  fix.member = at->field;
  CharSourceRange whole = CharSourceRange::getTokenRange(at->expr->getSourceRange());
  std::string type_of_low;  // "" for the member's own type
  if (matrix) {
    if (up.value.from_world)
      return std::string("a world-to-view or world-to-clip matrix: pre-translate it by the camera (UE 5.4 `FDFInverseMatrix::MakeFromRelativeWorldMatrix`) by hand");
    if (!declared(context, "FDFMatrix") || !declared(context, "FDFVector3")) {
      std::string why = column_split(up, *at, name, low, *indent, object, function, context, fix, type_of_low);
      if (!why.empty()) return why;
    } else {
    std::string local = name + "DF";
    if (!unused_name(local, function, context)) return "`" + local + "` is taken";
    std::string source = value;
    std::string prefix;
    // The matrix is read twice (its origin and itself); a call is made once, into a local.
    if (!repeatable(up.value_expr, context)) {
      source = name + "Absolute";
      if (!unused_name(source, function, context)) return "`" + source + "` is taken";
      prefix = "const auto& " + source + " = " + value + ";\n" + *indent;
    }
    fix.changes.push_back({whole, prefix + "const FDFMatrix " + local + " = FDFMatrix::MakeToRelativeWorldMatrix(FDFVector3(" + source +
                                      ".GetOrigin()).High, " + source + ");\n" + *indent + target + " = " + local + ".M;\n" + *indent + object + low +
                                      " = " + local + ".PostTranslation"});
    fix.form = "`FDFMatrix::MakeToRelativeWorldMatrix`";
    fix.read = "`MakeDFMatrix(" + low + ", " + name + ")`";
    type_of_low = "FVector3f";
    }
  } else if (const char* df = df_type(up.narrowing->getType(), context)) {
    std::string local = name + "DF";
    if (!unused_name(local, function, context)) return "`" + local + "` is taken";
    fix.changes.push_back({whole, std::string("const ") + df + " " + local + "(" + value + ");\n" + *indent + target + " = " + local + ".High;\n" +
                                      *indent + object + low + " = " + local + ".Low"});
    fix.form = std::string("`") + df + "`";
    fix.read = "`MakeDF" + std::string(df + 3) + "(" + name + ", " + low + ")`";
  } else {
    // low = float(value - double(high)): the difference is exact in double, and its nearest
    // float is the rest the high half lost (lwc::host::split in lwcport's lwc_host.h does the same).
    QualType wide = up.value_expr->getType();
    const CXXMethodDecl* method = isa<CXXMemberCallExpr>(up.narrowing) ? cast<CXXMemberCallExpr>(up.narrowing)->getMethodDecl() : nullptr;
    bool by_method = method && method->getTemplateSpecializationArgs();  // `v.cast<float>()`, widened by `cast<double>()`
    std::string wide_type = spelled_type_of(up.value_expr, context);
    bool vector = wide->isVectorType();  // a compiler vector (simd_double3): converted by `__builtin_convertvector`
    if (!by_method && !vector && !widens_from_float(wide.getNonReferenceType()))
      return "`" + wide_type + "` has no constructor from its float twin to subtract the high half in double";
    std::string source = value;
    // The value is read twice (narrowed, then subtracted from): a call is made once, into a local.
    if (!repeatable(up.value_expr, context)) {
      source = name + "World";
      if (!unused_name(source, function, context)) return "`" + source + "` is taken";
      SourceLocation begin = sm.getExpansionLoc(at->expr->getBeginLoc());
      fix.changes.push_back({CharSourceRange::getCharRange(begin, begin), "const " + wide_type + " " + source + " = " + value + ";\n" + *indent});
      fix.changes.push_back({CharSourceRange::getTokenRange(up.value_expr->getSourceRange()), source});
    }
    SourceLocation after = Lexer::findLocationAfterToken(sm.getExpansionLoc(at->expr->getEndLoc()), tok::semi, sm, lang, false);
    if (after.isInvalid()) return std::string("the assignment has no `;` right after it");
    std::string narrow = spelled(at->field->getType(), context);
    std::string rest = by_method ? "(" + source + " - " + target + "." + method->getNameAsString() + "<double>())." + method->getNameAsString() + "<float>()"
                       : vector  ? "__builtin_convertvector(" + source + " - __builtin_convertvector(" + target + ", " + wide_type + "), " + narrow + ")"
                                 : "static_cast<" + narrow + ">(" + source + " - static_cast<" + wide_type + ">(" + target + "))";
    fix.changes.push_back({CharSourceRange::getCharRange(after, after), "\n" + *indent + object + low + " = " + rest + ";"});
    fix.form = "a difference in double";
    fix.read = "a DoubleFloat pair (high `" + name + "`, low `" + low + "`), added only in DoubleFloat arithmetic";
    // A struct found by its upload, not named as a GPU block, may be a vertex layout: the new
    // member makes each element larger and needs an attribute of its own.
    std::string struct_name = at->field->getParent()->getNameAsString();
    if (up.vertex)
      fix.read += "; the stride is given as `sizeof`, so it follows, and `" + low + "` needs a vertex attribute of its own, at `offsetof(" +
                  struct_name + ", " + low + ")`";
    else if (up.sink.starts_with("member "))
      fix.read += "; where the struct is a vertex layout, its stride grows and `" + low + "` needs a vertex attribute of its own";
  }
  if (!field_named(at->field->getParent(), low)) {
    auto declaration = declare(at->field, type_of_low, low, up.vertex, context);
    if (auto* why = std::get_if<std::string>(&declaration)) return *why;
    fix.changes.push_back(std::get<Reporter::Change>(declaration));
  }
  return fix;
}

void PortedUploadCheck::upload(const Upload& up, const MatchFinder::MatchResult& match) {
  if (!reports(up)) return;
  Vars vars;
  Finding* finding = report_upload(up, match, rule_, out_, tables_, port(), vars);
  if (!finding) return;
  std::optional<CameraInScope> camera = camera_in_scope(up.narrowing, *match.Context, tables_);
  std::string why = camera ? translated(up, *camera, *finding, vars, match) : "no camera in scope (a parameter or local of a view type, rules/host-world.json \"views\")";
  if (why.empty()) return;
  finding->withheld.push_back("translated: " + why);
  auto fix = high_low_fix(up, *match.Context);
  if (auto* not_split = std::get_if<std::string>(&fix)) {
    finding->withheld.push_back("high-low: " + *not_split);
    return;
  }
  const HighLowFix& split = std::get<HighLowFix>(fix);
  vars["low"] = "`" + split.low + "`";
  vars["form"] = split.form;
  vars["read"] = split.read;
  vars["holder"] = up.vertex ? "the vertex layout `" + split.member->getParent()->getNameAsString() + "`" : "the parameter struct";
  if (!out_.fix(*finding, rule_, "high-low", vars, split.changes, *match.SourceManager, match.Context->getLangOpts())) {
    // The new member would go into a file the run does not report on (a system or library header).
    const SourceManager& sm = *match.SourceManager;
    SourceLocation declared = sm.getExpansionLoc(split.member->getLocation());
    finding->withheld.push_back("high-low: the member is declared in " + llvm::sys::path::filename(sm.getFilename(declared)).str() +
                                ", outside the files this run reports on");
    return;
  }
  if (finding->facts.count("port")) finding->facts["port"] = up.value.kind == Kind::position ? "high-low-position" : "high-low-matrix";
}

}  // namespace lwc::host
