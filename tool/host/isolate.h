#pragma once
#include <functional>
#include <string>

namespace lwc::host {

// Runs `work(i)` for each i < count, each in a process of its own (at most `jobs` at once), and
// hands what it returned to `done(i, bytes)` in this process, in the order the units finish. A
// unit whose process crashes, is killed or runs past `cpu_seconds` of CPU goes to
// `failed(i, why)` instead: one bad unit costs its own findings, never the run's. The caller must
// have no other threads (each unit's process starts as a copy of this one).
void run_isolated(size_t count, unsigned jobs, unsigned cpu_seconds, const std::function<std::string(size_t)>& work,
                  const std::function<void(size_t, std::string&&)>& done, const std::function<void(size_t, const std::string&)>& failed);

}  // namespace lwc::host
