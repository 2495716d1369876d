#include "render/headless_context.h"

#include <cstdio>
#include <cstring>
#include <vector>

#include <EGL/egl.h>
#include <EGL/eglext.h>

#include "core/error.h"
#include "render/gl.h"

namespace prt::render {

namespace {

bool has_extension(const char* list, const char* name) {
  if (list == nullptr) return false;
  const std::size_t length = std::strlen(name);
  for (const char* p = list; (p = std::strstr(p, name)) != nullptr; p += length) {
    const bool starts = p == list || p[-1] == ' ';
    const bool ends = p[length] == ' ' || p[length] == '\0';
    if (starts && ends) return true;
  }
  return false;
}

std::string egl_error_name(EGLint code) {
  switch (code) {
    case EGL_NOT_INITIALIZED: return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ACCESS: return "EGL_BAD_ACCESS";
    case EGL_BAD_ALLOC: return "EGL_BAD_ALLOC";
    case EGL_BAD_ATTRIBUTE: return "EGL_BAD_ATTRIBUTE";
    case EGL_BAD_CONFIG: return "EGL_BAD_CONFIG";
    case EGL_BAD_CONTEXT: return "EGL_BAD_CONTEXT";
    case EGL_BAD_DISPLAY: return "EGL_BAD_DISPLAY";
    case EGL_BAD_MATCH: return "EGL_BAD_MATCH";
    case EGL_BAD_PARAMETER: return "EGL_BAD_PARAMETER";
    default: {
      char buffer[32];
      std::snprintf(buffer, sizeof buffer, "EGL error 0x%04x", static_cast<unsigned>(code));
      return buffer;
    }
  }
}

// Initialises `display` and creates a current 4.5 core context on it; on failure returns false with
// the reason in `why` and leaves nothing initialised.
bool try_display(EGLDisplay display, EGLContext& context, std::string& why) {
  if (display == EGL_NO_DISPLAY) {
    why = "no display (" + egl_error_name(eglGetError()) + ")";
    return false;
  }
  EGLint major = 0, minor = 0;
  if (!eglInitialize(display, &major, &minor)) {
    why = "eglInitialize failed (" + egl_error_name(eglGetError()) + ")";
    return false;
  }
  const char* extensions = eglQueryString(display, EGL_EXTENSIONS);
  if (!has_extension(extensions, "EGL_KHR_surfaceless_context")) {
    why = "no EGL_KHR_surfaceless_context";
    eglTerminate(display);
    return false;
  }
  if (!eglBindAPI(EGL_OPENGL_API)) {
    why = "no desktop OpenGL API";
    eglTerminate(display);
    return false;
  }
  const EGLint config_attributes[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
  EGLConfig config = nullptr;
  EGLint config_count = 0;
  const bool no_config_context = has_extension(extensions, "EGL_KHR_no_config_context");
  if (!eglChooseConfig(display, config_attributes, &config, 1, &config_count) || config_count < 1) {
    if (!no_config_context) {
      why = "no OpenGL-capable EGL config";
      eglTerminate(display);
      return false;
    }
    config = nullptr;  // EGL_NO_CONFIG_KHR
  }
  const EGLint context_attributes[] = {EGL_CONTEXT_MAJOR_VERSION, kGlMajor, EGL_CONTEXT_MINOR_VERSION, kGlMinor,
                                       EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                       EGL_NONE};
  context = eglCreateContext(display, config, EGL_NO_CONTEXT, context_attributes);
  if (context == EGL_NO_CONTEXT) {
    why = "cannot create an OpenGL " + std::to_string(kGlMajor) + "." + std::to_string(kGlMinor) +
          " core context (" + egl_error_name(eglGetError()) + ")";
    eglTerminate(display);
    return false;
  }
  if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context)) {
    why = "eglMakeCurrent failed (" + egl_error_name(eglGetError()) + ")";
    eglDestroyContext(display, context);
    eglTerminate(display);
    return false;
  }
  return true;
}

}  // namespace

HeadlessContext::HeadlessContext() {
  const char* client_extensions = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  auto get_platform_display = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
      eglGetProcAddress("eglGetPlatformDisplayEXT"));
  std::string attempts;
  auto note = [&attempts](const std::string& name, const std::string& why) {
    attempts += (attempts.empty() ? "" : "; ") + name + ": " + why;
  };
  EGLContext context = EGL_NO_CONTEXT;
  std::string why;

  // 1. Mesa's surfaceless platform.
  if (get_platform_display != nullptr && has_extension(client_extensions, "EGL_MESA_platform_surfaceless")) {
    EGLDisplay display = get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    if (try_display(display, context, why)) {
      display_ = display;
      description_ = "EGL surfaceless";
    } else {
      note("surfaceless", why);
    }
  } else {
    note("surfaceless", "platform not available");
  }

  // 2. Enumerated devices.
  if (display_ == nullptr) {
    auto query_devices =
        reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
    if (get_platform_display != nullptr && query_devices != nullptr &&
        has_extension(client_extensions, "EGL_EXT_platform_device")) {
      EGLint device_count = 0;
      query_devices(0, nullptr, &device_count);
      std::vector<EGLDeviceEXT> devices(static_cast<std::size_t>(device_count > 0 ? device_count : 0));
      if (device_count > 0) query_devices(device_count, devices.data(), &device_count);
      if (device_count <= 0) note("device platform", "no devices");
      for (EGLint i = 0; i < device_count && display_ == nullptr; ++i) {
        EGLDisplay display = get_platform_display(EGL_PLATFORM_DEVICE_EXT, devices[static_cast<std::size_t>(i)], nullptr);
        if (try_display(display, context, why)) {
          display_ = display;
          description_ = "EGL device " + std::to_string(i);
        } else {
          note("device " + std::to_string(i), why);
        }
      }
    } else {
      note("device platform", "not available");
    }
  }

  // 3. The default display.
  if (display_ == nullptr) {
    EGLDisplay display = eglGetDisplay(EGL_DEFAULT_DISPLAY);
    if (try_display(display, context, why)) {
      display_ = display;
      description_ = "EGL default display";
    } else {
      note("default display", why);
    }
  }

  if (display_ == nullptr) fail("cannot create a headless OpenGL 4.5 context through EGL (" + attempts + ")");
  context_ = context;
  description_ += ", " + describe_current_context();
}

HeadlessContext::~HeadlessContext() {
  if (display_ == nullptr) return;
  eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  eglDestroyContext(display_, context_);
  eglTerminate(display_);
}

}  // namespace prt::render
