#pragma once
// A child forked from a threaded process gets every lock as it stood: one that another thread held
// stays held in the child forever. Compile children (verify/compile.cpp) run glslang and the
// include resolver, so the locks those take are held under this gate, shared, and a fork takes the
// gate alone: it happens only while no thread holds them.
#include <mutex>

#include <sys/types.h>

namespace lwc {

// Holds the gate shared for the calling thread while it lives; nested holds are free.
class ForkGateHold {
 public:
  ForkGateHold();
  ~ForkGateHold();
  ForkGateHold(const ForkGateHold&) = delete;
  ForkGateHold& operator=(const ForkGateHold&) = delete;
};

// A mutex lock taken under the gate (the gate first, always, so the order is one).
class ForkSafeLock {
 public:
  explicit ForkSafeLock(std::mutex& m) : lock_(m) {}

 private:
  ForkGateHold hold_;
  std::lock_guard<std::mutex> lock_;
};

// fork() with the gate held alone (new holders wait while one is pending). In the child the gate
// counts as held by its one thread, so what it calls never waits on it. A thread that holds the
// gate itself cannot fork (it would wait for itself): -1 with errno EDEADLK.
pid_t fork_alone();

}  // namespace lwc
