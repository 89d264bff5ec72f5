#include "gl/context.h"

#include <cstdio>
#include <cstring>
#include <vector>

#include <epoxy/egl.h>
#include <epoxy/gl.h>

#include "core/error.h"

namespace rl {
namespace {

void GLAPIENTRY debug_callback(GLenum, GLenum type, GLuint, GLenum severity, GLsizei,
                               const GLchar* message, const void*) {
  if (severity == GL_DEBUG_SEVERITY_NOTIFICATION) return;
  if (type == GL_DEBUG_TYPE_ERROR || severity == GL_DEBUG_SEVERITY_HIGH) {
    std::fprintf(stderr, "GL error: %s\n", message);
  } else if (severity == GL_DEBUG_SEVERITY_MEDIUM) {
    std::fprintf(stderr, "GL warning: %s\n", message);
  }
}

EGLContext create_core_context(EGLDisplay display) {
  if (!eglBindAPI(EGL_OPENGL_API)) return EGL_NO_CONTEXT;
  const EGLint attribs[] = {EGL_CONTEXT_MAJOR_VERSION,
                            4,
                            EGL_CONTEXT_MINOR_VERSION,
                            5,
                            EGL_CONTEXT_OPENGL_PROFILE_MASK,
                            EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                            EGL_CONTEXT_OPENGL_DEBUG,
                            EGL_TRUE,
                            EGL_NONE};
  // Configless contexts need no surface type: we only ever render to FBOs.
  return eglCreateContext(display, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attribs);
}

bool try_display(EGLDisplay display, std::string& why) {
  if (display == EGL_NO_DISPLAY) {
    why = "no display";
    return false;
  }
  EGLint major = 0, minor = 0;
  if (!eglInitialize(display, &major, &minor)) {
    why = "eglInitialize failed";
    return false;
  }
  EGLContext ctx = create_core_context(display);
  if (ctx == EGL_NO_CONTEXT) {
    why = "no OpenGL 4.5 core context";
    eglTerminate(display);
    return false;
  }
  if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, ctx)) {
    why = "eglMakeCurrent without a surface failed";
    eglDestroyContext(display, ctx);
    eglTerminate(display);
    return false;
  }
  return true;
}

}  // namespace

GlContext& GlContext::shared() {
  static GlContext context;
  return context;
}

GlContext::GlContext() {
  std::string tried;
  bool ok = false;
  // 1. Hardware EGL devices (NVIDIA's driver exposes its GPUs here). Mesa's software device
  //    is skipped: the surfaceless platform below gives the same llvmpipe.
  if (epoxy_has_egl_extension(EGL_NO_DISPLAY, "EGL_EXT_device_enumeration") &&
      epoxy_has_egl_extension(EGL_NO_DISPLAY, "EGL_EXT_platform_device")) {
    EGLDeviceEXT devices[16];
    EGLint count = 0;
    if (eglQueryDevicesEXT(16, devices, &count)) {
      for (EGLint i = 0; i < count && !ok; ++i) {
        const char* ext = eglQueryDeviceStringEXT(devices[i], EGL_EXTENSIONS);
        if (ext && std::strstr(ext, "EGL_MESA_device_software")) continue;
        EGLDisplay d = eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr);
        std::string why;
        if (try_display(d, why)) {
          ok = true;
          platform_ = "device";
        } else {
          tried += " device " + std::to_string(i) + ": " + why + ";";
        }
      }
    }
  }
  // 2. Mesa's surfaceless platform.
  if (!ok && epoxy_has_egl_extension(EGL_NO_DISPLAY, "EGL_MESA_platform_surfaceless")) {
    EGLDisplay d =
        eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    std::string why;
    if (try_display(d, why)) {
      ok = true;
      platform_ = "surfaceless";
    } else {
      tried += " surfaceless: " + why + ";";
    }
  }
  if (!ok)
    throw GlError("cannot create a headless OpenGL 4.5 core context through EGL (" + tried +
                  " ) — install libegl-mesa0 and libgl1-mesa-dri, or a GPU driver with EGL");
  renderer_ = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  version_ = reinterpret_cast<const char*>(glGetString(GL_VERSION));
  software_ = renderer_.find("llvmpipe") != std::string::npos ||
              renderer_.find("softpipe") != std::string::npos ||
              renderer_.find("SwiftShader") != std::string::npos;
  glEnable(GL_DEBUG_OUTPUT);
  glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
  glDebugMessageCallback(debug_callback, nullptr);
}

}  // namespace rl
