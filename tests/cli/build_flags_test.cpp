// The machine code of the `ringcrush` tool holds no fused multiply-add. The bitwise pins of the
// suite and the README (one against two threads, lanes against the scalar path, a build with
// link-time optimisation against one without, README "Build") rest on it: a fused a·b + c rounds
// once where the source rounds twice, so a contraction that inlining across files (RINGCRUSH_LTO)
// or a wider target (a kernel's [[gnu::target]]) made possible would move results in the last
// bits. The default ISA has no FMA; a build for the machine's CPU (RINGCRUSH_NATIVE, __FMA__)
// may fuse and is expected to differ, so it is not checked here.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <string>

namespace {

struct Disassembly {
  bool ran = false;
  long instructions = 0;  // lines of the form "  addr:\tmnemonic ..."
  long fused = 0;         // vfmadd…, vfmsub…, vfnmadd…, vfnmsub…
  std::string first_fused;
  bool avx2_kernel = false;  // a [[gnu::target("avx2")]] kernel is there, under its own name
};

Disassembly disassemble(const std::string& exe) {
  Disassembly d;
  const std::string cmd = "objdump -d --no-show-raw-insn '" + exe + "' 2>/dev/null";
  FILE* pipe = popen(cmd.c_str(), "r");
  if (!pipe) return d;
  std::array<char, 4096> buf{};
  while (std::fgets(buf.data(), static_cast<int>(buf.size()), pipe)) {
    const std::string line(buf.data());
    // A function's label: "0000000000278ef0 <…_avx2…>:" (the lane kernels, fe/element, hinge).
    if (line.find(">:") != std::string::npos && line.find("avx2") != std::string::npos) d.avx2_kernel = true;
    if (line.size() < 3 || line[0] != ' ' || line.find(":\t") == std::string::npos) continue;
    ++d.instructions;
    if (line.find("\tvfmadd") != std::string::npos || line.find("\tvfmsub") != std::string::npos ||
        line.find("\tvfnmadd") != std::string::npos || line.find("\tvfnmsub") != std::string::npos) {
      if (d.fused == 0) d.first_fused = line;
      ++d.fused;
    }
  }
  d.ran = pclose(pipe) == 0;
  return d;
}

}  // namespace

TEST(BuildFlags, ToolHasNoFusedMultiplyAdd) {
#ifdef __FMA__
  GTEST_SKIP() << "a build with FMA (RINGCRUSH_NATIVE): fused operations are expected there";
#else
  const Disassembly d = disassemble(RINGCRUSH_EXE);
  ASSERT_TRUE(d.ran) << "objdump (binutils, installed with g++) could not disassemble " << RINGCRUSH_EXE;
  // The tool is ≈ 0.7 M instructions: a short count means the disassembly was not read.
  ASSERT_GT(d.instructions, 100000);
  EXPECT_TRUE(d.avx2_kernel) << "no AVX2 kernel in the disassembly: the check below saw no AVX code";
  EXPECT_EQ(d.fused, 0) << "first: " << d.first_fused;
#endif
}
