#include "rules/checks/translation_row.h"

namespace lwc::checks {
namespace {

// `M[3]` for a use `M`: the subscript, or -1.
int row_three(const SyntaxTree& t, int use) {
  int row = t.at(use).parent;
  if (!t.is(row, "subscript_expression") || t.child_by_field(row, "argument") != use) return -1;
  int index = t.subscript_index(row);
  return index >= 0 && t.text(index) == "3" ? row : -1;
}

// The statement `M[3][k] += T.c` (c the k-th of x, y, z) or `M[3].xyz += T` that `use` starts:
// the statement, the coordinate (3 for all three) and T; -1 when it is not one.
struct RowAdd {
  int statement = -1;
  int coordinate = -1;
  int translation = -1;
};
RowAdd row_add(const CheckContext& ctx, int use) {
  const SyntaxTree& t = ctx.tree;
  int row = row_three(t, use);
  if (row < 0) return {};
  int target = t.at(row).parent, coordinate = 3;
  if (t.is(target, "subscript_expression") && t.child_by_field(target, "argument") == row) {
    int index = t.subscript_index(target);
    std::string_view k = index >= 0 ? t.text(index) : "";
    if (k != "0" && k != "1" && k != "2") return {};
    coordinate = k[0] - '0';
  } else if (!is_field_of(t, target, row, "xyz")) {
    return {};
  }
  int assignment = t.at(target).parent;
  if (!t.is(assignment, "assignment_expression") || t.child_by_field(assignment, "left") != target ||
      t.text(t.child_by_field(assignment, "operator")) != "+=")
    return {};
  int value = t.child_by_field(assignment, "right");
  while (t.is(value, "parenthesized_expression")) value = t.named_child(value);
  int translation = value;
  if (coordinate < 3) {
    if (!t.is(value, "field_expression")) return {};
    int field = t.child_by_field(value, "field");
    if (field < 0 || t.text(field) != std::string_view("xyz").substr(static_cast<size_t>(coordinate), 1)) return {};
    translation = t.child_by_field(value, "argument");
  }
  if (ctx.world.kind(undemoted(t, translation)) != Kind::camera_offset) return {};
  int statement = t.at(assignment).parent;
  if (!unconditional_statement(t, statement)) return {};
  return {statement, coordinate, translation};
}

}  // namespace

std::optional<TranslationRow> translation_row_of(const CheckContext& ctx, int var) {
  const SyntaxTree& t = ctx.tree;
  if (var < 0) return std::nullopt;
  const Variable& v = ctx.world.variables()[static_cast<size_t>(var)];
  if (v.role != Variable::Role::local || v.init < 0 || v.type != "float4x4") return std::nullopt;
  TranslationRow row{var, undemoted(t, v.init), {}, -1};
  bool seen[4] = {false, false, false, false};
  bool done = false;
  for (int use : ctx.world.uses(var)) {
    RowAdd add = done ? RowAdd{} : row_add(ctx, use);
    if (add.statement < 0) {
      // Past the translation, the local is only read: any write, or a read before, is another shape.
      if (!done || row_three(t, use) >= 0 || t.is(t.at(use).parent, "assignment_expression")) return std::nullopt;
      continue;
    }
    if (seen[add.coordinate] || (row.translation >= 0 && t.text(row.translation) != t.text(add.translation))) return std::nullopt;
    seen[add.coordinate] = true;
    row.translation = add.translation;
    row.statements.push_back(add.statement);
    done = seen[3] || (seen[0] && seen[1] && seen[2]);
    if (seen[3] && row.statements.size() != 1) return std::nullopt;
  }
  if (!done) return std::nullopt;
  return row;
}

std::optional<TranslationRow> translation_row_at(const CheckContext& ctx, int member) {
  const SyntaxTree& t = ctx.tree;
  // Through parentheses and a demotion (`float4x4 M = DFDemote(X.LocalToWorld);`).
  int n = member, p = t.at(n).parent;
  for (;;) {
    if (t.is(p, "parenthesized_expression")) {
      n = p, p = t.at(n).parent;
    } else if (int call = t.is(p, "argument_list") ? t.at(p).parent : -1; call >= 0 && undemoted(t, call) == n) {
      n = call, p = t.at(n).parent;
    } else {
      break;
    }
  }
  // The copy the row starts from: `float4x4 M = member;`.
  if (t.is(p, "init_declarator") && t.child_by_field(p, "value") == n) {
    int id = t.child_by_field(p, "declarator");
    return translation_row_of(ctx, id >= 0 ? ctx.world.variable_declared_at(id) : -1);
  }
  // The translation added: climb to the assignment, then to the local whose row it is.
  for (int a = p; a >= 0 && !t.is(a, "expression_statement"); a = t.at(a).parent) {
    if (!t.is(a, "assignment_expression")) continue;
    int target = t.child_by_field(a, "left");
    while (t.is(target, "subscript_expression") || t.is(target, "field_expression")) target = t.child_by_field(target, "argument");
    if (!t.is(target, "identifier")) return std::nullopt;
    auto row = translation_row_of(ctx, ctx.world.variable_at(target));
    if (!row) return std::nullopt;
    for (int s : row->statements)
      if (t.at(s).begin <= t.at(member).begin && t.at(member).end <= t.at(s).end) return row;
    return std::nullopt;
  }
  return std::nullopt;
}

}  // namespace lwc::checks
