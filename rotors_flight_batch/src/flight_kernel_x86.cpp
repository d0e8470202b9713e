// x86-64's kernels: AVX-512 (eight lanes), AVX2 (four lanes) and SSE2 (x86-64's baseline: pairs),
// each where this CPU has it.
#include "rotors_flight_batch/flight_kernel_target.h"

namespace rotors_flight_batch {

unsigned StepGroupAvx512(const KernelModel& m, const KernelArrays& a, size_t i0, const KernelWind& wind,
                         const KernelBefore& before);
unsigned StepOneAvx512(const KernelModel& m, const KernelArrays& a, size_t i, const KernelWind& wind,
                       const KernelBefore& before);
unsigned StepGroupAvx2(const KernelModel& m, const KernelArrays& a, size_t i0, const KernelWind& wind,
                       const KernelBefore& before);
unsigned StepOneAvx2(const KernelModel& m, const KernelArrays& a, size_t i, const KernelWind& wind,
                     const KernelBefore& before);

void PackLeeAvx512(const LeeConstantsT<double> each[kGroupLanes], LeeGroupConstants* group);
void LeeGroupAvx512(int rotors, const LeeGroupConstants& group, const LeeInputsT<double> in[kGroupLanes],
                    LeeGroupSpeeds omega);
void PackLeeAvx2(const LeeConstantsT<double> each[kGroupLanes], LeeGroupConstants* group);
void LeeGroupAvx2(int rotors, const LeeGroupConstants& group, const LeeInputsT<double> in[kGroupLanes],
                  LeeGroupSpeeds omega);

const char* const kTargetName = "x86-64";

std::vector<TargetKernel> TargetKernels() {
  __builtin_cpu_init();
  const bool avx2 = __builtin_cpu_supports("avx2");
  const bool avx512 = avx2 && __builtin_cpu_supports("avx512f");
  return {{{"avx512", &StepGroupAvx512, &StepOneAvx512, &PackLeeAvx512, &LeeGroupAvx512}, avx512, "AVX-512F"},
          {{"avx2", &StepGroupAvx2, &StepOneAvx2, &PackLeeAvx2, &LeeGroupAvx2}, avx2, "AVX2"},
          {{"sse2", &StepGroupPairs, &StepOnePairs, &PackLeePairs, &LeeGroupPairs}, true, "SSE2"}};
}

}  // namespace rotors_flight_batch
