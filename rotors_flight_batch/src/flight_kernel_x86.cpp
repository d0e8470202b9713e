// x86-64's kernels: AVX-512 (eight lanes), AVX2 (four lanes) and SSE2 (x86-64's baseline: pairs),
// each where this CPU has it.
#include "rotors_flight_batch/flight_kernel_target.h"

namespace rotors_flight_batch {

extern const Kernels kAvx512Kernels, kAvx2Kernels;  // flight_kernel_avx512.cpp, flight_kernel_avx2.cpp

const char* const kTargetName = "x86-64";

std::vector<TargetKernel> TargetKernels() {
  __builtin_cpu_init();
  const bool avx2 = __builtin_cpu_supports("avx2");
  const bool avx512 = avx2 && __builtin_cpu_supports("avx512f");
  return {
      {kAvx512Kernels, avx512, "AVX-512F"}, {kAvx2Kernels, avx2, "AVX2"}, {KernelsIn<PairLanes>("sse2"), true, "SSE2"}};
}

}  // namespace rotors_flight_batch
