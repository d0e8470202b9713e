// The kernels of the instruction sets this build's target offers. One of flight_kernel_x86.cpp
// (x86-64: AVX-512, AVX2 and SSE2 lanes), flight_kernel_arm64.cpp (AArch64: NEON lanes) or
// flight_kernel_other.cpp (no lanes but the generic pairs) is compiled, chosen by CMake from the
// target processor; nothing else in the batch names an instruction set.
#pragma once

#include <vector>

#include "rotors_flight_batch/flight_kernel.h"

namespace rotors_flight_batch {

/// Two lanes of 16 bytes: x86-64's SSE2 and AArch64's NEON registers (GCC lowers them to scalar
/// code on a target with neither).
typedef double PairLanes __attribute__((vector_size(16)));

struct TargetKernel {
  Kernels kernels;
  bool cpu_has_it;    ///< this CPU runs it
  const char* needs;  ///< what the CPU must have, for the error when it has not
};

/// The target's name for errors ("x86-64", "arm64", ...).
extern const char* const kTargetName;

/// The target's kernels with lanes, fastest first (the scalar kernel is added by ChooseKernels).
std::vector<TargetKernel> TargetKernels();

}  // namespace rotors_flight_batch
