// The kernel as four AVX2 lanes (compiled with -mavx2 -mfma -ffp-contract=off: no fused multiply-add,
// so that each lane equals the scalar step): four vehicles at once, or one vehicle's rotors four at
// a time. Called only where the CPU has AVX2 (FourLaneKernel, StepOneOfFour). Only templates of the
// AVX2 lane type are instantiated here, so no function compiled for AVX2 stands in for a baseline one.
#include "rotors_flight_batch/flight_kernel.h"

namespace rotors_flight_batch {

typedef double Avx2Lanes __attribute__((vector_size(32)));

unsigned StepFourAvx2(const KernelModel& m, const KernelArrays& a, size_t i0, const KernelWind& wind,
                      const KernelBefore& before) {
  return StepLanes<Avx2Lanes>(m, a, i0, wind, before);
}

void RotorLanesAvx2(const KernelModel& m, const KernelArrays& a, size_t i, const OneBody& b, RotorTerms& out) {
  RotorLanes<Avx2Lanes>(m, a, i, b, out);
}

}  // namespace rotors_flight_batch
