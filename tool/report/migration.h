#pragma once
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli/report.h"

namespace lwc {

// `lwcport report`: what a lead reads about a port (docs/report.md). The data is gathered by the
// command from the same analysis `lint` runs; these functions only aggregate and write it.

// A lossy shortcut left in the code (`LWCHackToFloat`, `DF*_Hack`, `LWC_HACK_TO_ZERO`).
struct MarkerSite {
  std::string path;
  int line = 0, column = 0;
  std::string marker;   // the name written
  std::string demotes;  // the text it is applied to
  std::string removal;  // whether lwcport removes it: "safe fix", "unsafe fix: why" or "by hand: why"
};

struct FileEntry {
  std::string path;
  std::string era;  // "UE4", "UE 5.0-5.3", "UE 5.4+", "HLSL", "GLSL"
  std::vector<ReportedFinding> findings;
};

// What the port costs under one scene profile.
struct SceneCost {
  std::string name;
  size_t needed = 0, not_needed = 0, safe = 0, unsafe = 0, by_hand = 0, translated = 0, df = 0;
  double minutes = 0;
};

// The counts at one commit of the tree's history.
struct HistoryPoint {
  std::string commit, date, subject;
  std::map<std::string, size_t> by_rule;
  size_t total = 0, markers = 0;
};

// A host change and the shader side it needs: the GPU member a host finding stores into, what the
// port makes it (a translated-world position or matrix), and the shader files that read it.
struct HostPair {
  std::string where;  // path:line of the host finding
  std::string rule;
  std::string parameter;
  std::string port;  // "translated-position", "translated-matrix", "high-low-position", "high-low-matrix"
  std::vector<std::string> shader_files;
};

struct MigrationReport {
  std::string scene = "default";  // the profile the findings' fixes were planned for
  std::vector<FileEntry> files;   // sorted by path
  std::vector<MarkerSite> markers;
  std::vector<SceneCost> scenes;      // one per bundled or given profile
  std::vector<HistoryPoint> history;  // oldest first; empty without --history / --since
  nlohmann::json verification;        // --verify: `lwcport verify --format json`'s functions; null without
  bool host = false;                  // --host: C++ host code was analysed (its files have the era "C++ host")
  std::vector<HostPair> host_pairs;
};

// Minutes one finding costs by this estimate: none when the scene does not need it, one to review
// a safe fix, five to review and test an unsafe one, else the rule's minutes by hand.
double effort_minutes(const ReportedFinding& f);
// The marker a lwc-hack-marker finding stands for, with the argument it demotes.
MarkerSite marker_site(const std::string& path, const ReportedFinding& f);
// What the findings of one analysis cost under a scene.
SceneCost scene_cost(const std::string& name, const std::vector<FileEntry>& files);

// What the era column means, for both written forms.
extern const char* const kEraNote;
// The era of the host code's files.
extern const char* const kHostEra;
// What the host-side work list is, for both written forms.
extern const char* const kHostSideNote;
// What the host must change for a shader finding to be ported (a uniform it uploads, a note of the
// finding's fix, a reason a rewrite was withheld that names the host), or "".
std::string host_work(const ReportedFinding& f);

// report.json (docs/report.md), and report.md and report.html written from it: the same data in
// three forms.
nlohmann::ordered_json report_json(const MigrationReport& report);
std::string report_markdown(const nlohmann::ordered_json& report);
std::string report_html(const nlohmann::ordered_json& report);

// How a host port changes what a shader parameter holds, in words ("a translated-world position").
std::string port_text(const std::string& port);

}  // namespace lwc
