// gl_functions.hpp — the OpenGL 3.3 core entry points the renderer uses, as a table of function
// pointers resolved through GlContext::proc_address (OSMesaGetProcAddress or eglGetProcAddress).
//
// Why a table instead of linking libGL / libOpenGL: OSMesa carries its own GL dispatch, and
// mixing it with glvnd's libOpenGL in one process sends calls to whichever library the linker
// met first; resolving every function through the context that is current keeps both backends
// right, with no loader vendored (no GLEW, no glad). Private to the renderer library.
#pragma once

#include <GL/glcorearb.h>

#include "shadowref/renderer/gl_context.hpp"

namespace shadowref::renderer {

// X(type, name): the function glName of type `type`.
#define SHADOWREF_GL_FUNCTIONS(X)                                         \
  X(PFNGLGETSTRINGPROC, GetString)                                        \
  X(PFNGLGETERRORPROC, GetError)                                          \
  X(PFNGLGETINTEGERVPROC, GetIntegerv)                                    \
  X(PFNGLGETFLOATVPROC, GetFloatv)                                        \
  X(PFNGLISENABLEDPROC, IsEnabled)                                        \
  X(PFNGLGETUNIFORMFVPROC, GetUniformfv)                                  \
  X(PFNGLGETTEXLEVELPARAMETERIVPROC, GetTexLevelParameteriv)              \
  X(PFNGLGETFRAMEBUFFERATTACHMENTPARAMETERIVPROC, GetFramebufferAttachmentParameteriv) \
  X(PFNGLENABLEPROC, Enable)                                              \
  X(PFNGLDISABLEPROC, Disable)                                            \
  X(PFNGLVIEWPORTPROC, Viewport)                                          \
  X(PFNGLSCISSORPROC, Scissor)                                            \
  X(PFNGLCLEARPROC, Clear)                                                \
  X(PFNGLCLEARCOLORPROC, ClearColor)                                      \
  X(PFNGLCLEARDEPTHPROC, ClearDepth)                                      \
  X(PFNGLCLEARSTENCILPROC, ClearStencil)                                  \
  X(PFNGLFINISHPROC, Finish)                                              \
  X(PFNGLREADPIXELSPROC, ReadPixels)                                      \
  X(PFNGLPIXELSTOREIPROC, PixelStorei)                                    \
  X(PFNGLREADBUFFERPROC, ReadBuffer)                                      \
  X(PFNGLDRAWBUFFERPROC, DrawBuffer)                                      \
  X(PFNGLDRAWBUFFERSPROC, DrawBuffers)                                    \
  X(PFNGLCLEARBUFFERFVPROC, ClearBufferfv)                                \
  X(PFNGLDISABLEIPROC, Disablei)                                          \
  X(PFNGLDEPTHFUNCPROC, DepthFunc)                                        \
  X(PFNGLCLIPCONTROLPROC, ClipControl)                                    \
  X(PFNGLDEPTHMASKPROC, DepthMask)                                        \
  X(PFNGLCOLORMASKPROC, ColorMask)                                        \
  X(PFNGLSTENCILFUNCPROC, StencilFunc)                                    \
  X(PFNGLSTENCILOPPROC, StencilOp)                                        \
  X(PFNGLSTENCILOPSEPARATEPROC, StencilOpSeparate)                        \
  X(PFNGLSTENCILMASKPROC, StencilMask)                                    \
  X(PFNGLCULLFACEPROC, CullFace)                                          \
  X(PFNGLPOLYGONOFFSETPROC, PolygonOffset)                                \
  X(PFNGLBLENDFUNCPROC, BlendFunc)                                        \
  X(PFNGLDRAWELEMENTSPROC, DrawElements)                                  \
  X(PFNGLDRAWARRAYSPROC, DrawArrays)                                      \
  X(PFNGLGENBUFFERSPROC, GenBuffers)                                      \
  X(PFNGLDELETEBUFFERSPROC, DeleteBuffers)                                \
  X(PFNGLBINDBUFFERPROC, BindBuffer)                                      \
  X(PFNGLBUFFERDATAPROC, BufferData)                                      \
  X(PFNGLGENVERTEXARRAYSPROC, GenVertexArrays)                            \
  X(PFNGLDELETEVERTEXARRAYSPROC, DeleteVertexArrays)                      \
  X(PFNGLBINDVERTEXARRAYPROC, BindVertexArray)                            \
  X(PFNGLVERTEXATTRIBPOINTERPROC, VertexAttribPointer)                    \
  X(PFNGLENABLEVERTEXATTRIBARRAYPROC, EnableVertexAttribArray)            \
  X(PFNGLCREATESHADERPROC, CreateShader)                                  \
  X(PFNGLSHADERSOURCEPROC, ShaderSource)                                  \
  X(PFNGLCOMPILESHADERPROC, CompileShader)                                \
  X(PFNGLGETSHADERIVPROC, GetShaderiv)                                    \
  X(PFNGLGETSHADERINFOLOGPROC, GetShaderInfoLog)                          \
  X(PFNGLDELETESHADERPROC, DeleteShader)                                  \
  X(PFNGLCREATEPROGRAMPROC, CreateProgram)                                \
  X(PFNGLATTACHSHADERPROC, AttachShader)                                  \
  X(PFNGLLINKPROGRAMPROC, LinkProgram)                                    \
  X(PFNGLGETPROGRAMIVPROC, GetProgramiv)                                  \
  X(PFNGLGETPROGRAMINFOLOGPROC, GetProgramInfoLog)                        \
  X(PFNGLDELETEPROGRAMPROC, DeleteProgram)                                \
  X(PFNGLUSEPROGRAMPROC, UseProgram)                                      \
  X(PFNGLGETUNIFORMLOCATIONPROC, GetUniformLocation)                      \
  X(PFNGLUNIFORM1IPROC, Uniform1i)                                        \
  X(PFNGLUNIFORM1FPROC, Uniform1f)                                        \
  X(PFNGLUNIFORM2FPROC, Uniform2f)                                        \
  X(PFNGLUNIFORM2FVPROC, Uniform2fv)                                      \
  X(PFNGLUNIFORM3FPROC, Uniform3f)                                        \
  X(PFNGLUNIFORM4FPROC, Uniform4f)                                        \
  X(PFNGLUNIFORMMATRIX4FVPROC, UniformMatrix4fv)                          \
  X(PFNGLGENTEXTURESPROC, GenTextures)                                    \
  X(PFNGLDELETETEXTURESPROC, DeleteTextures)                              \
  X(PFNGLBINDTEXTUREPROC, BindTexture)                                    \
  X(PFNGLACTIVETEXTUREPROC, ActiveTexture)                                \
  X(PFNGLTEXIMAGE2DPROC, TexImage2D)                                      \
  X(PFNGLTEXIMAGE3DPROC, TexImage3D)                                      \
  X(PFNGLTEXPARAMETERIPROC, TexParameteri)                                \
  X(PFNGLTEXPARAMETERFVPROC, TexParameterfv)                              \
  X(PFNGLGENFRAMEBUFFERSPROC, GenFramebuffers)                            \
  X(PFNGLDELETEFRAMEBUFFERSPROC, DeleteFramebuffers)                      \
  X(PFNGLBINDFRAMEBUFFERPROC, BindFramebuffer)                            \
  X(PFNGLFRAMEBUFFERTEXTURE2DPROC, FramebufferTexture2D)                  \
  X(PFNGLFRAMEBUFFERTEXTURELAYERPROC, FramebufferTextureLayer)            \
  X(PFNGLFRAMEBUFFERRENDERBUFFERPROC, FramebufferRenderbuffer)            \
  X(PFNGLCHECKFRAMEBUFFERSTATUSPROC, CheckFramebufferStatus)              \
  X(PFNGLGENRENDERBUFFERSPROC, GenRenderbuffers)                          \
  X(PFNGLDELETERENDERBUFFERSPROC, DeleteRenderbuffers)                    \
  X(PFNGLBINDRENDERBUFFERPROC, BindRenderbuffer)                          \
  X(PFNGLRENDERBUFFERSTORAGEPROC, RenderbufferStorage)                    \
  X(PFNGLBINDBUFFERBASEPROC, BindBufferBase)                              \
  X(PFNGLGETUNIFORMBLOCKINDEXPROC, GetUniformBlockIndex)                  \
  X(PFNGLUNIFORMBLOCKBINDINGPROC, UniformBlockBinding)

struct GlFunctions {
#define SHADOWREF_GL_MEMBER(type, name) type name = nullptr;
  SHADOWREF_GL_FUNCTIONS(SHADOWREF_GL_MEMBER)
#undef SHADOWREF_GL_MEMBER

  // Resolves every entry; throws GlError naming the first one the context does not provide.
  explicit GlFunctions(const GlContext& context);
};

}  // namespace shadowref::renderer
