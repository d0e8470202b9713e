// Lee's controllers of a group of vehicles at once: lee_law.h's laws (the ones LeeController runs
// for one vehicle) with T a lane type, a lane per vehicle. Each vehicle keeps its own LeeController
// (its reference, its parameters); the group reads their constants, packed once into lanes, and
// their inputs at each step. A lane equals that vehicle's LeeController bit for bit.
#pragma once

#include <cstddef>
#include <cstring>
#include <new>

#include "rotors_control/lee_law.h"
#include "rotors_flight_batch/group.h"

namespace rotors_flight_batch {

using rotors_control::kMaxMixerRotors;
using rotors_control::LeeConstantsT;
using rotors_control::LeeInputsT;

/// A group's controller constants, packed for the kernels' lane width (kGroupLanes / L structs
/// LeeConstantsT<V> in turn: the same bytes for any L).
struct alignas(64) LeeGroupConstants {
  unsigned char bytes[kGroupLanes * sizeof(LeeConstantsT<double>)];
};

/// Rotor speeds of a group [rad/s]: rotor r of lane l at [r][l].
using LeeGroupSpeeds = double[kMaxMixerRotors][kGroupLanes];

namespace lee_lanes_detail {
/// Lanes first .. first + L - 1 of `each` (structs whose members are all doubles) as one struct of
/// V (the same members, each a V): member k of lane l from member k of each[first + l].
template <class V, class OutStruct, class InStruct>
inline void Transpose(const InStruct* each, size_t first, OutStruct* out) {
  constexpr size_t kMembers = sizeof(InStruct) / sizeof(double), L = sizeof(V) / sizeof(double);
  static_assert(sizeof(OutStruct) == kMembers * sizeof(V), "every member a V, in the same order");
  unsigned char* bytes = reinterpret_cast<unsigned char*>(out);
  for (size_t l = 0; l < L; ++l) {
    const unsigned char* src = reinterpret_cast<const unsigned char*>(&each[first + l]);
    for (size_t k = 0; k < kMembers; ++k)
      std::memcpy(bytes + k * sizeof(V) + l * sizeof(double), src + k * sizeof(double), sizeof(double));
  }
}
}  // namespace lee_lanes_detail

/// Packs the constants of a group's kGroupLanes controllers for lanes of V.
template <class V>
inline void PackLeeGroupIn(const LeeConstantsT<double> each[kGroupLanes], LeeGroupConstants* group) {
  constexpr size_t L = sizeof(V) / sizeof(double);
  static_assert(sizeof(LeeConstantsT<V>) * (kGroupLanes / L) == sizeof(LeeGroupConstants), "packed in place");
  for (size_t sub = 0; sub < kGroupLanes / L; ++sub) {
    auto* c = new (group->bytes + sub * sizeof(LeeConstantsT<V>)) LeeConstantsT<V>;
    lee_lanes_detail::Transpose<V>(each, sub * L, c);
  }
}

/// The group's rotor speeds for its controllers' inputs at this step (law::LeeRotorSpeeds per lane).
template <class V>
inline void LeeGroupIn(int rotors, const LeeGroupConstants& group, const LeeInputsT<double> in[kGroupLanes],
                       LeeGroupSpeeds omega) {
  constexpr size_t L = sizeof(V) / sizeof(double);
  for (size_t sub = 0; sub < kGroupLanes / L; ++sub) {
    const auto& c =
        *std::launder(reinterpret_cast<const LeeConstantsT<V>*>(group.bytes + sub * sizeof(LeeConstantsT<V>)));
    LeeInputsT<V> x;
    lee_lanes_detail::Transpose<V>(in, sub * L, &x);
    V w[kMaxMixerRotors];
    rotors_control::law::LeeRotorSpeeds(rotors, c, x, w);
    for (int r = 0; r < rotors; ++r) std::memcpy(&omega[r][sub * L], &w[r], sizeof(V));
  }
}

using PackLeeGroupFn = void (*)(const LeeConstantsT<double> each[kGroupLanes], LeeGroupConstants* group);
using LeeGroupFn = void (*)(int rotors, const LeeGroupConstants& group, const LeeInputsT<double> in[kGroupLanes],
                            LeeGroupSpeeds omega);

}  // namespace rotors_flight_batch
