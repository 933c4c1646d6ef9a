// What makes two builds give different episode results from the same
// genome: the mrsim version, the compiler, the MuJoCo library and the CPU
// features that change floating point (FMA contracts a*b+c into one
// rounding; glibc's libm picks FMA/AVX2 variants of exp, sin, pow at run
// time). A farm master refuses workers whose fingerprint differs from its
// own unless told --allow-mixed-builds (docs/security.md).
#pragma once

#include <string>

namespace mrsim {

// e.g. "mrsim 0.9.0; gcc 12.2.0; MuJoCo 3.2.7; x86_64 fma avx2".
std::string BuildFingerprint();

}  // namespace mrsim
