// The world-space analysis (analyzer.h): a document's last model replayed, function by function, where its inputs are as they were (ModelReuse).
#include <algorithm>
#include <cctype>
#include <set>

#include "world/analyzer.h"

namespace lwc::analysis {

void Analyzer::prepare_reuse() {
  if (!context_.reuse) return;
  if (t_.number == 0) {  // a tree the next parse will not edit (lang/syntax.h): nothing to keep
    context_.reuse->logs_.erase(context_.variant);
    return;
  }
  log_ = std::make_unique<ModelReuse::Log>();
  log_->tree = t_.number;
  log_->data = &d_;
  log_->includes = inc_;
  log_->names_as_evidence = m_.names_as_evidence_;
  log_->plain_names = m_.plain_names_;
  log_->era = m_.era_;
  log_->collected = m_.variables_;
  log_->function_order = function_order_;
  for (int fn : function_order_) log_->function_names.push_back(function_name(fn));
  auto it = context_.reuse->logs_.find(context_.variant);
  if (it == context_.reuse->logs_.end() || t_.reused_from == 0) return;
  ModelReuse::Log& old = *it->second;
  if (old.tree != t_.reused_from || old.data != &d_ || old.includes != inc_ || old.names_as_evidence != m_.names_as_evidence_ ||
      old.plain_names != m_.plain_names_ || old.era != m_.era_)
    return;
  to_old_.assign(t_.nodes.size(), kGone);
  for (const SyntaxTree::Reused& r : t_.reused) {
    if (to_new_.size() < static_cast<size_t>(r.there + r.count)) to_new_.resize(r.there + r.count, kGone);
    for (int32_t k = 0; k < r.count; ++k) {
      to_old_[r.here + k] = r.there + k;
      to_new_[r.there + k] = r.here + k;
    }
  }
  if (old.collected.size() != m_.variables_.size()) return;
  for (size_t i = 0; i < old.collected.size(); ++i)
    if (!(moved(old.collected[i]) == m_.variables_[i])) return;
  // The same functions by name in the same order (an edited one has no old node).
  if (old.function_names != log_->function_names) return;
  for (size_t i = 0; i < function_order_.size(); ++i)
    if (new_id(old.function_order[i]) != function_order_[i] && (new_id(old.function_order[i]) >= 0 || to_old_[function_order_[i]] >= 0))
      return;
  old_ = &old;
}

Variable Analyzer::moved(Variable v) const {
  for (int* n : {&v.decl, &v.declaration, &v.function, &v.init, &v.block}) *n = new_id(*n);
  return v;
}

VariableState Analyzer::variable_state(int var) const {
  auto it = named_outputs_.find(var);
  return {m_.variables_[var].kind, it != named_outputs_.end() ? std::optional<NamedOutput>(it->second) : std::nullopt};
}

std::optional<Summary> Analyzer::memo_entry(const MemoKey& key) const {
  auto it = memo_.find(key);
  return it != memo_.end() ? std::optional<Summary>(it->second) : std::nullopt;
}

std::optional<Kind> Analyzer::field_kind(const std::string& key) const {
  auto it = field_kinds_.find(key);
  return it != field_kinds_.end() ? std::optional<Kind>(it->second) : std::nullopt;
}

void Analyzer::touch_variable(int var) const {
  if (run_ && !touched_variables_.count(var)) touched_variables_.emplace(var, variable_state(var));
}

void Analyzer::touch_field(const std::string& key) {
  if (run_ && touched_fields_.insert(key).second) run_->fields_before.emplace_back(key, field_kind(key));
}

void Analyzer::begin_run() {
  if (!log_) return;
  current_run_ = {};
  run_ = &current_run_;
}

void Analyzer::end_run(int fn) {
  if (!run_) return;
  for (const auto& [var, before] : touched_variables_) {
    run_->variables_before.emplace_back(m_.variables_[var].decl, before);
    run_->variables_after.emplace_back(m_.variables_[var].decl, variable_state(var));
  }
  for (const MemoKey& key : touched_memo_)
    if (auto s = memo_entry(key)) run_->memo_after.emplace_back(key, *s);
  for (const std::string& key : touched_fields_)
    if (auto k = field_kind(key)) run_->fields_after.emplace_back(key, *k);
  run_->kinds.assign(run_kinds_.begin(), run_kinds_.end());
  touched_variables_.clear();
  touched_memo_.clear();
  touched_fields_.clear();
  run_kinds_.clear();
  log_->runs[fn] = std::move(current_run_);
  run_ = nullptr;
}

bool Analyzer::replay(int fn) {
  if (!old_ || to_old_[fn] < 0) return false;
  auto found = old_->runs.find(to_old_[fn]);
  if (found == old_->runs.end()) return false;
  const RunLog& r = found->second;
  auto memo_key = [&](const MemoKey& key) { return MemoKey{new_id(key.first), key.second}; };
  auto variable = [&](int decl) {
    auto it = decl_var_.find(new_id(decl));
    return it != decl_var_.end() ? it->second : -1;
  };
  for (int f : r.functions)
    if (new_id(f) < 0) return false;
  for (const auto& [decl, before] : r.variables_before) {
    if (new_id(decl) < 0) return false;
    int var = variable(decl);
    if (before ? var < 0 || !(variable_state(var) == *before) : var >= 0) return false;
  }
  for (const auto& [key, before] : r.memo_before)
    if (memo_entry(memo_key(key)) != before) return false;
  for (const auto& [key, before] : r.fields_before)
    if (field_kind(key) != before) return false;

  // Valid: the log moves to this model, its nodes renumbered for this tree, and is applied.
  RunLog now = std::move(found->second);
  for (std::vector<int>* nodes : {&now.functions, &now.too_deep, &now.cleared})
    for (int& n : *nodes) n = new_id(n);
  for (Variable& v : now.created) v = moved(std::move(v));
  for (auto& [decl, state] : now.variables_before) decl = new_id(decl);
  for (auto& [decl, state] : now.variables_after) decl = new_id(decl);
  for (auto& [key, summary] : now.memo_before) key.first = new_id(key.first);
  for (auto& [key, summary] : now.memo_after) key.first = new_id(key.first);
  for (auto& [node, k] : now.kinds) node = new_id(node);
  for (auto& [identifier, decl] : now.refs) identifier = new_id(identifier), decl = new_id(decl);
  for (AbsoluteHolder& h : now.reports) h.site = new_id(h.site);

  auto here = [&](int decl) { return decl_var_.at(decl); };
  for (const Variable& v : now.created) new_variable(v);
  for (const auto& [decl, after] : now.variables_after) {
    int var = here(decl);
    m_.variables_[var].kind = after.kind;
    if (after.output) named_outputs_[var] = *after.output;
  }
  for (const auto& [key, after] : now.memo_after) memo_[key] = after;
  for (const auto& [key, after] : now.fields_after) field_kinds_[key] = after;
  for (const auto& [node, k] : now.kinds) join_at_node(node, k);
  for (const auto& [identifier, decl] : now.refs) m_.refs_[identifier] = here(decl);
  for (const AbsoluteHolder& h : now.reports) report(h);
  m_.too_deep_.insert(m_.too_deep_.end(), now.too_deep.begin(), now.too_deep.end());
  for (int decl : now.cleared) m_.cleared_.insert(here(decl));
  for (const auto& [name, k] : now.returns) m_.returns_[name] = join(m_.returns_[name], k);
  for (const auto& [name, type] : now.return_types) m_.return_types_[name] = type;
  log_->runs[fn] = std::move(now);  // old_ is set only beside a log_
  return true;
}

}  // namespace lwc::analysis
