#pragma once
// An OpenGL 4.5 core context with no window and no display server, through EGL. The renderer draws
// into its own framebuffer objects, so the context needs no surface (EGL_KHR_surfaceless_context).
//
// Display selection, first that works:
//   1. the Mesa surfaceless platform (EGL_MESA_platform_surfaceless): software (llvmpipe) or the
//      render node of a GPU, no X server needed;
//   2. the device platform (EGL_EXT_platform_device with EGL_EXT_device_enumeration): each enumerated
//      device in order (how NVIDIA's driver exposes headless GPUs);
//   3. the default display (eglGetDisplay(EGL_DEFAULT_DISPLAY)), e.g. with EGL_PLATFORM set.
// A display is used only if it initialises, supports desktop OpenGL and creates a 4.5 core context.
#include <string>

namespace prt::render {

class HeadlessContext {
 public:
  /// Creates the context and makes it current on the calling thread. Throws prt::Error with one line
  /// saying what each attempt found if no EGL display gives an OpenGL 4.5 core context.
  /// One HeadlessContext per process at a time: EGL displays are process-wide and the destructor
  /// terminates its display.
  HeadlessContext();
  ~HeadlessContext();
  HeadlessContext(const HeadlessContext&) = delete;
  HeadlessContext& operator=(const HeadlessContext&) = delete;

  /// Which display was used ("surfaceless", "device 0", "default") and the GL renderer string.
  const std::string& description() const { return description_; }

 private:
  void* display_ = nullptr;  // EGLDisplay
  void* context_ = nullptr;  // EGLContext
  std::string description_;
};

}  // namespace prt::render
