// The kernel as two pairs of SSE2 lanes (x86-64's baseline) or without lanes, and the choice of
// kernels for this CPU.
#include "flight_kernel.h"

#include "rotors_core/error.h"

namespace rotors_flight_batch {

typedef double Sse2Lanes __attribute__((vector_size(16)));

unsigned StepFourAvx2(const KernelModel& m, const KernelArrays& a, size_t i0, const KernelWind& wind,
                      const KernelBefore& before);
void RotorLanesAvx2(const KernelModel& m, const KernelArrays& a, size_t i, const OneBody& b, RotorTerms& out);
void RotorLanesAvx512(const KernelModel& m, const KernelArrays& a, size_t i, const OneBody& b, RotorTerms& out);

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

unsigned StepFourScalar(const KernelModel& m, const KernelArrays& a, size_t i0, const KernelWind& wind,
                        const KernelBefore& before) {
  unsigned touching = 0;
  for (size_t l = 0; l < 4; ++l) {
    const KernelWind w{wind.force_W + l, wind.moment_W + l, wind.velocity_W + l};
    const KernelBefore b{before.v_W + l, before.omega_W + l, before.R_WB + l};
    touching |= StepLanesStrided<double, 4>(m, a, i0 + l, w, b) << l;
  }
  return touching;
}
}  // namespace

unsigned StepOneOfFour(const Kernels& kernels, const KernelModel& m, const KernelArrays& a, size_t i, size_t lane,
                       const KernelWind& wind, const KernelBefore& before) {
  const KernelWind w{wind.force_W + lane, wind.moment_W + lane, wind.velocity_W + lane};
  const KernelBefore b{before.v_W + lane, before.omega_W + lane, before.R_WB + lane};
  return StepLanesStrided<double, 4>(m, a, i, w, b, kernels.rotor_lanes) << lane;
}

Kernels ChooseKernels(const std::string& instruction_set) {
  __builtin_cpu_init();
  const bool avx2 = __builtin_cpu_supports("avx2");
  const bool avx512 = avx2 && __builtin_cpu_supports("avx512f");
  const std::string set = instruction_set.empty() ? (avx512 ? "avx512" : avx2 ? "avx2" : "sse2") : instruction_set;
  if (set == "avx512") {
    if (!avx512)
      throw rotors_sim::SimError(
          "FlightBatch: kernel 'avx512' asked for, but this CPU has no AVX-512F; use avx2 or sse2");
    return {"avx512", &StepFourAvx2, &RotorLanesAvx512};
  }
  if (set == "avx2") {
    if (!avx2) throw rotors_sim::SimError("FlightBatch: kernel 'avx2' asked for, but this CPU has no AVX2; use sse2");
    return {"avx2", &StepFourAvx2, &RotorLanesAvx2};
  }
  if (set == "sse2") return {"sse2", &StepFourSse2, &RotorLanes<Sse2Lanes>};
  if (set == "scalar") return {"scalar", &StepFourScalar, nullptr};
  throw rotors_sim::SimError("FlightBatch: unknown kernel '" + set + "'; use avx512, avx2, sse2 or scalar");
}

}  // namespace rotors_flight_batch
