// programs.cpp — the renderer's GLSL programs: compiled, linked, their samplers bound to the units
// the light maps use (shadow_maps/light_map.cpp), and each lookup's surface program on first use.
#include <string>
#include <vector>

#include "frame.hpp"
#include "shaders.hpp"
#include "shadow_maps/lookup.hpp"

namespace shadowref::renderer {
namespace {

GLuint compile(const GlFunctions& gl, GLenum type, const std::vector<std::string>& sources, const char* what) {
  std::vector<const char*> strings;
  for (const std::string& s : sources) strings.push_back(s.c_str());
  const GLuint s = gl.CreateShader(type);
  gl.ShaderSource(s, static_cast<GLsizei>(strings.size()), strings.data(), nullptr);
  gl.CompileShader(s);
  GLint ok = 0;
  gl.GetShaderiv(s, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[4096] = {};
    gl.GetShaderInfoLog(s, sizeof log, nullptr, log);
    gl.DeleteShader(s);
    throw GlError(std::string("shader ") + what + " does not compile: " + log);
  }
  return s;
}

Program link(const GlFunctions& gl, const std::vector<std::string>& fragment, bool alpha_tested, std::string what) {
  const GLuint vs = compile(gl, GL_VERTEX_SHADER, {shaders::kSceneVertex}, "scene vertex");
  if (alpha_tested) what += ", alpha-tested";
  const GLuint fs = compile(gl, GL_FRAGMENT_SHADER, shaders::with_alpha_test(fragment, alpha_tested), what.c_str());
  Program p;
  p.id = gl.CreateProgram();
  gl.AttachShader(p.id, vs);
  gl.AttachShader(p.id, fs);
  gl.LinkProgram(p.id);
  gl.DeleteShader(vs);
  gl.DeleteShader(fs);
  GLint ok = 0;
  gl.GetProgramiv(p.id, GL_LINK_STATUS, &ok);
  if (!ok) {
    char log[4096] = {};
    gl.GetProgramInfoLog(p.id, sizeof log, nullptr, log);
    throw GlError("program " + what + " does not link: " + log);
  }
  // The joints of a skinned draw (GpuMesh binds its block there, the rigid block otherwise).
  if (const GLuint block = gl.GetUniformBlockIndex(p.id, "Skin"); block != GL_INVALID_INDEX)
    gl.UniformBlockBinding(p.id, block, kSkinBlockBinding);
  const auto loc = [&](const char* name) { return gl.GetUniformLocation(p.id, name); };
  p.clip_from_world = loc("u_clip_from_world");
  p.shadow_from_world = loc("u_shadow_from_world");
  p.colour = loc("u_colour");
  p.mode = loc("u_mode");
  p.albedo = loc("u_albedo");
  p.ambient = loc("u_ambient");
  p.light = loc("u_light");
  p.light_intensity = loc("u_light_intensity");
  p.spot = loc("u_spot");
  // The samplers' texture units (light_map.cpp's texture_unit); a program has at most one of them
  // and its moments.
  gl.UseProgram(p.id);
  const std::pair<const char*, GLint> units[] = {{"u_shadow_map", 0}, {"u_packed_map", 1}, {"u_depth_map", 2}, {"u_moment_map", 3},
                                                 {"u_alpha_mask", static_cast<GLint>(kAlphaMaskUnit - GL_TEXTURE0)}};
  for (const auto& [name, unit] : units)
    if (const GLint l = loc(name); l >= 0) gl.Uniform1i(l, unit);
  gl.UseProgram(0);
  return p;
}

std::vector<std::string> depth_fragment(DepthProgram pass) {
  switch (pass) {
    case DepthProgram::Flat: return {shaders::kVersion, shaders::kFlatFragment};
    case DepthProgram::PackedDepth: return {shaders::kVersion, shaders::kDepthPacking, shaders::kPackedDepthFragmentBody};
    case DepthProgram::Moments: return {shaders::kVersion, shaders::kMomentsFragment};
    case DepthProgram::Distance: return {shaders::kVersion, shaders::kDistanceFragment};
    case DepthProgram::OffsetDepth: return {shaders::kVersion, shaders::kOffsetDepthFragment};
    case DepthProgram::MomentsOffsetDepth: return {shaders::kVersion, shaders::kDepthByHand, shaders::kMomentsFragment};
  }
  throw GlError("unknown depth program");
}

const char* depth_name(DepthProgram pass) {
  switch (pass) {
    case DepthProgram::Flat: return "flat";
    case DepthProgram::PackedDepth: return "packed depth";
    case DepthProgram::Moments: return "moments";
    case DepthProgram::Distance: return "distance";
    case DepthProgram::OffsetDepth: return "offset depth";
    case DepthProgram::MomentsOffsetDepth: return "moments and offset depth";
  }
  return "?";
}

}  // namespace

Programs::Programs(const GlFunctions& gl) : gl_(gl) {
  for (const DepthProgram pass : {DepthProgram::Flat, DepthProgram::PackedDepth, DepthProgram::Moments, DepthProgram::Distance,
                                 DepthProgram::OffsetDepth, DepthProgram::MomentsOffsetDepth})
    depth(pass);
  surface();
}

Programs::~Programs() {
  for (const auto& [key, p] : depth_) gl_.DeleteProgram(p.id);
  for (const auto& [key, p] : surface_) gl_.DeleteProgram(p.id);
}

const Program& Programs::depth(DepthProgram pass, bool alpha_tested) const {
  Program& p = depth_[{pass, alpha_tested}];
  if (!p.id) p = link(gl_, depth_fragment(pass), alpha_tested, depth_name(pass));
  return p;
}

const Program& Programs::surface(const MapLookup* lookup, bool alpha_tested) const {
  Program& p = surface_[{lookup, alpha_tested}];
  if (!p.id)
    p = link(gl_, shaders::surface_fragment(lookup), alpha_tested,
             "surface (" + std::string(lookup ? lookup->name : "no map") + ")");
  return p;
}

}  // namespace shadowref::renderer
