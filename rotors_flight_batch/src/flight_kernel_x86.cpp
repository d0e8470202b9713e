// x86-64's kernels: AVX-512 (a lone vehicle's rotors in eight lanes, groups of four vehicles as
// AVX2), AVX2 (four lanes) and SSE2 (x86-64's baseline: two pairs), each where this CPU has it.
#include "rotors_flight_batch/flight_kernel_target.h"

namespace rotors_flight_batch {

unsigned StepFourAvx2(const KernelModel& m, const KernelArrays& a, size_t i0, const KernelWind& wind,
                      const KernelBefore& before);
void RotorLanesAvx2(const KernelModel& m, const KernelArrays& a, size_t i, const OneBody& b, RotorTerms& out);
void RotorLanesAvx512(const KernelModel& m, const KernelArrays& a, size_t i, const OneBody& b, RotorTerms& out);

const char* const kTargetName = "x86-64";

std::vector<TargetKernel> TargetKernels() {
  __builtin_cpu_init();
  const bool avx2 = __builtin_cpu_supports("avx2");
  const bool avx512 = avx2 && __builtin_cpu_supports("avx512f");
  return {{{"avx512", &StepFourAvx2, &RotorLanesAvx512}, avx512, "AVX-512F"},
          {{"avx2", &StepFourAvx2, &RotorLanesAvx2}, avx2, "AVX2"},
          {{"sse2", &StepFourPairs, &RotorLanesPairs}, true, "SSE2"}};
}

}  // namespace rotors_flight_batch
