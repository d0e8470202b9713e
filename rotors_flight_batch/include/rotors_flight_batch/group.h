// How many vehicles the batch steps together (a group): AVX-512's eight lanes of doubles, or as many
// narrower lanes in turn. The kernels (flight_kernel.h) and the controllers (lee_lanes.h) both work
// a group at a time.
#pragma once

#include <cstddef>

namespace rotors_flight_batch {

constexpr size_t kGroupLanes = 8;

}  // namespace rotors_flight_batch
