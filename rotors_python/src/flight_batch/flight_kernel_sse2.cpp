// The kernel as two pairs of SSE2 lanes (x86-64's baseline), and the choice of kernel for this CPU.
#include "flight_kernel.h"

namespace rotors_flight_batch {

typedef double Sse2Lanes __attribute__((vector_size(16)));

unsigned StepFourAvx2(const KernelModel& m, const KernelArrays& a, size_t i0, const KernelWind& wind,
                      const KernelBefore& before);

namespace {
unsigned StepFourSse2(const KernelModel& m, const KernelArrays& a, size_t i0, const KernelWind& wind,
                      const KernelBefore& before) {
  // lanes 2 and 3 read their wind and write their state-before at offset 2 of each [3][4] row
  const KernelWind w2{wind.force_W + 2, wind.moment_W + 2, wind.velocity_W + 2};
  const KernelBefore b2{before.v_W + 2, before.omega_W + 2, before.R_WB + 2};
  const unsigned low = StepLanesStrided<Sse2Lanes, 4>(m, a, i0, wind, before);
  const unsigned high = StepLanesStrided<Sse2Lanes, 4>(m, a, i0 + 2, w2, b2);
  return low | (high << 2);
}
}  // namespace

unsigned StepOneOfFour(const KernelModel& m, const KernelArrays& a, size_t i, size_t lane, const KernelWind& wind,
                       const KernelBefore& before) {
  const KernelWind w{wind.force_W + lane, wind.moment_W + lane, wind.velocity_W + lane};
  const KernelBefore b{before.v_W + lane, before.omega_W + lane, before.R_WB + lane};
  return StepLanesStrided<double, 4>(m, a, i, w, b) << lane;
}

StepFourLanes FourLaneKernel() {
  __builtin_cpu_init();
  return __builtin_cpu_supports("avx2") ? &StepFourAvx2 : &StepFourSse2;
}

}  // namespace rotors_flight_batch
