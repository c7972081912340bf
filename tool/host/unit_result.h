#pragma once
#include <map>
#include <string>
#include <vector>

#include "host/host.h"
#include "host/member_values.h"

namespace lwc::host {

// A finding that rests on a member's name alone: it waits for the whole run's values for that
// member (member_values.h).
struct RestingFinding {
  std::string path;
  Finding finding;
  std::string member;
};

// What one translation unit gives the run. It is made in the unit's own process and passed
// back whole as bytes (to_bytes, from_bytes).
struct UnitResult {
  std::map<std::string, HostFile> files;  // by absolute path: the findings that stand alone, the comments, the text
  std::vector<RestingFinding> resting;
  MemberValues given;      // what the unit gives members judged by name
  std::string error;       // why Clang could not compile the unit (its first error), "" when it did
  std::vector<std::string> notes;  // what was changed in its command, and why (a precompiled header read as its header)
};

std::string to_bytes(const UnitResult& result);
// Throws when the bytes are not a whole UnitResult.
UnitResult from_bytes(const std::string& bytes);

}  // namespace lwc::host
