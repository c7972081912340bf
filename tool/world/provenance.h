#pragma once
// Where a value's world-space kind comes from, read back from a finished WorldModel: the chain
// from an expression to the data that made it what it is (`View.WorldCameraOrigin`, a uniform
// named as a world matrix, a call of `mul`, an assignment). For the editor's hover and a
// finding's related locations.
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "world/model.h"

namespace lwc {

// What a kind means, in words ("an absolute world position").
std::string kind_words(Kind kind);

struct ProvenanceStep {
  Span span;         // where this step is in the file
  std::string text;  // what happens there, in Markdown ("through `mul` (line 12)")
};

// Reads where values come from in one model: one tracer serves every node of the file (it
// indexes the file's functions once).
class ProvenanceTracer {
 public:
  explicit ProvenanceTracer(const WorldModel& model);
  // The steps from `node` back to where its kind comes from, nearest first (at most eight). A
  // node whose kind is unknown or small has none.
  std::vector<ProvenanceStep> trace(int node);

 private:
  int step(int node);
  int step_identifier(int node);
  int defining(int var, int use) const;
  int returned_value(int function) const;
  // An argument a call in the file gives this parameter, of the kind the parameter holds, or -1.
  int argument_for(int var);
  int strongest_child(int node) const;
  // The classified value of most concern anywhere inside `node`, or -1.
  int strongest_inside(int node) const;
  // Why an unknown function returns what it does, in words ("" when the model does not say).
  std::string return_basis(const std::string& name) const;
  const WorldData::Source* source_for(const Path& path, bool declared_global = false) const;
  std::string code(int node) const;
  int line(int node) const;
  void add(int node, std::string text);

  const WorldModel& m_;
  const SyntaxTree& t_;
  std::map<std::string, int, std::less<>> functions_;  // name -> its first definition
  std::optional<std::map<std::string, std::vector<int>, std::less<>>> calls_;  // name -> its calls, built on first use
  std::vector<ProvenanceStep> steps_;
  std::set<int> seen_;
};

// The innermost value the model classified at `offset` (an expression, or a declared variable's
// name), or -1.
int value_node_at(const WorldModel& model, uint32_t offset);

// The node a finding at `span` is about: the classified expression, declared name or function name
// (what it returns) with exactly that span; -1 when none.
int value_node_for(const WorldModel& model, Span span);

// The kind of a value node from value_node_at: its recorded kind, or a declared variable's.
Kind value_kind(const WorldModel& model, int node);

}  // namespace lwc
