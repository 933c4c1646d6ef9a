// An off-screen OpenGL context with no display: EGL on Mesa's surfaceless
// platform (llvmpipe when there is no GPU). MuJoCo's built-in loader finds
// eglGetProcAddress in the process and renders into its own framebuffer.
#pragma once

#include <memory>
#include <string>

namespace mrsim {

class GlContext {
 public:
  // Creates the context and makes it current on the calling thread. Throws
  // std::runtime_error naming the EGL call that failed.
  GlContext();
  ~GlContext();
  GlContext(const GlContext&) = delete;
  GlContext& operator=(const GlContext&) = delete;

  // Makes the context current on the calling thread again.
  void MakeCurrent();
  // "EGL 1.5 (Mesa Project), platform surfaceless" or similar.
  const std::string& description() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace mrsim
