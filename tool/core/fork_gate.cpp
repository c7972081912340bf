#include "core/fork_gate.h"

#include <pthread.h>
#include <unistd.h>

#include <cerrno>

namespace lwc {
namespace {

pthread_rwlock_t* gate() {
  static pthread_rwlock_t* lock = [] {
    static pthread_rwlock_t l;
    pthread_rwlockattr_t attr;
    pthread_rwlockattr_init(&attr);
    // A waiting fork goes before new holders, or a steady stream of compiles would starve it.
    pthread_rwlockattr_setkind_np(&attr, PTHREAD_RWLOCK_PREFER_WRITER_NONRECURSIVE_NP);
    pthread_rwlock_init(&l, &attr);
    pthread_rwlockattr_destroy(&attr);
    return &l;
  }();
  return lock;
}

thread_local int held = 0;  // this thread's nested holds (a writer-preferring lock is not re-entrant)

}  // namespace

ForkGateHold::ForkGateHold() {
  if (held++ == 0) pthread_rwlock_rdlock(gate());
}

ForkGateHold::~ForkGateHold() {
  if (--held == 0) pthread_rwlock_unlock(gate());
}

pid_t fork_alone() {
  if (held > 0) {
    errno = EDEADLK;
    return -1;
  }
  pthread_rwlock_wrlock(gate());
  pid_t pid = ::fork();
  if (pid == 0) {
    held = 1;  // the child's copy stays locked by its one thread: every hold there is nested
    return 0;
  }
  pthread_rwlock_unlock(gate());
  return pid;
}

}  // namespace lwc
