#pragma once
#include <string>
#include <string_view>
#include <vector>

#include <clang/AST/ASTContext.h>
#include <clang/AST/Expr.h>
#include <clang/ASTMatchers/ASTMatchers.h>
#include <nlohmann/json.hpp>

namespace lwc::host {

// A list of name globs (rules/host-world.json), with the project's additions.
struct Names {
  std::vector<std::string> globs;
  bool match(std::string_view name) const;
};

// rules/host-world.json with the project's "host" additions: what is world space in C++ code.
struct Tables {
  Names position_calls, position_names, position_not, position_from_matrix;
  std::vector<std::pair<std::string, Names>> position_members;  // member name, the types it is a world position of
  Names matrix_calls, matrix_names, matrix_not, matrix_keep, matrix_inverse;
  Names from_world_calls, from_world_names;  // matrices that take world positions in (view, view-projection)
  Names transform_calls, inverse_transform_calls;  // `M.TransformPosition(p)`, `M.InverseTransformPosition(p)`
  Names look_at_calls;  // `glm::lookAt(eye, center, up)`: a world-to-view matrix with the eye's translation
  Names translate_calls;  // `glm::translate(M, v)`: a move by v, then M
  Names compose_calls;  // `glm::rotate(M, angle, axis)`, `glm::scale(M, s)`: M's translation kept
  Names offset_calls, offset_names;
  Names double_scalars, float_scalars, matrix_types;
  Names linear_matrix_types;  // 3x3 matrices and smaller, by name, where no template argument says so
  Names row_vector_types;  // matrices applied as `p * M` (UE, OSG, DirectXMath): in a product the left factor acts first
  Names gpu_macros, gpu_structs, upload_calls, address_calls;
  Names copy_calls, mapped_pointers;  // `memcpy(mapped, &block, size)`: a copy into mapped GPU memory
  Names narrowing_methods;  // `v.cast<float>()` (Eigen): a method whose template argument is the scalar it converts to
  std::vector<std::pair<Names, Names>> upload_methods;  // method names, and the classes they upload through (osg::Uniform::set)
  Names upload_constructors;  // classes whose construction uploads its arguments (`new osg::Uniform(name, value)`)
  // Where a vertex stride is given: `sizeof(S)` passed to one of these calls, or stored in (or
  // constructed into) one of these members, makes S a vertex layout.
  Names stride_calls, stride_members;
  Names high_names, low_names;  // the two halves of a high/low split
  // How a function reaches the camera: from a parameter or local of one of `types`, either the
  // view's PreViewTranslation (added to a world position) or the camera's world origin (subtracted).
  struct View {
    Names types;
    std::string code;  // with `{view}.` standing for the variable, e.g. "{view}.ViewMatrices.GetPreViewTranslation()"
    bool subtract = false;  // a camera origin ("camera-origin"), not a PreViewTranslation
  };
  std::vector<View> views;

  // The names that say a matrix, or a position, is not a world one (`*Relative*`, `*Dir*`).
  const Names& not_world(bool matrix) const { return matrix ? matrix_not : position_not; }

  // The built-in tables with a project's additions (each list under the same key extends the built-in one).
  static Tables load(const nlohmann::json& additions);
};

// What a C++ expression holds, as far as the host rules care.
enum class Kind {
  none,
  position,       // an absolute world position (or one of its components)
  matrix,         // a matrix or transform with the world translation in it
  camera_offset,  // the view's PreViewTranslation (minus the camera position)
  relative,       // a difference of positions, or a position already made camera-relative
  model_view,     // a world matrix times a world-to-view one: camera-relative, and camera-dependent
};

struct Value {
  Kind kind = Kind::none;
  const clang::Expr* expr = nullptr;  // the code it comes from, e.g. `Actor->GetActorLocation()` (its text is read only when reported)
  bool from_world = false;  // a matrix that takes world positions in (world to view or clip), not one that gives them
  bool cut = false;  // followed no further (the depth limit): a product with it is not known either
  // The variable or member whose name alone says what it holds (`cu.view`, a `position`
  // parameter), when nothing in the unit shows where its value came from. Other units may show it
  // (engine.cpp weighs the values the whole project gives a member).
  const clang::NamedDecl* named = nullptr;
};

// A value that `e` makes of `from` (a component, a product, a sum): of kind `kind`, resting on the
// same name as `from`.
inline Value derived(Kind kind, const clang::Expr* e, const Value& from, bool from_world = false) {
  return {kind, e, from_world, false, from.named};
}

class World {
 public:
  World(const Tables& tables, clang::ASTContext& context) : tables_(tables), context_(context) {}

