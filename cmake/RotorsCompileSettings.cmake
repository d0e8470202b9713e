# The compile settings every package of this repository shares (included by their CMakeLists):
# C++17, a Release build unless one is asked for, warnings on, and ROTORS_WERROR=ON (set by .ci/run)
# to make every warning an error, so that a new one fails CI.
# (-Wmaybe-uninitialized is off: GCC 12 reports it inside Eigen's products, a known false positive.)
add_compile_options(-Wall -Wextra -Wno-maybe-uninitialized)
# No fused multiply-add anywhere: GCC contracts a * b + c by default where the target has FMA
# (AArch64 always), which changes results in the last bit; without it arm64 computes what x86-64
# computes, and the batch's lanes equal its scalar step on every target.
add_compile_options(-ffp-contract=off)
if(ROTORS_WERROR)
  add_compile_options(-Werror)
endif()
set(CMAKE_CXX_STANDARD 17)
set(CMAKE_CXX_STANDARD_REQUIRED ON)
if(NOT CMAKE_BUILD_TYPE)
  set(CMAKE_BUILD_TYPE Release)
endif()
