// compile_shader_isolated forks a child per compile. glslang guards its process-wide tables with a
// mutex: a fork while another thread held it left the child waiting for it until the 120 s limit
// (verify -j 8 on 2 cores lost two minutes; the default -j on 16 cores ten times its time).
#include <gtest/gtest.h>

#include <atomic>
#include <thread>
#include <vector>

#include "core/fork_gate.h"
#include "verify/compile.h"

namespace lwc {
namespace {

CompileInput small_shader(int i) {
  CompileInput in;
  in.lang = Lang::glsl;
  in.stage = Stage::compute;
  in.name = "t" + std::to_string(i) + ".comp";
  in.text = "#version 450\nlayout(local_size_x = 1) in;\nlayout(std430, binding = 0) buffer B { float v[]; };\n"
            "void main() { v[0] = v[1] * " + std::to_string(i) + ".0 + 1.0; }\n";
  in.spirv = true;
  return in;
}

TEST(CompileIsolation, ForksBesideThreadsInsideGlslangNeverHang) {
  std::atomic<bool> stop{false};
  std::atomic<int> in_process{0};
  std::vector<std::thread> compilers;
  for (int t = 0; t < 3; ++t)
    compilers.emplace_back([&, t] {
      for (int i = 0; !stop; ++i)
        if (compile_shader(small_shader(t * 1000 + i)).ok) ++in_process;
    });
  std::vector<std::thread> forkers;
  std::atomic<int> isolated_ok{0}, isolated_failed{0};
  for (int t = 0; t < 3; ++t)
    forkers.emplace_back([&, t] {
      for (int i = 0; i < 40; ++i) {
        CompileResult r = compile_shader_isolated(small_shader(t * 100 + i));
        (r.ok ? isolated_ok : isolated_failed)++;
        if (!r.ok) ADD_FAILURE() << r.crashed << format_messages(r);
      }
    });
  for (std::thread& f : forkers) f.join();
  stop = true;
  for (std::thread& c : compilers) c.join();
  EXPECT_EQ(isolated_ok, 120);
  EXPECT_EQ(isolated_failed, 0);
  EXPECT_GT(in_process, 0);  // the in-process compiles did run beside the forks
}

// The include resolver runs in the child too: a cache lock other threads take (the project's include
// summaries) is taken with ForkSafeLock, so no fork happens while one of them holds it.
TEST(CompileIsolation, IncludeResolverLocksTakenUnderTheGateNeverHangAChild) {
  std::mutex cache;
  int lookups = 0;
  std::atomic<bool> stop{false};
  std::vector<std::thread> users;
  for (int t = 0; t < 3; ++t)
    users.emplace_back([&] {
      while (!stop) {
        ForkSafeLock lock(cache);
        ++lookups;
      }
    });
  CompileInput in = small_shader(7);
  in.text = "#version 450\n#extension GL_GOOGLE_include_directive : require\n#include \"scale.glsl\"\n"
            "layout(local_size_x = 1) in;\nlayout(std430, binding = 0) buffer B { float v[]; };\nvoid main() { v[0] = kScale; }\n";
  in.include = [&](const std::string& name, const std::string&) -> std::optional<IncludedFile> {
    ForkSafeLock lock(cache);
    return IncludedFile{name, "const float kScale = 2.0;\n"};
  };
  for (int i = 0; i < 60; ++i) {
    CompileResult r = compile_shader_isolated(in);
    EXPECT_TRUE(r.ok) << r.crashed << format_messages(r);
    if (!r.ok) break;
  }
  stop = true;
  for (std::thread& u : users) u.join();
  EXPECT_GT(lookups, 0);
}

}  // namespace
}  // namespace lwc
