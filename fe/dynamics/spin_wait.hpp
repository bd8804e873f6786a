// One turn of a spin-wait between the two threads of a ForkJoin (fork_join.hpp,
// work_dealer.hpp, ChainModel): a pause, and every 64th turn a yield of the core.
//
// Why the yield: on a machine whose other core is busy (other jobs, or more threads than
// cores) the thread we wait for may be queued behind us on the same core, and a pure spin
// then burns our whole time slice before it can run — measured (session 10, thesis scene,
// first 1 ms, load ≈ 1–4 on 2 cores): 17–27 s of CPU on two threads against 2.3–3.2 s on one.
// On an idle core the yield returns at once (a system call, well under a µs against 64
// pauses), so the idle spin costs the same. Only timing changes: what the threads compute,
// and the order of the sums, do not depend on it.
#pragma once

#include <thread>

namespace ringcrush::fe {

inline void spin_wait_turn(unsigned& turn) {
  if ((++turn & 63u) == 0) {
    std::this_thread::yield();
    return;
  }
#if defined(__x86_64__) || defined(__i386__)
  __builtin_ia32_pause();
#endif
}

}  // namespace ringcrush::fe
