// report.html: one self-contained page (inline CSS, SVG charts drawn here, a little script to
// sort and filter the tables). Nothing is fetched: it opens from a CI artifact or a mail.
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "report/migration.h"

namespace lwc {

namespace {

using json = nlohmann::ordered_json;

std::string esc(std::string_view s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&#39;"; break;
      default: out += c;
    }
  }
  return out;
}

std::string str(const json& v) { return v.is_string() ? v.get<std::string>() : v.is_number_float() ? fmt::format("{:g}", v.get<double>()) : v.dump(); }

constexpr const char* kStyle = R"(
body{font:14px/1.45 system-ui,sans-serif;margin:2em auto;max-width:1200px;padding:0 1em;color:#1d2430}
h1{font-size:1.6em}h2{margin-top:2em;border-bottom:1px solid #d7dce3;padding-bottom:.2em}
.cards{display:flex;gap:1em;flex-wrap:wrap}.card{background:#f3f5f8;border-radius:6px;padding:.7em 1.1em;min-width:9em}
.card b{display:block;font-size:1.5em}
table{border-collapse:collapse;width:100%;margin:.6em 0}th,td{border-bottom:1px solid #e3e7ec;padding:.25em .5em;text-align:left;vertical-align:top}
th{background:#f3f5f8;cursor:pointer;user-select:none}td{overflow-wrap:anywhere}td.n,th.n{text-align:right}code{font-size:.92em}
.basis{color:#4a5566;font-size:.92em}svg text{font:11px system-ui,sans-serif;fill:#1d2430}
.safe{fill:#2f9e44}.unsafe{fill:#f08c00}.hand{fill:#c92a2a}.nn{fill:#ced4da}.total{stroke:#1c7ed6;fill:none;stroke-width:2}
.markers{stroke:#c92a2a;fill:none;stroke-width:2;stroke-dasharray:4 3}.front{stroke:#2f9e44;fill:none;stroke-width:1.5}
)";

// Sorting by a header click, the rule filter (also read from `#rule=<id>` so a link can carry it).
constexpr const char* kScript = R"(
function sortBy(th){const t=th.closest('table'),i=[...th.parentNode.children].indexOf(th),b=t.tBodies[0];
const rows=[...b.rows],num=th.classList.contains('n'),dir=th.dataset.dir==='asc'?-1:1;th.dataset.dir=dir===1?'asc':'desc';
rows.sort((x,y)=>{const a=x.cells[i].dataset.v??x.cells[i].textContent,c=y.cells[i].dataset.v??y.cells[i].textContent;
return num?dir*(parseFloat(a)-parseFloat(c)):dir*a.localeCompare(c)});rows.forEach(r=>b.appendChild(r));}
function filterRule(rule){document.querySelectorAll('tr[data-rules]').forEach(r=>{
r.hidden=rule!==''&&!r.dataset.rules.split(' ').includes(rule)});
const shown=document.querySelectorAll('#findings tbody tr:not([hidden])').length;
document.getElementById('shown').textContent=shown;}
document.querySelectorAll('th').forEach(th=>th.addEventListener('click',()=>sortBy(th)));
const pick=document.getElementById('rule');pick.addEventListener('change',()=>filterRule(pick.value));
const m=location.hash.match(/rule=([\w-]+)/);if(m){pick.value=m[1];}filterRule(pick.value);
)";

std::string th(const std::vector<std::pair<std::string, bool>>& heads) {
  std::string out = "<thead><tr>";
  for (const auto& [h, numeric] : heads) out += numeric ? "<th class=n>" + esc(h) + "</th>" : "<th>" + esc(h) + "</th>";
  return out + "</tr></thead>";
}

std::string td(const json& v, bool numeric = false) {
  return numeric ? "<td class=n>" + esc(str(v)) + "</td>" : "<td>" + esc(str(v)) + "</td>";
}

// Findings by rule: a bar per rule, split into safe fix, unsafe fix and by hand.
std::string rule_chart(const json& rules) {
  if (rules.empty()) return "";
  size_t most = 1;
  for (const auto& r : rules) most = std::max(most, r["findings"].get<size_t>());
  int row = 22, left = 210, width = 520;
  std::string out = fmt::format(R"(<svg id=rule-chart role=img aria-label="findings by rule" width={} height={}>)", left + width + 60,
                                rules.size() * row + 30);
  int y = 0;
  for (const auto& r : rules) {
    double x = left;
    out += fmt::format(R"(<text x=0 y={}>{}</text>)", y + 15, esc(r["rule"].get<std::string>()));
    for (const auto& [key, cls] : {std::pair{"safe", "safe"}, {"unsafe", "unsafe"}, {"by_hand", "hand"}, {"not_needed", "nn"}}) {
      double w = width * r[key].get<double>() / most;
      if (w > 0) out += fmt::format(R"(<rect class={} x={:.1f} y={} width={:.1f} height=16><title>{} {}</title></rect>)", cls, x, y + 3, w, str(r[key]), key);
      x += w;
    }
    out += fmt::format(R"(<text x={:.1f} y={}>{}</text>)", x + 6, y + 15, str(r["findings"]));
    y += row;
  }
  out += fmt::format(R"(<rect class=safe x={} y={} width=10 height=10></rect><text x={} y={}>safe fix</text>)", left, y + 8, left + 14, y + 17);
  out += fmt::format(R"(<rect class=unsafe x={} y={} width=10 height=10></rect><text x={} y={}>unsafe fix</text>)", left + 90, y + 8, left + 104, y + 17);
  out += fmt::format(R"(<rect class=hand x={} y={} width=10 height=10></rect><text x={} y={}>by hand</text>)", left + 190, y + 8, left + 204, y + 17);
  out += fmt::format(R"(<rect class=nn x={} y={} width=10 height=10></rect><text x={} y={}>not needed</text>)", left + 280, y + 8, left + 294, y + 17);
  return out + "</svg>";
}

// The burn-down: findings and markers at each commit, oldest on the left.
std::string history_chart(const json& history) {
  if (history.empty()) return "<p>Run with <code>--history N</code> or <code>--since REV</code> for the counts over the tree's history.</p>";
  size_t most = 1;
  for (const auto& h : history) most = std::max({most, h["findings"].get<size_t>(), h["markers"].get<size_t>()});
  int w = 1100, h = 300, left = 50, bottom = 30;
  double step = history.size() > 1 ? double(w - left - 230) / (history.size() - 1) : 0;
  auto y_of = [&](double v) { return (h - bottom) - v / most * (h - bottom - 20); };
  std::string total, markers;
  for (size_t i = 0; i < history.size(); ++i) {
    double x = left + i * step;
    total += fmt::format("{}{:.1f},{:.1f}", i ? " " : "", x, y_of(history[i]["findings"].get<double>()));
    markers += fmt::format("{}{:.1f},{:.1f}", i ? " " : "", x, y_of(history[i]["markers"].get<double>()));
  }
  std::string out = fmt::format(R"(<svg id=burn-down role=img aria-label="findings over the history" width={} height={}>)", w, h);
  out += fmt::format(R"(<line x1={} y1={} x2={} y2={} stroke=#999></line>)", left, h - bottom, w - 10, h - bottom);
  out += fmt::format(R"(<text x=0 y={}>{}</text><text x=0 y={}>0</text>)", y_of(most) + 4, most, h - bottom + 4);
  out += fmt::format(R"(<polyline class=total points="{}"></polyline><polyline class=markers points="{}"></polyline>)", total, markers);
  // Each rule's own count, thin, in its own hue; the legend names them in order.
  std::set<std::string> rules;
  for (const auto& p : history)
    for (const auto& [rule, n] : p["by_rule"].items()) rules.insert(rule);
  int hue = 0, legend_y = 28;
  for (const std::string& rule : rules) {
    std::string pts;
    for (size_t i = 0; i < history.size(); ++i)
      pts += fmt::format("{}{:.1f},{:.1f}", i ? " " : "", left + i * step, y_of(history[i]["by_rule"].value(rule, 0.0)));
    std::string colour = fmt::format("hsl({},55%,45%)", hue);
    out += fmt::format(R"(<polyline class=rule points="{}" stroke="{}" fill=none stroke-width=1><title>{}</title></polyline>)", pts, colour, esc(rule));
    out += fmt::format(R"(<text x={} y={} style="fill:{}">{}</text>)", w - 200, legend_y, colour, esc(rule));
    legend_y += 13;
    hue = (hue + 47) % 360;
  }
  for (size_t i = 0; i < history.size(); ++i)
    out += fmt::format(R"(<circle cx={:.1f} cy={:.1f} r=3 fill=#1c7ed6><title>{} {}: {} findings, {} markers</title></circle>)", left + i * step,
                       y_of(history[i]["findings"].get<double>()), esc(history[i]["commit"].get<std::string>().substr(0, 10)),
                       esc(history[i]["date"].get<std::string>()), str(history[i]["findings"]), str(history[i]["markers"]));
  out += fmt::format(R"(<text x={} y={}>{}</text><text x={} y={} text-anchor=end>{}</text>)", left, h - 8,
                     esc(history.front()["date"].get<std::string>().substr(0, 10)), w - 10, h - 8,
                     esc(history.back()["date"].get<std::string>().substr(0, 10)));
  out += fmt::format(R"(<text x={} y=14 style="fill:#1c7ed6">findings</text><text x={} y=14 style="fill:#c92a2a">markers (dashed)</text>)", left + 10, left + 90);
  return out + "</svg>";
}

// Whether a variant has a cost and an error to plot.
bool plottable(const json& v, const char* error) {
  return v[error].is_number() && v["spirvInstructions"].is_number() && v["spirvInstructions"].get<double>() > 0;
}

// One verified function: each variant's error against its cost, the Pareto front joined. The error
// is the largest distance from the float64 reference where the function has world outputs, else
// the largest error in ULPs.
std::string verify_chart(const json& fn) {
  const char* error = "maxError";
  if (std::none_of(fn["variants"].begin(), fn["variants"].end(), [&](const json& v) { return plottable(v, error); })) error = "maxUlps";
  std::vector<std::tuple<double, double, std::string, bool>> points;  // cost, error, label, on the front
  for (const auto& v : fn["variants"])
    if (plottable(v, error))
      points.emplace_back(v["spirvInstructions"].get<double>(), std::max(v[error].get<double>(), 1e-12), v["variant"].get<std::string>(),
                          v.value("paretoFront", false));
  if (points.empty()) return "<p>No variant ran to a result to plot.</p>";
  double cmin = 1e300, cmax = 0, emin = 1e300, emax = 0;
  for (const auto& [c, e, l, f] : points) cmin = std::min(cmin, c), cmax = std::max(cmax, c), emin = std::min(emin, e), emax = std::max(emax, e);
  int w = 460, h = 240, left = 60, bottom = 30;
  auto x_of = [&](double c) { return left + (cmax > cmin ? (c - cmin) / (cmax - cmin) : 0.5) * (w - left - 140); };
  double lmin = std::log10(emin), lmax = std::log10(emax);
  auto y_of = [&](double e) { return (h - bottom) - (lmax > lmin ? (std::log10(e) - lmin) / (lmax - lmin) : 0.5) * (h - bottom - 30); };
  std::string out = fmt::format(R"(<svg class=verify role=img aria-label="error against cost" width={} height={}>)", w, h);
  out += fmt::format(R"(<line x1={} y1={} x2={} y2={} stroke=#999></line><line x1={} y1=10 x2={} y2={} stroke=#999></line>)", left, h - bottom,
                     w - 10, h - bottom, left, left, h - bottom);
  out += fmt::format(R"(<text x={} y={}>SPIR-V instructions</text><text x=0 y=14>{}</text>)", left, h - 6,
                     error == std::string("maxError") ? "max error (cm, log)" : "max error (ULPs, log)");
  std::vector<std::pair<double, double>> front;
  for (const auto& [c, e, l, f] : points) {
    out += fmt::format(R"(<circle cx={:.1f} cy={:.1f} r=4 fill={}><title>{}: {:g} instructions, error {:.3g}</title></circle>)", x_of(c), y_of(e),
                       f ? "#2f9e44" : "#868e96", esc(l), c, e);
    if (f) front.emplace_back(x_of(c), y_of(e));
  }
  std::sort(front.begin(), front.end());
  if (!front.empty()) {
    std::string pts;
    for (const auto& [x, y] : front) pts += fmt::format("{:.1f},{:.1f} ", x, y);
    out += fmt::format(R"(<polyline class=front points="{}"></polyline>)", pts);
  }
  return out + "</svg>";
}

}  // namespace

std::string report_html(const json& j) {
  std::string scene = j["scene"];
  const json& s = j["summary"];
  std::string out = "<!DOCTYPE html><html lang=en><head><meta charset=utf-8><title>lwcport migration report</title><style>";
  out += kStyle;
  out += "</style></head><body><h1>lwcport migration report</h1>";
  out += "<div class=cards>";
  for (const auto& [label, value] : std::vector<std::pair<std::string, std::string>>{
           {"files", str(s["files"])}, {"findings", str(s["findings"])}, {"safe fix", str(s["safe"])}, {"unsafe fix", str(s["unsafe"])},
           {"by hand", str(s["by_hand"])}, {"not needed", str(s["not_needed"])}, {"markers", std::to_string(j["markers"].size())},
           {"estimated hours", str(j["effort"]["hours"])}})
    out += "<div class=card><b>" + esc(value) + "</b>" + esc(label) + "</div>";
  out += "</div>";
  out += fmt::format("<p>{} error(s), {} warning(s), {} note(s); fixes planned for scene <code>{}</code>.</p>", str(s["error"]), str(s["warning"]),
                     str(s["note"]), esc(scene));
  out += "<p class=basis>Effort: " + esc(j["effort"]["basis"].get<std::string>()) + ".</p>";

  out += "<h2>Findings by rule</h2>" + rule_chart(s["by_rule"]);
  out += "<table id=rules>" + th({{"rule", false}, {"findings", true}, {"error", true}, {"warning", true}, {"note", true}, {"safe fix", true},
                                   {"unsafe fix", true}, {"by hand", true}, {"minutes", true}}) + "<tbody>";
  for (const auto& row : s["by_rule"])
    out += "<tr data-rules=\"" + esc(row["rule"].get<std::string>()) + "\"><td><code>" + esc(row["rule"].get<std::string>()) + "</code></td>" +
           td(row["findings"], true) + td(row["error"], true) + td(row["warning"], true) + td(row["note"], true) + td(row["safe"], true) +
           td(row["unsafe"], true) + td(row["by_hand"], true) + td(row["minutes"], true) + "</tr>";
  out += "</tbody></table>";

  out += "<h2>Files by era</h2><p class=basis>" + esc(kEraNote) + "</p><table id=eras>" + th({{"era", false}, {"files", true}}) + "<tbody>";
  for (const auto& [era, count] : s["eras"].items()) out += "<tr>" + td(era) + td(count, true) + "</tr>";
  out += "</tbody></table>";

  out += fmt::format("<h2>Marker ledger ({})</h2>", j["markers"].size());
  if (j["markers"].empty()) out += "<p>No <code>LWCHackToFloat</code>, <code>DF*_Hack</code> or <code>LWC_HACK_TO_ZERO</code> left.</p>";
  else {
    out += "<table id=markers>" + th({{"where", false}, {"marker", false}, {"demotes", false}, {"removal", false}}) + "<tbody>";
    for (const auto& m : j["markers"])
      out += "<tr>" + td(m["path"].get<std::string>() + ":" + str(m["line"])) + "<td><code>" + esc(m["marker"].get<std::string>()) + "</code></td><td><code>" +
             esc(m["demotes"].get<std::string>()) + "</code></td>" + td(m["removal"]) + "</tr>";
    out += "</tbody></table>";
  }

  out += fmt::format("<h2>Host-side work ({})</h2>", j["host_side"].size());
  if (j["host_side"].empty()) out += "<p>No value the shaders read needs the host to hand it over differently.</p>";
  else {
    out += "<p class=basis>" + esc(kHostSideNote) + "</p><table id=host-side>" +
           th({{"where", false}, {"rule", false}, {"value", false}, {"what the host must do", false}}) + "<tbody>";
    for (const auto& h : j["host_side"])
      out += "<tr>" + td(h["path"].get<std::string>() + ":" + str(h["line"])) + "<td><code>" + esc(h["rule"].get<std::string>()) +
             "</code></td><td><code>" + esc(h["value"].get<std::string>()) + "</code></td>" + td(h["needs"]) + "</tr>";
    out += "</tbody></table>";
  }

  if (!j["scenes"].empty()) {
    out += "<h2>What each scene needs</h2><table id=scenes>" +
           th({{"scene", false}, {"needed", true}, {"not needed", true}, {"safe fix", true}, {"unsafe fix", true}, {"by hand", true},
               {"translated", true}, {"DoubleFloat", true}, {"minutes", true}}) + "<tbody>";
    for (const auto& c : j["scenes"])
      out += "<tr>" + td(c["name"]) + td(c["needed"], true) + td(c["not_needed"], true) + td(c["safe"], true) + td(c["unsafe"], true) +
             td(c["by_hand"], true) + td(c["translated"], true) + td(c["df"], true) + td(c["minutes"], true) + "</tr>";
    out += "</tbody></table>";
  }

  if (j["host"].is_object()) {
    const auto& h = j["host"];
    out += fmt::format("<h2>Host code</h2><p><code>lwcport host</code>: {} finding(s) in {} C++ file(s). A translated-world or high/low port changes "
                       "both sides at once: each host change below and the shaders that read what it uploads.</p>",
                       str(h["findings"]), str(h["files"]));
    out += "<table id=host>" + th({{"host change", false}, {"shader parameter", false}, {"the shaders must read it as", false}, {"shader files that read it", false}}) +
           "<tbody>";
    for (const auto& p : h["pairs"]) {
      std::string files;
      for (const auto& f : p["shader_files"]) files += (files.empty() ? "" : ", ") + f.get<std::string>();
      std::string port = port_text(p["port"]);
      out += "<tr data-rules=\"" + esc(p["rule"].get<std::string>()) + "\">" + td(p["where"]) + "<td><code>" + esc(p["parameter"].get<std::string>()) +
             "</code></td>" + td(port) + td(files.empty() ? "none found" : files) + "</tr>";
    }
    out += "</tbody></table>";
  }

  out += "<h2>Burn-down</h2>" + history_chart(j["history"]);

  std::vector<json> ranked(j["files"].begin(), j["files"].end());
  std::stable_sort(ranked.begin(), ranked.end(), [](const json& a, const json& b) { return a["minutes"].get<double>() > b["minutes"].get<double>(); });
  out += "<h2>Top offenders</h2><table id=offenders>" + th({{"file", false}, {"era", false}, {"findings", true}, {"by hand", true}, {"minutes", true}}) + "<tbody>";
  for (size_t i = 0; i < ranked.size() && i < 10 && ranked[i]["findings"].get<size_t>() > 0; ++i)
    out += "<tr>" + td(ranked[i]["path"]) + td(ranked[i]["era"]) + td(ranked[i]["findings"], true) + td(ranked[i]["by_hand"], true) +
           td(ranked[i]["minutes"], true) + "</tr>";
  out += "</tbody></table>";
  size_t not_needed = s["not_needed"].get<size_t>();
  if (not_needed) {
    out += fmt::format("<h2>Not needed at scene <code>{}</code> ({})</h2><p>The scene's numbers show float32 is precise enough at these "
                       "sites: they are reported as notes and cost nothing.</p><table id=not-needed>",
                       esc(scene), not_needed) + th({{"where", false}, {"rule", false}, {"finding", false}}) + "<tbody>";
    for (const auto& f : j["findings"])
      if (f["fix"] == "not needed")
        out += "<tr>" + td(f["path"].get<std::string>() + ":" + str(f["line"])) + "<td><code>" + esc(f["rule"].get<std::string>()) + "</code></td>" +
               td(f["message"]) + "</tr>";
    out += "</tbody></table>";
  }

  // The rule filter applies to the tables below.
  out += "<h2>Files</h2><p><label>Rule: <select id=rule><option value=\"\">every rule</option>";
  for (const auto& row : s["by_rule"]) out += "<option>" + esc(row["rule"].get<std::string>()) + "</option>";
  out += "</select></label> <span id=shown></span> finding(s) shown.</p>";
  out += "<table id=directories>" + th({{"directory", false}, {"files", true}, {"findings", true}, {"by hand", true}, {"minutes", true}}) + "<tbody>";
  for (const auto& d : j["directories"])
    out += "<tr data-rules=\"" + esc(fmt::format("{}", fmt::join(d["rules"].get<std::vector<std::string>>(), " "))) + "\">" + td(d["path"]) + td(d["files"], true) + td(d["findings"], true) + td(d["by_hand"], true) + td(d["minutes"], true) + "</tr>";
  out += "</tbody></table>";
  out += "<table id=files>" + th({{"file", false}, {"era", false}, {"findings", true}, {"safe fix", true}, {"unsafe fix", true}, {"by hand", true}, {"minutes", true}}) + "<tbody>";
  for (const auto& f : j["files"]) {
    std::vector<std::string> rules;
    for (const auto& [rule, count] : f["by_rule"].items()) rules.push_back(rule);
    out += "<tr data-rules=\"" + esc(fmt::format("{}", fmt::join(rules, " "))) + "\">" + td(f["path"]) + td(f["era"]) + td(f["findings"], true) + td(f["safe"], true) + td(f["unsafe"], true) +
           td(f["by_hand"], true) + td(f["minutes"], true) + "</tr>";
  }
  out += "</tbody></table>";
  out += "<h2>Findings</h2><table id=findings>" + th({{"where", false}, {"rule", false}, {"severity", false}, {"fix", false}, {"message", false}}) + "<tbody>";
  for (const auto& f : j["findings"])
    out += "<tr data-rules=\"" + esc(f["rule"].get<std::string>()) + "\">" + td(f["path"].get<std::string>() + ":" + str(f["line"]) + ":" + str(f["column"])) +
           "<td><code>" + esc(f["rule"].get<std::string>()) + "</code></td>" + td(f["severity"]) + td(f["fix"]) + td(f["message"]) + "</tr>";
  out += "</tbody></table>";

  if (j["verification"].is_array()) {
    out += "<h2>Verification</h2><p>Each function run on the Vulkan device (lavapipe) as written and as each rewrite, against a float64 "
           "reference: its largest error against its cost; the Pareto front is green.</p>";
    for (const auto& fn : j["verification"]) {
      out += "<h3><code>" + esc(fn.value("function", std::string())) + "</code> <small>" + esc(fn.value("file", std::string())) + "</small></h3>";
      out += verify_chart(fn);
      out += "<table class=verdicts>" + th({{"variant", false}, {"status", false}, {"max error", true}, {"SPIR-V instructions", true}}) + "<tbody>";
      for (const auto& v : fn["variants"])
        out += "<tr>" + td(v["variant"]) + td(v["status"]) + td(v["maxError"], true) + td(v["spirvInstructions"], true) + "</tr>";
      out += "</tbody></table><p>" + esc(fn.value("pick", std::string())) + "</p>";
    }
  }
  out += "<script>";
  out += kScript;
  out += "</script></body></html>\n";
  return out;
}

}  // namespace lwc
