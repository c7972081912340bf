#pragma once
#include <functional>
#include <string>

namespace lwc::host {

// Runs `work(i)` for each i < count in worker processes (at most `jobs`, each taking units one
// after another), and hands what it returned to `done(i, bytes)` in this process, in the order the
// units finish. A unit during which its worker crashes, is killed or runs past `cpu_seconds` of CPU
// goes to `failed(i, why)` instead, and a new worker takes the units left: one bad unit costs its
// own findings, never the run's. The caller must have no other threads (a worker starts as a copy
// of this process).
void run_isolated(size_t count, unsigned jobs, unsigned cpu_seconds, const std::function<std::string(size_t)>& work,
                  const std::function<void(size_t, std::string&&)>& done, const std::function<void(size_t, const std::string&)>& failed);

}  // namespace lwc::host
