#include "optimizer/farm/build_fingerprint.h"

#include <mujoco/mujoco.h>

#include "common/version.h"

namespace mrsim {
namespace {

std::string Compiler() {
#if defined(__clang__)
  return "clang " __clang_version__;
#elif defined(__GNUC__)
  return "gcc " __VERSION__;
#else
  return "unknown compiler";
#endif
}

// Compiled-in and run-time features; either changes results.
std::string CpuFeatures() {
  std::string out;
#if defined(__x86_64__)
  out = "x86_64";
#if defined(__FMA__)
  out += " fma-code";
#endif
#if defined(__AVX2__)
  out += " avx2-code";
#endif
  __builtin_cpu_init();
  if (__builtin_cpu_supports("fma")) out += " fma";
  if (__builtin_cpu_supports("avx2")) out += " avx2";
  if (__builtin_cpu_supports("avx512f")) out += " avx512f";
#elif defined(__aarch64__)
  out = "aarch64";  // FMA always there
#else
  out = "other-cpu";
#endif
  return out;
}

}  // namespace

std::string BuildFingerprint() {
  return std::string("mrsim ") + kVersion + "; " + Compiler() + "; MuJoCo " +
         mj_versionString() + "; " + CpuFeatures();
}

}  // namespace mrsim