  // What `e` holds: followed through locals' initialisers, member access and + and -.
  Value classify(const clang::Expr* e, int depth = 0) const;
  // What a declaration holds by its name alone (`position`, `view`), as a value of `type` read by `e`.
  Value by_name(const clang::NamedDecl* decl, clang::QualType type, const clang::Expr* e) const;
  // The declaration `v` rests on by name holds float numbers (`center->v.x + r * cos(a)` in C, made
  // double by `cos` alone): narrowing the sum rounds no position that was not in float already.
  bool named_in_float(const Value& v) const;
  // What a value given to a variable or member says it holds: as `classify`, but a matrix made 3x3
  // on the way (`glm::mat4(glm::mat3(view))`) is relative, with no translation left.
  Value given(const clang::Expr* value) const;
  // 'd' when the type's scalars are double (double, FVector, glm::dvec3, Eigen::Vector3d, a
  // struct of doubles), 'f' for float, 0 for anything else.
  char scalar(clang::QualType type) const;
  bool is_matrix_type(clang::QualType type) const;
  // How many numbers a vector holds: a compiler vector's (simd_double3) size, or for a record that is
  // plainly a vector, its size as a template argument
  // (glm's vec<3, T, Q>, Eigen's Matrix<T, 3, 1>) or its floating-point members (`double x, y, z;`,
  // OSG's `_v[3]`). 0 for a record that is no vector (a member of another kind: `int satellites;`),
  // -1 where it cannot tell (not a record, or its numbers kept in a member of record type). A
  // pointer counts as what it points to.
  static int components(clang::QualType type);
  // The numbers a record's members hold, as `components` counts them.
  static int numbers_in(const clang::RecordDecl* record);
  // Whether a value of this type can hold a position in a 3D world: a number, or a vector of 3
  // numbers, or 4 (homogeneous); not two numbers, a point on a screen or a canvas.
  static bool may_hold_position(clang::QualType type);
  // A matrix of 3x3 numbers or fewer (glm's mat3, Eigen's Matrix3d, a `double m[9]` record): a
  // rotation and scale, with no room for a translation.
  bool is_linear_only(clang::QualType type) const;
  // `e` is made of constants that float holds exactly (`V3d(o + w / 2, o + w / 2, 0.0)` with `o`
  // and `w` constant integers: an overlay's centre in pixels), read directly or through a local
  // initialised with them: its narrowing rounds nothing.
  bool exact_in_float(const clang::Expr* e) const;
  // `e` is the point (0, 0, 0), written as constants as exact_in_float reads them.
  bool is_origin(const clang::Expr* e) const;
  // Matrices of this type act on row vectors (`p * M`), so in `A * B` the left factor acts first.
  bool is_row_vector(clang::QualType type) const;
  // The type's name without qualifiers, namespace or template arguments (`FVector3f`, `vec`).
  static std::string type_name(clang::QualType type);
  // `e` has a known type: in a template's pattern an expression's type may depend on the
  // template's arguments or be missing (a parenthesised initialiser); the instantiations are read.
  static bool typed(const clang::Expr* e);
  // The source text of a range, as written.
  std::string text(clang::SourceRange range) const;
  const Tables& tables() const { return tables_; }
  clang::ASTContext& context() const { return context_; }

 private:
  // The numbers `e` is made of, where each is a constant (`V3d(o + w / 2, 0, 0)` with constant `o`
  // and `w`, directly or through a local initialised with them); none otherwise.
  std::vector<clang::APValue> constant_parts(const clang::Expr* e) const;
  // The product `a * b` of values that are matrices where `both_matrices` (else one of them may be a
  // scalar); `row`: they act on row vectors, so `a` acts first.
  Value product(const Value& a, const Value& b, bool both_matrices, bool row, const clang::Expr* e) const;
  // `-p`, written so.
  static bool negated(const clang::Expr* e);
  // A matrix written as the identity: `glm::dmat4(1.0)`, `glm::dmat4()`.
  bool is_identity(const clang::Expr* e) const;
  // `matrix` applied to `point` (or its inverse applied): into the world, or out of it.
  Value transformed(Value matrix, const clang::Expr* point, bool inverse, const clang::Expr* e) const;
  // A value taken from somewhere (a variable, a member, an element, a call), not made on the spot
  // from constants: a world position minus such a value the tables do not know is relative to it
  // (`pos - lastPos`), while minus a constant (`Location - FVector(0, 0, 10)`) it is a world position still.
  static bool names_a_value(const clang::Expr* e);
  // A homogeneous vector written with w = 0 (`dvec4(n, 0.0)`): a direction, which no translation moves.
  static bool is_direction(const clang::Expr* point);
  // `e` is a matrix applied to a point (through conversions), whatever the matrix.
  bool is_transform(const clang::Expr* e) const;
  // `e` builds a matrix from its parts on the spot: a translate or look-at call, or a rotate or
  // scale of one (or of the identity).
  bool builds_matrix(const clang::Expr* e) const;
  // Whether a local is changed after its initialiser (assigned, a mutating method called for its
  // effect as `v.normalize();`, passed by reference or by address): then it no longer holds it.
  bool changed(const clang::VarDecl* var) const;
  // The value last given to `var` by a plain `=` before `use`, where that assignment is a statement
  // of a block around the use and nothing between them may change `var`; else null.
  const clang::Expr* assigned_before(const clang::VarDecl* var, const clang::Expr* use) const;
  // `e` passes through a 3x3 matrix (`glm::mat4(glm::mat3(view))`): whatever it came from, it has
  // no translation left.
  bool drops_translation(const clang::Expr* e) const;
  // Whether the function holding `member` (`data.eyePos`) changes that member of that object in
  // place: a mutating method called for its effect, a compound assignment, a pass by reference.
  // A direction made from a position that way keeps the position's name.
  bool changed_in_place(const clang::MemberExpr* member) const;
  const Tables& tables_;
  clang::ASTContext& context_;
};

// The source text of a range, as written (a token range for a SourceRange); "" inside a macro.
std::string source_text(clang::CharSourceRange range, clang::ASTContext& context);
std::string source_text(clang::SourceRange range, clang::ASTContext& context);

// The function a statement or expression is in, if any.
const clang::FunctionDecl* enclosing_function(const clang::Stmt* s, clang::ASTContext& context);

// The numbers a class template is given (`vec<3, double, Q>`: 3 and Q; Eigen's `Matrix<double, 4, 4>`:
// 4, 4 and its options), in order; none for anything else.
std::vector<int64_t> template_numbers(clang::QualType type);

// Skips what does not change a value: parentheses, implicit casts, temporaries, copies.
const clang::Expr* strip(const clang::Expr* e);

// A match in a template's pattern that involves a dependent expression or declaration: left to
// the instantiations, where every type is known (each check's callback starts with it).
bool in_template_pattern(const clang::ast_matchers::BoundNodes& nodes);

}  // namespace lwc::host
