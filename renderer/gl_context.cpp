// gl_context.cpp — picks the Mesa driver (GALLIUM_DRIVER) and the context implementation, and
// checks that the driver that answered is the one asked for.
#include "shadowref/renderer/gl_context.hpp"

#include <cstdlib>
#include <optional>
#include <stdexcept>
#include <string>

#include "gl_functions.hpp"

namespace shadowref::renderer {

const char* to_string(GlApi api) { return api == GlApi::OSMesa ? "osmesa" : "egl"; }

const char* to_string(Driver driver) {
  switch (driver) {
    case Driver::Llvmpipe: return "llvmpipe";
    case Driver::Softpipe: return "softpipe";
    case Driver::Native: return "native";
  }
  return "?";
}

GlApi parse_gl_api(std::string_view name) {
  if (name == "osmesa") return GlApi::OSMesa;
  if (name == "egl") return GlApi::Egl;
  throw std::invalid_argument("unknown GL context '" + std::string(name) + "' (osmesa or egl)");
}

Driver parse_driver(std::string_view name) {
  if (name == "llvmpipe") return Driver::Llvmpipe;
  if (name == "softpipe") return Driver::Softpipe;
  if (name == "native") return Driver::Native;
  throw std::invalid_argument("unknown backend '" + std::string(name) + "' (llvmpipe, softpipe or native)");
}

std::unique_ptr<GlContext> create_gl_context(GlApi api, Driver driver) {
  // Mesa reads GALLIUM_DRIVER when it creates its screen (the first context of the process for
  // OSMesa); a later different request would silently keep the first driver, so refuse it.
  static std::optional<Driver> first_driver;
  if (first_driver && *first_driver != driver)
    throw GlError(std::string("this process already uses the ") + to_string(*first_driver) +
                  " driver; Mesa cannot switch to " + to_string(driver) + " (run another process)");
  if (driver != Driver::Native) setenv("GALLIUM_DRIVER", to_string(driver), 1);
  // llvmpipe rasterises in the calling thread (LP_NUM_THREADS=0, read when Mesa creates its screen),
  // whatever the environment asks for. Why: with rasteriser threads, Mesa 22.3's llvmpipe can free a
  // fence while the thread that signals it has yet to unlock the fence's mutex. lp_fence_signal
  // increments the count, broadcasts and only then unlocks, while llvmpipe_fence_finish reads the
  // count without the mutex (lp_fence_signalled): a waiter that sees the fence complete drops it, and
  // the rasteriser thread then unlocks freed memory. The process dies with SIGSEGV in malloc, SIGABRT
  // in pthread's priority check, or SIGILL on `xend` (glibc's elided unlock of a mutex that is not
  // locked), about once in 4 000 `shadowref conform` processes under load; a delay between the
  // broadcast and the unlock makes it one in three with one rasteriser thread, and never without
  // threads (docs/architecture.md, "The GL context"). The cost: one frame at 1024² takes 1.3 - 1.7
  // times as long on two cores, a run of many cases at 256² no longer (bench/README.md). The pixels
  // are the same.
  if (driver == Driver::Llvmpipe) setenv("LP_NUM_THREADS", "0", 1);
  first_driver = driver;

  std::unique_ptr<GlContext> context = api == GlApi::OSMesa ? create_osmesa_context() : create_egl_context();
  if (driver != Driver::Native) {
    const GlFunctions gl(*context);
    const auto* renderer = reinterpret_cast<const char*>(gl.GetString(GL_RENDERER));
    if (!renderer || std::string(renderer).find(to_string(driver)) == std::string::npos)
      throw GlError(std::string("asked for Mesa's ") + to_string(driver) + " but the context's renderer is '" +
                    (renderer ? renderer : "(none)") + "'");
  }
  return context;
}

}  // namespace shadowref::renderer
