#include "host/unit_result.h"

#include <nlohmann/json.hpp>

namespace lwc {

// The whole of a finding, byte spans and all: the wire between a unit's process and the run.
using nlohmann::json;

static void to_json(json& j, const Span& s) { j = json::array({s.begin, s.end}); }
static void from_json(const json& j, Span& s) { s = {j.at(0).get<uint32_t>(), j.at(1).get<uint32_t>()}; }

static void to_json(json& j, const Edit& e) { j = {{"span", e.span}, {"text", e.text}, {"path", e.path}}; }
static void from_json(const json& j, Edit& e) {
  j.at("span").get_to(e.span);
  j.at("text").get_to(e.text);
  j.at("path").get_to(e.path);
}

static void to_json(json& j, const Fix& f) {
  j = {{"title", f.title},       {"safe", f.applicability == Applicability::safe}, {"reason", f.reason}, {"strategy", f.strategy},
       {"edits", f.edits},       {"library", f.library},                          {"notes", f.notes}};
}
static void from_json(const json& j, Fix& f) {
  j.at("title").get_to(f.title);
  f.applicability = j.at("safe").get<bool>() ? Applicability::safe : Applicability::unsafe;
  j.at("reason").get_to(f.reason);
  j.at("strategy").get_to(f.strategy);
  j.at("edits").get_to(f.edits);
  j.at("library").get_to(f.library);
  j.at("notes").get_to(f.notes);
}

static void to_json(json& j, const Finding& f) {
  j = {{"rule", f.rule},         {"severity", static_cast<int>(f.severity)}, {"span", f.span},         {"message", f.message},
       {"hint", f.hint},         {"fixes", f.fixes},                         {"withheld", f.withheld}, {"decision", f.decision},
       {"not_needed", f.not_needed}, {"facts", f.facts},                     {"related", f.related}};
}
static void from_json(const json& j, Finding& f) {
  j.at("rule").get_to(f.rule);
  f.severity = static_cast<Severity>(j.at("severity").get<int>());
  j.at("span").get_to(f.span);
  j.at("message").get_to(f.message);
  j.at("hint").get_to(f.hint);
  j.at("fixes").get_to(f.fixes);
  j.at("withheld").get_to(f.withheld);
  j.at("decision").get_to(f.decision);
  j.at("not_needed").get_to(f.not_needed);
  j.at("facts").get_to(f.facts);
  j.at("related").get_to(f.related);
}

static void to_json(json& j, const HostFile& f) { j = {{"text", f.text}, {"findings", f.findings}, {"comments", f.comments}}; }
static void from_json(const json& j, HostFile& f) {
  j.at("text").get_to(f.text);
  j.at("findings").get_to(f.findings);
  j.at("comments").get_to(f.comments);
}

namespace host {

std::string to_bytes(const UnitResult& r) {
  json resting = json::array(), given = json::object();
  for (const RestingFinding& f : r.resting) resting.push_back({{"path", f.path}, {"finding", f.finding}, {"member", f.member}});
  for (const auto& [key, counts] : r.given) given[key] = {counts.world, counts.not_world};
  json j = {{"files", r.files}, {"resting", resting}, {"given", given}, {"error", r.error}, {"notes", r.notes}};
  std::vector<uint8_t> cbor = json::to_cbor(j);
  return std::string(cbor.begin(), cbor.end());
}

UnitResult from_bytes(const std::string& bytes) {
  json j = json::from_cbor(bytes);
  UnitResult r;
  j.at("files").get_to(r.files);
  for (const json& f : j.at("resting")) r.resting.push_back({f.at("path"), f.at("finding").get<Finding>(), f.at("member")});
  for (const auto& [key, counts] : j.at("given").items()) r.given[key] = {counts.at(0).get<unsigned>(), counts.at(1).get<unsigned>()};
  j.at("error").get_to(r.error);
  j.at("notes").get_to(r.notes);
  return r;
}

}  // namespace host
}  // namespace lwc
