#include "cli/verify_report.h"

#include "cli/report.h"


#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>

namespace lwc {

namespace {

constexpr double kU = 0x1p-24;

const char* lang_label(Lang lang) { return lang == Lang::glsl ? "GLSL" : "HLSL"; }

const char* family_name(InputFamily f) {
  switch (f) {
    case InputFamily::sum: return "any";
    case InputFamily::ordered: return "|a| >= |b|";
    case InputFamily::same_sign: return "same signs";
    case InputFamily::opposite: return "opposite signs";
    case InputFamily::close: return "close, same sign";
    case InputFamily::product: return "2^-40..2^40";
    case InputFamily::quotient: return "2^-40..2^40";
    case InputFamily::positive: return "positive";
    case InputFamily::uncanonical: return "Low beyond an ULP";
    case InputFamily::tile_offset: return "tiles to 2^22";
    case InputFamily::world: return "to 2^43, tile edges";
  }
  return "";
}

// The kind of a variant's result: its status up to the reason ("fail", "incomplete", "unchanged").
std::string status_kind(const std::string& status) { return status.substr(0, status.find(':')); }

std::string short_status(const std::string& status) {
  if (status.rfind("reported", 0) == 0) return "reported";
  if (status.rfind("error", 0) == 0) return "error";
  return status;
}

}  // namespace

std::string format_relative_error(double relative) {
  if (relative == 0) return "0";
  if (!std::isfinite(relative)) return "inf";
  if (relative >= 0.01 * kU) return fmt::format("{:.3g}u", relative / kU);
  return fmt::format("{:.3g}u^2", relative / (kU * kU));
}

void print_library_text(std::ostream& out, const std::string& device, const DriverProbes& probes,
                        const LibraryAccuracy& accuracy, size_t inputs) {
  out << fmt::format("DoubleFloat library on {}\n\nDriver probes:\n", device);
  for (const std::string& line : describe_probes(probes)) out << "  " << line << '\n';
  out << "\nSPIR-V: ";
  bool first = true;
  for (const auto& [lang, losses] : accuracy.contraction_losses) {
    out << (first ? "" : "; ")
        << fmt::format("{} error-free function(s) in {}, {}", accuracy.error_free_functions_checked.at(lang), lang_label(lang),
                       losses.empty() ? "every float operation carries NoContraction" : fmt::format("{} lost NoContraction", losses.size()));
    first = false;
  }
  out << '\n';
  for (const auto& [lang, losses] : accuracy.contraction_losses)
    for (const std::string& loss : losses) out << fmt::format("  {}: {}\n", lang_label(lang), loss);

  out << fmt::format("\n{} inputs per operation (named adversarial cases first, then random); relative error against a "
                     "double-double reference, u = 2^-24\n\n", inputs);
  std::vector<Lang> langs;
  if (!accuracy.ops.empty())
    for (const auto& [lang, m] : accuracy.ops.front().by_lang) langs.push_back(lang);
  std::string header = fmt::format("{:<33} {:<17}", "operation", "inputs");
  for (Lang lang : langs) header += fmt::format(" {:>9} {:>9}", fmt::format("{} max", lang_label(lang)), "median");
  out << header << fmt::format("  {:<40} {}\n", "published bound", "result");
  // Inputs outside the library's domain that miss the bound, by reason: "op (misses of inputs)".
  struct OutsideList {
    std::vector<std::string> entries;
    std::string example;
  } beyond_split_limit, denormal_range;
  auto note_outside = [](OutsideList& list, const std::string& op, const OpMeasurement::Outside& o) {
    if (!o.misses) return;
    std::string entry = fmt::format("{} ({} of {})", op, o.misses, o.inputs);
    if (std::find(list.entries.begin(), list.entries.end(), entry) == list.entries.end()) list.entries.push_back(entry);
    if (list.example.empty()) list.example = o.example;
  };
  std::vector<std::string> details;
  for (const OpReport& r : accuracy.ops) {
    std::string row = fmt::format("{:<33} {:<17}", r.op->name(), family_name(r.op->inputs));
    std::string result;
    for (Lang lang : langs) {
      const OpMeasurement& m = r.by_lang.at(lang);
      row += fmt::format(" {:>9} {:>9}", format_relative_error(m.max_relative), format_relative_error(m.median_relative));
      std::string s = short_status(m.status);
      if (result.empty()) result = s;
      else if (result != s) result += "/" + s;
      note_outside(beyond_split_limit, r.op->name(), m.beyond_split_limit);
      note_outside(denormal_range, r.op->name(), m.denormal_range);
      if (m.status != "pass") {
        std::string why = m.status;
        if (m.non_canonical) why += fmt::format(" ({} results not canonical)", m.non_canonical);
        details.push_back(fmt::format("{} [{}]: {}\n    worst: {}", r.op->name(), lang_label(lang), why, m.worst));
      }
    }
    out << row << fmt::format("  {:<40} {}\n", r.op->bound.text, result);
  }
  if (!details.empty()) {
    out << '\n';
    for (const std::string& d : details) out << d << '\n';
  }
  if (!beyond_split_limit.entries.empty())
    out << fmt::format("\nOutside the domain: beyond Dekker's split limit (|operand| above 8.3e34, where 4097 * A overflows) these "
                       "miss the bound, their inputs counted apart (world values stay below 2^43 cm, their products below 2^86): {}\n"
                       "  e.g. {}\n", fmt::join(beyond_split_limit.entries, ", "), beyond_split_limit.example);
  if (!denormal_range.entries.empty())
    out << fmt::format("\nOutside the domain: this driver flushes denormals (Vulkan allows it), so with low parts below 2^-126 "
                       "these miss the bound, their inputs counted apart (world values, and their error terms, stay far above "
                       "2^-100 cm): {}\n  e.g. {}\n", fmt::join(denormal_range.entries, ", "), denormal_range.example);
  out << fmt::format("\n{}: pipelines {:.2f} s, dispatches {:.2f} s.\n",
                     accuracy.failed() ? "FAILED" : "All bounds hold", accuracy.pipeline_seconds, accuracy.dispatch_seconds);
}

namespace {
nlohmann::json outside_json(const OpMeasurement::Outside& o) {
  return {{"inputs", o.inputs}, {"missingTheBound", o.misses}, {"example", o.example}};
}
}  // namespace

void print_library_json(std::ostream& out, const std::string& device, const DriverProbes& probes,
                        const LibraryAccuracy& accuracy, size_t inputs) {
  using nlohmann::json;
  json j;
  j["device"] = device;
  j["probes"] = {{"inputs", DriverProbes::kInputs},
                 {"reassociates", probes.reassociates()},
                 {"reassociatedInputs", probes.reassociated},
                 {"fusesFma", probes.fuses_fma()},
                 {"fmaFusedInputs", probes.fma_fused},
                 {"keepsDenormals", probes.keeps_denormals()},
                 {"denormalsKeptInputs", probes.denormals_kept},
                 {"summary", describe_probes(probes)}};
  json contraction = json::object();
  for (const auto& [lang, losses] : accuracy.contraction_losses)
    contraction[std::string(lang_name(lang))] = {{"errorFreeFunctions", accuracy.error_free_functions_checked.at(lang)}, {"losses", losses}};
  j["noContraction"] = contraction;
  j["inputsPerOperation"] = inputs;
  json ops = json::array();
  for (const OpReport& r : accuracy.ops) {
    json results = json::object();
    for (const auto& [lang, m] : r.by_lang)
      results[std::string(lang_name(lang))] = {{"status", m.status},
                                  {"maxRelativeError", m.max_relative},
                                  {"medianRelativeError", m.median_relative},
                                  {"maxErrorOverBound", std::isfinite(m.max_bound_ratio) ? json(m.max_bound_ratio) : json(nullptr)},
                                  {"nonCanonicalResults", m.non_canonical},
                                  {"outsideDomain", {{"beyondSplitLimit", outside_json(m.beyond_split_limit)},
                                                     {"denormalRange", outside_json(m.denormal_range)}}},
                                  {"inputs", m.inputs},
                                  {"worst", m.worst}};
    ops.push_back({{"operation", r.op->name()}, {"inputs", family_name(r.op->inputs)}, {"bound", r.op->bound.text},
                   {"needsFusedFma", r.op->needs_fused_fma}, {"results", results}});
  }
  j["operations"] = ops;
  j["timing"] = {{"pipelineSeconds", accuracy.pipeline_seconds}, {"dispatchSeconds", accuracy.dispatch_seconds}};
  j["failed"] = accuracy.failed();
  out << json_text(j, 2) << '\n';
}

namespace {
std::string cm(double x) { return std::isfinite(x) ? fmt::format("{:.3g} cm", x) : "inf"; }
struct TimeSplit {
  double compile = 0, pipeline = 0, dispatch = 0;
};
TimeSplit time_split(const std::vector<FunctionResult>& results) {
  TimeSplit t;
  for (const FunctionResult& r : results) t.compile += r.compile_seconds, t.pipeline += r.pipeline_seconds, t.dispatch += r.dispatch_seconds;
  return t;
}

}  // namespace

void print_functions_text(std::ostream& out, const std::string& device, const DriverProbes& probes,
                          const std::vector<FunctionResult>& results, double wall_seconds, bool explain) {
  out << fmt::format("Verification on {}\n\n", device);
  // The verdicts first, one line per function; the tables and the reasons follow.
  for (const FunctionResult& r : results) {
    std::vector<std::string> verdicts;
    for (const VariantResult& v : r.variants) {
      std::string kind = status_kind(v.status);
      std::string size = !v.measured ? "" : v.world_outputs ? cm(v.max_error) : v.max_ulps > 0 ? fmt::format("{:.3g} ULPs", v.max_ulps) : "";
      verdicts.push_back(size.empty() ? fmt::format("{} {}", v.label, kind) : fmt::format("{} {} ({})", v.label, kind, size));
    }
    out << fmt::format("{}: {}: {}\n", r.file, r.function, fmt::join(verdicts, "; "));
  }
  out << "\nDriver probes:\n";
  for (const std::string& line : describe_probes(probes)) out << "  " << line << '\n';
  size_t variants = 0;
  std::vector<std::pair<std::string, size_t>> statuses;  // each kind of result, in order of first appearance
  for (const FunctionResult& r : results) {
    out << fmt::format("\n{}: {} (reference: {})\n", r.file, r.function, r.reference);
    if (explain)
      for (const std::string& input : r.inputs) out << "  input " << input << '\n';
    size_t w = 20;  // the label column fits the longest label
    for (const VariantResult& v : r.variants) w = std::max(w, v.label.size());
    out << fmt::format("  {:<{}} {:>11} {:>11} {:>11} {:>10} {:>13} {:>7}  {:<6} {}\n", "variant", w, "max error", "median", "own max",
                       "max ULPs", "ns/inv", "SPIR-V", "Pareto", "result");
    std::vector<std::string> details;
    for (const VariantResult& v : r.variants) {
      ++variants;
      std::string kind = status_kind(v.status);
      auto counted = std::find_if(statuses.begin(), statuses.end(), [&](const auto& s) { return s.first == kind; });
      if (counted == statuses.end()) statuses.emplace_back(kind, 1);
      else ++counted->second;
      std::string result = v.status.size() > 40 ? kind : v.status;
      if (!v.measured) {
        out << fmt::format("  {:<{}} {:>11} {:>11} {:>11} {:>10} {:>13} {:>7}  {:<6} {}\n", v.label, w, "-", "-", "-", "-", "-", "-", "", result);
        details.push_back(fmt::format("{}: {}", v.label, v.status));
        continue;
      }
      if (v.mismatches) result += fmt::format(" ({} decision(s) differ)", v.mismatches);
      // Without an output in world units the cm columns say so ("-"), never "0 cm" beside a failure.
      auto world = [&](double x) { return v.world_outputs ? cm(x) : std::string("-"); };
      // The median run time over the interleaved rounds, and their spread.
      std::string cost = r.timing.empty() ? fmt::format("{:.3g} ±{:.0f}%", v.ns_per_invocation, 50 * v.cost_spread) : "-";
      out << fmt::format("  {:<{}} {:>11} {:>11} {:>11} {:>10.3g} {:>13} {:>7}  {:<6} {}\n", v.label, w, world(v.max_error), world(v.median_error),
                         world(v.own_max_error), v.max_ulps, cost, v.spirv_instructions, v.pareto ? "*" : "", result);
      if (v.status != "pass" && !v.worst.empty()) details.push_back(fmt::format("{}: worst {}", v.label, v.worst));
      for (const std::string& loss : v.contraction_losses) details.push_back(fmt::format("{}: {}", v.label, loss));
    }
    out << fmt::format("  scene pick: {}\n", r.pick);
    if (!r.timing.empty()) out << fmt::format("  {}\n", r.timing);
    else out << fmt::format("  run time: median of {} interleaved rounds, ± half its 95% confidence interval\n", r.timing_rounds);
    for (const std::string& d : details) out << "    " << d << '\n';
  }
  // Every kind of result is counted: pass (within the scene's precision), input-limited (right on
  // the inputs it is handed, held back by float32 inputs its callers pass), fail, incomplete, does
  // not compile, did not run, timed only (no reference), not verifiable.
  std::vector<std::string> counts;
  for (const auto& [kind, count] : statuses) counts.push_back(fmt::format("{} {}", count, kind));
  out << fmt::format("\nVerified {} function(s), {} variant(s){}{}.\n", results.size(), variants, counts.empty() ? "" : ": ",
                     fmt::join(counts, ", "));
  TimeSplit t = time_split(results);
  out << fmt::format("Time: {:.1f} s, {:.2f} function(s) per second; glslang {:.1f} s, pipelines and JIT {:.1f} s, dispatches {:.1f} s.\n",
                     wall_seconds, results.size() / wall_seconds, t.compile, t.pipeline, t.dispatch);
}

void print_functions_json(std::ostream& out, const std::string& device, const DriverProbes& probes,
                          const std::vector<FunctionResult>& results, double wall_seconds) {
  using nlohmann::json;
  json fns = json::array();
  auto number = [](double x) { return std::isfinite(x) ? json(x) : json(nullptr); };
  for (const FunctionResult& r : results) {
    json vs = json::array();
    for (const VariantResult& v : r.variants)
      vs.push_back({{"variant", v.label}, {"status", v.status}, {"measured", v.measured}, {"maxError", v.world_outputs ? number(v.max_error) : nullptr},
                    {"medianError", v.world_outputs ? number(v.median_error) : nullptr}, {"maxUlps", number(v.max_ulps)},
                    {"ownMaxError", v.world_outputs ? number(v.own_max_error) : nullptr}, {"ownMaxUlps", number(v.own_max_ulps)},
                    {"decisionMismatches", v.mismatches}, {"worstOverTarget", number(v.worst_over_target)},
                    {"nsPerInvocation", r.timing.empty() ? json(v.ns_per_invocation) : json(nullptr)}, {"costSpread", v.cost_spread},
                    {"pipelineSeconds", v.pipeline_seconds},
                    {"spirvInstructions", v.spirv_instructions}, {"paretoFront", v.pareto},
                    {"contractionLosses", v.contraction_losses}, {"worst", v.worst}});
    fns.push_back({{"file", r.file}, {"function", r.function}, {"reference", r.reference}, {"inputs", r.inputs}, {"pick", r.pick},
                   {"timingRounds", r.timing_rounds}, {"timingProblem", r.timing}, {"variants", vs}});
  }
  TimeSplit t = time_split(results);
  json time = {{"wallSeconds", wall_seconds}, {"functionsPerSecond", results.size() / wall_seconds}, {"compileSeconds", t.compile},
               {"pipelineSeconds", t.pipeline}, {"dispatchSeconds", t.dispatch}};
  json j = {{"device", device}, {"probes", describe_probes(probes)}, {"functions", fns}, {"time", time}};
  out << json_text(j, 2) << '\n';
}

}  // namespace lwc
