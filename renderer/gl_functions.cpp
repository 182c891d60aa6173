// gl_functions.cpp — resolves the entry-point table of gl_functions.hpp through the context.
#include "gl_functions.hpp"

#include <string>

namespace shadowref::renderer {

GlFunctions::GlFunctions(const GlContext& context) {
#define SHADOWREF_GL_LOAD(type, name)                                              \
  name = reinterpret_cast<type>(context.proc_address("gl" #name));                 \
  if (!name) throw GlError(std::string("OpenGL function gl" #name " is not available"));
  SHADOWREF_GL_FUNCTIONS(SHADOWREF_GL_LOAD)
#undef SHADOWREF_GL_LOAD
}

}  // namespace shadowref::renderer
