// light_map.cpp — one light's shadow map, whatever its lookup (light_map.hpp): Williams 1978,
// "Casting curved shadows on curved surfaces".
//
// Per light, the scene's depth is rendered from the light into a texture; each camera fragment is
// then mapped through B · P_light · V_light (mathlib's shadow_bias_matrix, projections, look_at)
// and read by the lookup (lookup.hpp).
// Bias: the depth pass culls front faces of closed casters (the map then holds back faces, so a
// lit surface is never compared against itself; RenderOptions::depth_faces may draw the front faces
// or both instead, as engines do, and a lookup that searches for blockers draws both) and uses
// glPolygonOffset with the lookup's factor and units; open meshes (a ground quad, a leaf) are drawn
// two-sided, since culling would drop whichever side faces the light. A packed depth applies the
// same offset in its shader.
// The light's views come from the prepared scene (mathlib's light_fit.hpp: one orthographic view
// for a directional light, one perspective view or a cube of six for the others, with the map size),
// one map layer each; a cube's six faces are layers of a 2D array texture, the face picked per
// fragment by the largest component of (p − light), like a cube-map lookup. Empty faces are cleared,
// not drawn, and each face draws only the objects that may reach it.
// Distance cubes (RenderOptions::cube_depth): a cube's layers may hold the distance from the light
// over a range instead (kDistanceFragment writes it as the fragment's depth, with the offset's model
// by hand), compared with the looked-up point's own distance, in every convention alike.
// Conventions (mathlib's convention.hpp): the light's projection is in the run convention, like the
// camera's; the map is 24-bit (32-bit float under reversed-Z), cleared to the far depth, drawn with
// the "nearer" depth test and polygon offset of the convention's sign (a float map's offset written
// by hand with the 24-bit step, offset_by_hand: GL's unit there is relative to the depth), compared
// with the convention's "lit" compare (GL_LEQUAL; GL_GEQUAL under reversed-Z) through its bias matrix; its
// border holds the far depth, so that nothing occludes outside it.
// Cascaded fits (csm, csm-pcf): a directional light's map is the prepared scene's cascades
// (mathlib/cascades.hpp: practical splits, a stable sphere per slice snapped to whole texels, the
// whole scene's depth range), one layer each, the cascade picked per fragment by its camera depth
// (light_view_of).
// A fragment outside the single map, or behind its light, counts as lit: the map knows of no
// occluder there (directional maps hold the whole bounding sphere; a point light's single map
// holds the whole box, so only geometry-free directions fall outside).
// Fault switches (faults.hpp, ShadowMapFaults), each one `if` below where the bug would be: the
// compare reversed or not flipped for reversed-Z, the map cleared to 1, the offset's sign, no bias
// matrix or the −1..1 one, no offset (acne) or a large constant one (peter-panning), casters out of
// the camera's view culled, a light fit that clips casters, cube faces swapped or upside down, a
// half-texel offset, the alpha test of masked casters ignored or misread (AlphaFault, a uniform of the
// depth programs' shared alpha_test) and open cards culled like closed casters; for the cascades (CascadeFaults) a gap between them, depth ranges clipped to
// the slices, no texel snapping, and a fit to the frustum behind the camera. There is no
// border-colour switch: every fit holds every vertex with a margin (light_fit.hpp; a cascade, its
// slice with kCascadeMarginTexels), so no catalogue fragment maps outside its map or within a PCF tap
// of its edge (conformance/README.md: a border at the near depth changes no pixel of the catalogue).
#include "light_map.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "shadowref/cascades.hpp"
#include "shadowref/lispsm.hpp"
#include "shadowref/projection.hpp"
#include "shadowref/scene/scene.hpp"
#include "shadowref/shadow_map.hpp"
#include "shadowref/view.hpp"

namespace shadowref::renderer {
namespace {

// The texture units of the surface programs' samplers (programs.cpp binds the names to them): a
// compared depth map on 0, a packed one on 1, a raw one on 2 and its moments on 3.
constexpr GLenum kComparedUnit = GL_TEXTURE0;
constexpr GLenum kPackedUnit = GL_TEXTURE1;
constexpr GLenum kRawDepthUnit = GL_TEXTURE2;
constexpr GLenum kMomentUnit = GL_TEXTURE3;

GLenum texture_unit(MapStorage storage) {
  switch (storage) {
    case MapStorage::ComparedDepth: return kComparedUnit;
    case MapStorage::PackedRgba8: return kPackedUnit;
    case MapStorage::RawDepth:
    case MapStorage::RawDepthAndMoments: return kRawDepthUnit;
  }
  return kComparedUnit;
}

// The compare that means "lit" in this render: the convention's (lit_when), unless a fault says otherwise.
DepthCompare lit_compare(const RunConvention& conv, CompareFault fault) {
  const DepthCompare right = lit_when(conv);
  switch (fault) {
    case CompareFault::None: return right;
    case CompareFault::Reversed:  // FAULT: lit and shadowed swap
      return right == DepthCompare::LessEqual ? DepthCompare::GreaterEqual : DepthCompare::LessEqual;
    case CompareFault::ConventionIgnored: return DepthCompare::LessEqual;  // FAULT: reversed-Z not flipped
  }
  return right;
}

// FitFault: the light's projection with its near (or far) plane moved to the middle of its depth
// range, measured in view space along the view axis. NDC depth is remapped affinely (clip
// z' = s z + t w), which keeps a perspective a perspective and an orthographic projection
// orthographic, in any convention: [middle, far] (or [near, middle]) is stretched onto [near, far]
// and the rest is clipped.
Mat4<double> fit_with_fault(const RunConvention& conv, const Mat4<double>& projection, FitFault fault) {
  const Mat4<double> inverse = projection.inverse();
  const auto view_point = [&](double ndc_z) {
    const Vec4<double> v = inverse * Vec4<double>(0, 0, ndc_z, 1);
    return Vec3<double>(v.head<3>() / v.w());
  };
  const double zn = near_ndc_z(conv), zf = far_ndc_z(conv);
  const Vec3<double> middle = 0.5 * (view_point(zn) + view_point(zf));
  const Vec4<double> c = projection * Vec4<double>(middle.x(), middle.y(), middle.z(), 1.0);
  const double zm = c.z() / c.w();
  const double lo = fault == FitFault::NearTooTight ? zm : zn, hi = fault == FitFault::NearTooTight ? zf : zm;
  const double scale = (zf - zn) / (hi - lo);
  Mat4<double> remap = Mat4<double>::Identity();
  remap(2, 2) = scale;
  remap(2, 3) = zn - scale * lo;
  return remap * projection;
}

// The bound 2D array texture read with nearest taps and `wrap` at its edges.
void read_nearest(const GlFunctions& gl, GLint wrap) {
  gl.TexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  gl.TexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  gl.TexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_S, wrap);
  gl.TexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_T, wrap);
}

// Cascaded fits: each cascade's range of camera depth (the shader picks among at most 4).
void select_cascades(const Frame& frame, const LightFit& lc, LightMap& map) {
  if (map.layout != MapLayout::Cascades) return;
  const std::vector<double>& s = lc.cascade_splits;
  const std::size_t n = s.size() - 1;
  if (n > 4) throw GlError("the shader picks among at most 4 cascades");
  map.cascade_depth = lc.cascade_depth_from_scene.cast<float>();
  for (std::size_t c = 0; c < n; ++c) {
    map.cascade_begin[c] = c == 0 ? -3e38f : static_cast<float>(s[c]);
    double end = c + 1 < n ? s[c + 1] : 3e38;  // the last one open-ended, as light_view_of
    // FAULT: the selection ends short of the split the next cascade begins at.
    if (frame.faults().cascade.gap && c + 1 < n) end = s[c] + kCascadeGapFraction * (s[c + 1] - s[c]);
    map.cascade_end[c] = static_cast<float>(end);
  }
}

// RenderOptions::view_turn_degrees and view_phase_texels, on clip coordinates: x and y turned and
// scaled (the turned square inside −1..1, with a texel to spare on each side for the move), then
// moved by the phase (NDC is 2 / size per texel; a move of x by t·w in clip space is a move by t in
// NDC under any w). The identity for the pack's views.
Mat4<double> own_view(const RenderOptions& o, int size) {
  Mat4<double> m = Mat4<double>::Identity();
  if (o.view_turn_degrees == 0 && o.view_phase_texels == 0) return m;
  const double a = o.view_turn_degrees * std::acos(-1.0) / 180.0, c = std::cos(a), s = std::sin(a);
  const double scale = 1.0 / (std::abs(c) + std::abs(s)) * size / (size + 2.0);
  m(0, 0) = scale * c, m(0, 1) = -scale * s;
  m(1, 0) = scale * s, m(1, 1) = scale * c;
  m(0, 3) = m(1, 3) = o.view_phase_texels * 2.0 / size;
  return m;
}

// The light's projections (FitFault: with a depth range that clips casters), and for each view the
// matrices between the world and its texels and the line of 1 / view depth in window depth.
std::vector<Mat4<double>> light_matrices(const Frame& frame, const LightFit& lc, LightMap& map) {
  const RunConvention& conv = frame.convention();
  const ShadowMapFaults& faults = frame.faults().shadow_map;
  Mat4<double> bias = shadow_bias<double>(conv);
  // FAULT: the −1..1 bias matrix whatever the clip depth range.
  if (faults.neg_one_to_one_bias) bias = shadow_bias_matrix<double>(DepthRange::NegOneToOne);
  if (faults.no_bias_matrix) bias = Mat4<double>::Identity();  // FAULT: clip coordinates read as texture coordinates
  if (faults.half_texel_offset) {  // FAULT: half a texel added to s and t
    Mat4<double> shift = Mat4<double>::Identity();
    shift(0, 3) = shift(1, 3) = 0.5 / map.size;
    bias = shift * bias;
  }
  if (faults.lookup_y_flipped) {  // FAULT: t read as 1 − t (in homogeneous form: w − t)
    Mat4<double> flip = Mat4<double>::Identity();
    flip(1, 1) = -1.0;
    flip(1, 3) = 1.0;
    bias = flip * bias;
  }
  std::vector<Mat4<double>> projections;
  for (const LightView& v : lc.views)
    projections.push_back(drawn_projection(frame.options,
                                           faults.fit == FitFault::None ? v.projection : fit_with_fault(conv, v.projection, faults.fit),
                                           lc.size, map.size));
  for (std::size_t k = 0; k < lc.views.size(); ++k) {
    const Mat4<double> m = bias * projections[k] * lc.views[k].view;
    map.face_from_world.push_back(to_float(m));
    map.world_from_face.push_back(to_float(Mat4<double>(m.inverse())));
    // Window depth is affine in 1 / (view depth) under a perspective projection: two points on the
    // view axis (−z when right-handed) fix the line.
    const Mat4<double> bp = bias * projections[k];
    const double axis = conv.clip.hand == Handedness::Right ? -1.0 : 1.0;
    const auto window = [&](double z) {
      const Vec4<double> c = bp * Vec4<double>(0, 0, axis * z, 1);
      return c.z() / c.w();
    };
    const double d1 = window(1.0), d2 = window(2.0);
    const double a = d1 != d2 ? (1.0 - 0.5) / (d1 - d2) : 0.0;
    map.inv_view_depth.push_back(static_cast<float>(a));
    map.inv_view_depth.push_back(static_cast<float>(1.0 - a * d1));
  }
  map.shadow_from_world = map.face_from_world[0];
  return projections;
}

// The map's textures (depth, or RGBA8 with a depth renderbuffer; VSM's moments beside) and the
// framebuffer the depth pass draws into, bound as `fbo`. Returns the depth renderbuffer (0: none).
GLuint allocate_targets(const Frame& frame, LightMap& map, GLsizei layers, const MapLookup& lookup, GLuint& fbo) {
  const GlFunctions& gl = frame.gl;
  const RunConvention& conv = frame.convention();
  const int size = map.size;
  map.pool = &frame.maps;
  if (lookup.storage == MapStorage::PackedRgba8)
    map.texture = frame.maps.texture(GL_RGBA8, GL_RGBA, GL_UNSIGNED_BYTE, size, layers);
  else if (conv.float_depth)
    map.texture = frame.maps.texture(GL_DEPTH_COMPONENT32F, GL_DEPTH_COMPONENT, GL_FLOAT, size, layers);
  else
    map.texture = frame.maps.texture(GL_DEPTH_COMPONENT24, GL_DEPTH_COMPONENT, GL_UNSIGNED_INT, size, layers);
  read_nearest(gl, GL_CLAMP_TO_BORDER);
  // The far depth (1, or 0 under reversed-Z) / its packed form: nothing occludes outside the map. A
  // distance cube's far is 1 in every convention.
  const auto far = map.distance_range > 0 ? 1.0f : static_cast<float>(far_depth(conv));
  const float far_border[4] = {far, far, far, 1.0f};
  gl.TexParameterfv(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_BORDER_COLOR, far_border);

  GLuint depth_rb = 0;
  gl.GenFramebuffers(1, &fbo);
  gl.BindFramebuffer(GL_FRAMEBUFFER, fbo);
  if (lookup.storage == MapStorage::PackedRgba8) {
    // A plain depth buffer still picks the nearest surface; only the colour target is sampled.
    depth_rb = frame.maps.renderbuffer(GL_DEPTH_COMPONENT24, size);
    gl.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth_rb);
    gl.DrawBuffer(GL_COLOR_ATTACHMENT0);
  } else {
    // A raw depth map is read as it is (PCSS's blocker search averages the stored depths).
    gl.TexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_COMPARE_MODE,
                     lookup.storage == MapStorage::ComparedDepth ? GL_COMPARE_REF_TO_TEXTURE : GL_NONE);
    const DepthCompare lit = map.distance_range > 0 ? DepthCompare::LessEqual : lit_compare(conv, frame.faults().shadow_map.compare);
    gl.TexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_COMPARE_FUNC, static_cast<GLint>(gl_compare(lit)));
    gl.DrawBuffer(GL_NONE);
  }
  if (lookup.storage == MapStorage::RawDepthAndMoments) {
    // Read at texel centres like every other map (the filter is the shader's taps); (0, 0) where
    // nothing is drawn, which no surface writes (its view depth is beyond the near plane).
    map.moments = frame.maps.texture(GL_RG32F, GL_RG, GL_FLOAT, size, layers);
    read_nearest(gl, GL_CLAMP_TO_EDGE);
    gl.DrawBuffer(GL_COLOR_ATTACHMENT0);
  }
  gl.ReadBuffer(GL_NONE);

  return depth_rb;
}

// Whether the depth pass writes this map's depth with the offset by hand: a window-depth map in a
// float depth buffer, where GL's polygon offset unit is relative to the depth (kOffsetDepthFragment)
// and would not be the 24-bit step the lookup declares. A packed depth and a distance do it anyway.
bool offset_by_hand(const RunConvention& conv, const LightMap& map, const MapLookup& lookup) {
  return conv.float_depth && map.distance_range <= 0 && lookup.storage != MapStorage::PackedRgba8;
}

// The depth pass's fragment shader for this map: a distance cube's, the packed depth's, the moments',
// or the plain one whose depth is the map; under a float depth buffer, the moments' and the plain one
// with the offset by hand.
DepthProgram depth_program(const RunConvention& conv, const LightMap& map, const MapLookup& lookup) {
  if (map.distance_range > 0) return DepthProgram::Distance;
  const bool by_hand = offset_by_hand(conv, map, lookup);
  return lookup.storage == MapStorage::PackedRgba8          ? DepthProgram::PackedDepth
         : lookup.storage == MapStorage::RawDepthAndMoments ? (by_hand ? DepthProgram::MomentsOffsetDepth : DepthProgram::Moments)
         : by_hand                                          ? DepthProgram::OffsetDepth
                                                            : DepthProgram::Flat;
}

// The depth pass's state: viewport, clear values, depth test, and the programs' polygon offset (the
// convention's sign, the lookup's factor; the teeth's offset faults).
void set_depth_pass_state(const Frame& frame, const LightFit& lc, const LightMap& map, const MapLookup& lookup,
                          const PassPrograms& programs) {
  const GlFunctions& gl = frame.gl;
  const RunConvention& conv = frame.convention();
  const ShadowMapFaults& faults = frame.faults().shadow_map;
  const auto far = static_cast<float>(far_depth(conv));
  gl.Viewport(0, 0, map.size, map.size);
  if (map.distance_range > 0) {
    // A distance cube: the nearest distance kept, 1 where nothing is, in every convention; the
    // offset's model in the shader (a written depth takes no polygon offset). The fault switches
    // model window-depth maps' bugs and are not applied here: the teeth draw window depth.
    gl.DepthMask(GL_TRUE);
    gl.ClearDepth(1.0);
    gl.Enable(GL_DEPTH_TEST);
    gl.DepthFunc(GL_LESS);
    gl.Disable(GL_STENCIL_TEST);
    gl.Disable(GL_BLEND);
    gl.Disable(GL_POLYGON_OFFSET_FILL);
    gl.ColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    programs.set([&](const Program& p) {
      gl.Uniform3f(p.at(gl, "u_light_position"), map.light_position.x(), map.light_position.y(), map.light_position.z());
      gl.Uniform1f(p.at(gl, "u_distance_range"), map.distance_range);
      gl.Uniform1f(p.at(gl, "u_offset_factor"), lookup.offset_factor);
      gl.Uniform1f(p.at(gl, "u_offset_units"), lookup.offset_units);
    });
    return;
  }
  gl.DepthMask(GL_TRUE);
  const float clear = faults.clear_to_one ? 1.0f : far;  // FAULT: 1 whatever the convention
  gl.ClearDepth(clear);
  gl.ClearColor(clear, clear, clear, 1.0f);  // = pack_depth_rgba8(clear): 0xFFFFFF or 0
  gl.Enable(GL_DEPTH_TEST);
  gl.DepthFunc(frame.depth_nearer());
  gl.Disable(GL_STENCIL_TEST);
  gl.Disable(GL_BLEND);
  float sign = polygon_offset_sign(conv), factor = lookup.offset_factor, units = lookup.offset_units;
  if (faults.offset_sign_ignored) sign = 1.0f;  // FAULT: + whatever the convention
  if (faults.no_polygon_offset) factor = units = 0.0f;  // FAULT: acne
  if (faults.large_constant_offset) units = kPeterPanUnits;  // FAULT: peter-panning
  if (faults.constant_offset_world > 0) {  // FAULT: peter-panning of a given world size
    // Window depth changes by |P(2,2)| / 2 (−1..1) or |P(2,2)| (0..1) per world unit along an
    // orthographic view's axis; one unit of offset is one step of the 24-bit depth.
    const Mat4<double>& projection = lc.views.front().projection;
    if (lc.cube || projection(3, 3) != 1.0 || conv.float_depth)
      throw GlError("shadow_map.constant_offset_world needs a directional light and a fixed-point depth convention");
    const double per_world = std::abs(projection(2, 2)) * (conv.clip.depth == DepthRange::NegOneToOne ? 0.5 : 1.0);
    units = static_cast<float>(faults.constant_offset_world * per_world / kWindowDepthPerUnit);
  }
  // The offset in the shader: a packed depth's whole offset; the moments' only its constant part,
  // the bias VSM needs against the float tie of a receiver with its own moments (without it the
  // Cornell box's tall block, edge-on to the light, reads its own face as an occluder); the slope
  // term would push a steep face behind the ground it stands on, and the filter would read that
  // contact as lit (kMomentsFragment reads the factor only for the depth it writes by hand).
  // Under a float depth buffer the map's depth takes the whole offset by hand too (offset_by_hand).
  const bool by_hand = offset_by_hand(conv, map, lookup);
  programs.set([&](const Program& p) {
    if (lookup.shader_offset != ShaderOffset::None || by_hand) {
      gl.Uniform1f(p.at(gl, "u_offset_factor"), sign * factor);
      gl.Uniform1f(p.at(gl, "u_offset_units"), sign * units);
    }
    if (lookup.shader_offset != ShaderOffset::Whole) gl.Uniform4f(p.colour, 0, 0, 0, 0);
  });
  if (lookup.shader_offset == ShaderOffset::Whole) {
    gl.ColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  } else {
    const GLboolean colour = lookup.storage == MapStorage::RawDepthAndMoments ? GL_TRUE : GL_FALSE;
    gl.ColorMask(colour, colour, colour, colour);
  }
  if (by_hand) {
    gl.Disable(GL_POLYGON_OFFSET_FILL);
  } else if (lookup.shader_offset != ShaderOffset::Whole) {
    gl.Enable(GL_POLYGON_OFFSET_FILL);
    gl.PolygonOffset(sign * factor, sign * units);
  }
}

// What the depth pass draws with at this moment, as GL holds it: the offset (GL's, or the depth
// shader's own where GL's is off: a packed depth, a distance, a float map) and its unit, and the
// faces a closed caster keeps.
void record_drawn_state(const GlFunctions& gl, const Program& p, DrawnMap& drawn) {
  if (gl.IsEnabled(GL_POLYGON_OFFSET_FILL)) {
    gl.GetFloatv(GL_POLYGON_OFFSET_FACTOR, &drawn.slope_factor);
    gl.GetFloatv(GL_POLYGON_OFFSET_UNITS, &drawn.offset_units);
    // GL's unit: one step of a fixed-point depth attachment, or relative to the depth on a float one.
    GLint type = 0;
    gl.GetFramebufferAttachmentParameteriv(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_FRAMEBUFFER_ATTACHMENT_COMPONENT_TYPE, &type);
    drawn.unit_depth = type == GL_FLOAT ? 0.0 : kWindowDepthPerUnit;
  } else if (const GLint f = p.at(gl, "u_offset_factor"); f >= 0) {
    gl.GetUniformfv(p.id, f, &drawn.slope_factor);
    gl.GetUniformfv(p.id, p.at(gl, "u_offset_units"), &drawn.offset_units);
    drawn.unit_depth = drawn.distance ? 1.0 / 16777215.0 : kWindowDepthPerUnit;  // the shaders' own steps
  }
  drawn.slope_factor = std::abs(drawn.slope_factor);
  drawn.offset_units = std::abs(drawn.offset_units);
  GLint mode = 0;
  gl.GetIntegerv(GL_CULL_FACE_MODE, &mode);
  drawn.closed_faces = !gl.IsEnabled(GL_CULL_FACE) ? outputs::DepthFaces::Both
                       : mode == GL_FRONT          ? outputs::DepthFaces::Back
                                                   : outputs::DepthFaces::Front;
}

// The depth pass: every view into its layer, casters culled as the fit says, closed casters drawn
// with the faces RenderOptions::depth_faces asks (both for a lookup that draws the first surfaces).
// Records what it drew with in `drawn`, read back from GL at a closed caster's draw call.
void draw_depth_pass(const Frame& frame, const LightFit& lc, const std::vector<Mat4<double>>& projections,
                     const LightMap& map, const MapLookup& lookup, const PassPrograms& programs, DrawnMap& drawn) {
  const GlFunctions& gl = frame.gl;
  const ShadowMapFaults& faults = frame.faults().shadow_map;
  const auto layers = static_cast<GLsizei>(lc.views.size());
  const outputs::DepthFaces faces = lookup.draws_first_surfaces ? outputs::DepthFaces::Both : frame.options.depth_faces;
  gl.CullFace(faces == outputs::DepthFaces::Front ? GL_BACK : GL_FRONT);
  const bool cull = faces != outputs::DepthFaces::Both;
  const bool colour = lookup.storage == MapStorage::PackedRgba8 || lookup.storage == MapStorage::RawDepthAndMoments;
  for (GLsizei face = 0; face < layers; ++face) {
    if (face > 0) frame.finish_then_check_interrupted();  // a cube's faces, the cascades: one by one
    const auto k = static_cast<std::size_t>(face);
    const LightView& view = lc.views[k];
    GLint layer = face;
    // FAULT: the +z and −z views rendered into each other's layers (a left-handed cube's order).
    if (lc.cube && faults.cube == CubeFault::ZFacesSwapped && face >= 4) layer = 9 - face;
    gl.FramebufferTextureLayer(GL_FRAMEBUFFER,
                               lookup.storage == MapStorage::PackedRgba8 ? GL_COLOR_ATTACHMENT0 : GL_DEPTH_ATTACHMENT,
                               map.texture, 0, layer);
    if (lookup.storage == MapStorage::RawDepthAndMoments) {
      gl.FramebufferTextureLayer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, map.moments, 0, layer);
      gl.ClearColor(0.0f, 0.0f, 0.0f, 0.0f);
    }
    if (gl.CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
      throw GlError("the shadow-map framebuffer is incomplete");
    gl.Clear(colour ? GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT : GL_DEPTH_BUFFER_BIT);
    if (view.empty) continue;
    Mat4<double> clip = projections[k] * view.view;
    // FAULT: the ±y faces rendered with their up vector negated (the picture turned by 180 degrees:
    // NDC x and y negated), while they are sampled as the face table says.
    if (lc.cube && faults.cube == CubeFault::YFacesUpsideDown && (face == 2 || face == 3))
      clip = Vec4<double>(-1, -1, 1, 1).asDiagonal() * clip;
    programs.set([&](const Program& p) {
      if (lookup.storage == MapStorage::RawDepthAndMoments)
        gl.Uniform2f(p.at(gl, "u_layer_inv_view_depth"), map.inv_view_depth[2 * k], map.inv_view_depth[2 * k + 1]);
      set_matrix(gl, p.clip_from_world, to_float(clip));
    });
    for (std::size_t i = 0; i < frame.objects.size(); ++i) {
      if (!view.draw.empty() && !view.draw[i]) continue;
      // FAULT: an object out of the camera's view culled from the light's pass too.
      if (faults.cull_casters_outside_view && frame.outside_camera_view(i)) continue;
      if (cull && frame.closed(i)) gl.Enable(GL_CULL_FACE);
      else gl.Disable(GL_CULL_FACE);
      if (!frame.closed(i) && faults.cull_open_front_faces) {  // FAULT: an open card culled as a closed caster
        gl.CullFace(GL_FRONT);
        gl.Enable(GL_CULL_FACE);
      }
      const Program& p = programs.use(i);
      if (frame.closed(i) && !drawn.closed_faces) record_drawn_state(gl, p, drawn);
      // FAULT: a skinned caster drawn in its bind pose into the map, while the camera's passes pose it.
      frame.objects[i].draw(faults.skin_bind_pose ? SkinDraw::BindPose : frame.skins);
      if (!frame.closed(i) && faults.cull_open_front_faces) gl.CullFace(faces == outputs::DepthFaces::Front ? GL_BACK : GL_FRONT);
    }
  }
}

}  // namespace

Mat4<double> drawn_projection(const RenderOptions& o, const Mat4<double>& projection, int fit_size, int map_size) {
  // RenderOptions::guard_band_texels: the view shrunk into the map's middle fit_size texels.
  const double guard_scale = static_cast<double>(fit_size) / static_cast<double>(map_size);
  return own_view(o, map_size) * Vec4<double>(guard_scale, guard_scale, 1, 1).asDiagonal() * projection;
}

LightMap::LightMap(LightMap&& o) noexcept
    : pool(o.pool), texture(o.texture), moments(o.moments), size(o.size), layout(o.layout),
      distance_range(o.distance_range), light_position(o.light_position), shadow_from_world(o.shadow_from_world),
      face_from_world(std::move(o.face_from_world)), cascade_depth(o.cascade_depth), cascade_begin(o.cascade_begin),
      cascade_end(o.cascade_end), world_from_face(std::move(o.world_from_face)),
      inv_view_depth(std::move(o.inv_view_depth)) {
  o.texture = 0;
  o.moments = 0;
}

LightMap::~LightMap() {
  if (texture) pool->give_back(texture, true);
  if (moments) pool->give_back(moments, true);
}

// The cascades of the directional light `i` for csm and csm-pcf: the prepared ones, or, when a
// CascadeFaults switch changes how they are fitted, a refit (into `refit`) with that one change.
const LightFit& cascade_fit(const Frame& frame, std::size_t i, LightFit& refit) {
  const LightFit& prepared = technique_fit(frame.prepared, frame.options, true, i, refit);
  const CascadeFaults& f = frame.faults().cascade;
  if (prepared.cascade_splits.empty() || (!f.slice_depth_range && !f.no_snapping && !f.frustum_behind_camera))
    return prepared;
  CascadeOptions o;
  o.count = static_cast<int>(prepared.views.size());
  o.map_size = prepared.size;
  o.snap = !f.no_snapping;                        // FAULT: the windows follow the camera continuously
  o.scene_depth_range = !f.slice_depth_range;     // FAULT: casters outside the slice's sphere clipped
  CascadeCamera camera = scene::cascade_camera(frame.scene);
  if (f.frustum_behind_camera) camera.forward = -camera.forward;  // FAULT: the other handedness's axis
  refit = fit_cascades(frame.convention(), frame.light(i).head<3>(), frame.prepared.bounds, camera, o).value();
  if (f.frustum_behind_camera) {  // the selection is the shader's own, from the true view depth
    refit.cascade_splits = prepared.cascade_splits;
    refit.cascade_depth_from_scene = prepared.cascade_depth_from_scene;
  }
  return refit;
}

bool lispsm_warps(const scene::PreparedScene& prepared, const RenderOptions& options, bool cascaded, std::size_t i) {
  return options.lispsm && !cascaded && prepared.lights[i].w() == 0;
}

const LightFit& technique_fit(const scene::PreparedScene& prepared, const RenderOptions& options, bool cascaded,
                              std::size_t i, LightFit& storage) {
  if (cascaded) return prepared.cascade_fits[i];
  if (!lispsm_warps(prepared, options, cascaded, i)) return prepared.light_fits[i];
  storage = fit_lispsm(*prepared.convention, prepared.lights[i].head<3>(), prepared.bounds,
                       scene::cascade_camera(*prepared.scene), prepared.light_fits[i].size)
                .value();
  return storage;
}

bool holds_distance(const RenderOptions& options, const MapLookup& lookup, bool cube) {
  return options.cube_depth == outputs::StoredDepth::Distance && cube && lookup.may_store_distance;
}

double cube_distance_range(const scene::PreparedScene& prepared, std::size_t light) {
  const Vec4<double>& l = prepared.lights[light];
  const Vec3<double> c = l.head<3>() / l.w();
  double range = 0;
  for (int k = 0; k < 8; ++k) {
    const Vec3<double> corner((k & 1 ? prepared.bounds[1] : prepared.bounds[0]).x(),
                              (k & 2 ? prepared.bounds[1] : prepared.bounds[0]).y(),
                              (k & 4 ? prepared.bounds[1] : prepared.bounds[0]).z());
    range = std::max(range, (corner - c).norm());
  }
  return 1.01 * range;
}

LightMap draw_light_map(Frame& frame, std::size_t light, const LightFit& lc, const MapLookup& lookup) {
  const GlFunctions& gl = frame.gl;
  LightMap map;
  map.size = lc.size + 2 * frame.options.guard_band_texels;
  if (holds_distance(frame.options, lookup, lc.cube)) {
    map.distance_range = static_cast<float>(cube_distance_range(frame.prepared, light));
    const Vec4<double> l = frame.light(light);
    map.light_position = (l.head<3>() / l.w()).cast<float>();
  }
  map.layout = lc.cube ? MapLayout::Cube : lc.cascade_splits.empty() ? MapLayout::Single : MapLayout::Cascades;
  select_cascades(frame, lc, map);
  const std::vector<Mat4<double>> projections = light_matrices(frame, lc, map);
  GLuint fbo = 0;
  const GLuint depth_rb = allocate_targets(frame, map, static_cast<GLsizei>(lc.views.size()), lookup, fbo);
  const DepthProgram program = depth_program(frame.convention(), map, lookup);
  const PassPrograms programs(frame, [&](bool tested) -> const Program& { return frame.programs.depth(program, tested); });
  set_depth_pass_state(frame, lc, map, lookup, programs);
  // FAULT (AlphaFault): how the depth pass treats masked casters; set back to none below, since the
  // program is shared with passes the fault is not about.
  const auto alpha_fault = [&](AlphaFault fault) {
    programs.set([&](const Program& p) { gl.Uniform1i(p.at(gl, "u_alpha_fault"), static_cast<int>(fault)); });
  };
  alpha_fault(frame.faults().shadow_map.alpha);
  DrawnMap drawn;
  drawn.lookup = std::string(lookup.name);
  drawn.distance = map.distance_range > 0;
  gl.GetTexLevelParameteriv(GL_TEXTURE_2D_ARRAY, 0, GL_TEXTURE_WIDTH, &drawn.texels);
  draw_depth_pass(frame, lc, projections, map, lookup, programs, drawn);
  alpha_fault(AlphaFault::None);
  frame.result.drawn_maps.push_back(std::move(drawn));
  gl.Disable(GL_CULL_FACE);
  gl.CullFace(GL_BACK);
  gl.Disable(GL_POLYGON_OFFSET_FILL);
  gl.ColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  gl.BindFramebuffer(GL_FRAMEBUFFER, 0);
  gl.DeleteFramebuffers(1, &fbo);
  if (depth_rb) frame.maps.give_back(depth_rb, false);
  return map;
}

void bind_light_map(const Frame& frame, std::size_t light, const LightMap& map, const MapLookup& lookup,
                    const Program& p) {
  const GlFunctions& gl = frame.gl;
  gl.ActiveTexture(texture_unit(lookup.storage));
  gl.BindTexture(GL_TEXTURE_2D_ARRAY, map.texture);
  if (lookup.storage == MapStorage::RawDepthAndMoments) {
    gl.ActiveTexture(kMomentUnit);
    gl.BindTexture(GL_TEXTURE_2D_ARRAY, map.moments);
  }
  gl.ActiveTexture(GL_TEXTURE0);
  gl.UseProgram(p.id);
  const float texel = 1.0f / static_cast<float>(map.size);
  gl.Uniform2f(p.at(gl, "u_texel"), texel, texel);
  gl.Uniform1i(p.at(gl, "u_layout"), static_cast<int>(map.layout));
  gl.Uniform1i(p.at(gl, "u_random_taps"), frame.options.random_taps);
  gl.Uniform1f(p.at(gl, "u_random_pcf_radius"), static_cast<float>(kRandomPcfRadiusTexels));
  gl.Uniform1i(p.at(gl, "u_reversed"), frame.convention().clip.order == DepthOrder::Reversed ? 1 : 0);
  const DepthCompare lit = lit_compare(frame.convention(), frame.faults().shadow_map.compare);
  gl.Uniform1i(p.at(gl, "u_lit_greater"), lit == DepthCompare::GreaterEqual ? 1 : 0);
  static_assert(!Mat4<float>::IsRowMajor);
  const auto matrices = [&](const char* name, const std::vector<Mat4<float>>& all) {
    std::vector<float> m;
    for (const Mat4<float>& f : all) m.insert(m.end(), f.data(), f.data() + 16);
    gl.UniformMatrix4fv(p.at(gl, name), static_cast<GLsizei>(all.size()), GL_FALSE, m.data());
  };
  gl.Uniform1f(p.at(gl, "u_normal_offset_texels"), static_cast<float>(frame.options.normal_offset_texels));
  gl.Uniform1f(p.at(gl, "u_distance_range"), map.distance_range);
  matrices("u_layer_from_world[0]", map.face_from_world);
  matrices("u_world_from_layer[0]", map.world_from_face);
  gl.Uniform2fv(p.at(gl, "u_inv_view_depth[0]"), static_cast<GLsizei>(map.inv_view_depth.size() / 2),
                map.inv_view_depth.data());
  if (map.layout == MapLayout::Cascades) {
    gl.Uniform4f(p.at(gl, "u_cascade_depth"), map.cascade_depth.x(), map.cascade_depth.y(), map.cascade_depth.z(), map.cascade_depth.w());
    gl.Uniform4f(p.at(gl, "u_cascade_begin"), map.cascade_begin.x(), map.cascade_begin.y(), map.cascade_begin.z(), map.cascade_begin.w());
    gl.Uniform4f(p.at(gl, "u_cascade_end"), map.cascade_end.x(), map.cascade_end.y(), map.cascade_end.z(), map.cascade_end.w());
  }
  if (lookup.set_light_uniforms) lookup.set_light_uniforms(frame, p, light);
}

void unbind_light_maps(const GlFunctions& gl) {
  for (const GLenum unit : {kMomentUnit, kRawDepthUnit, kPackedUnit, kComparedUnit}) {
    gl.ActiveTexture(unit);
    gl.BindTexture(GL_TEXTURE_2D_ARRAY, 0);
  }
}

MapStoragePool::~MapStoragePool() {
  for (const Entry& e : entries_) {
    if (e.is_texture) gl_.DeleteTextures(1, &e.id);
    else gl_.DeleteRenderbuffers(1, &e.id);
  }
}

MapStoragePool::Entry* MapStoragePool::reuse(bool is_texture, GLenum internal_format, int size, int layers) {
  for (Entry& e : entries_)
    if (!e.in_use && e.is_texture == is_texture && e.internal_format == internal_format && e.size == size &&
        e.layers == layers) {
      e.in_use = true;
      return &e;
    }
  return nullptr;
}

GLuint MapStoragePool::texture(GLenum internal_format, GLenum format, GLenum type, int size, int layers) {
  if (const Entry* e = reuse(true, internal_format, size, layers)) {
    gl_.BindTexture(GL_TEXTURE_2D_ARRAY, e->id);
    return e->id;
  }
  GLuint t = 0;
  gl_.GenTextures(1, &t);
  gl_.BindTexture(GL_TEXTURE_2D_ARRAY, t);
  gl_.TexImage3D(GL_TEXTURE_2D_ARRAY, 0, static_cast<GLint>(internal_format), size, size, layers, 0, format, type, nullptr);
  // A map the GL cannot hold is said here, with its size, rather than as an incomplete framebuffer
  // later: llvmpipe refuses any texture over 1 GiB (a point light's six 8192-texel layers of 32-bit
  // depth are 1.5 GiB) with GL_OUT_OF_MEMORY. An error flag left by an earlier call would be read
  // here too; the render is lost either way, and the line says which call it follows.
  if (const GLenum err = gl_.GetError(); err != GL_NO_ERROR) {
    gl_.DeleteTextures(1, &t);
    const double mib = static_cast<double>(size) * size * layers * (internal_format == GL_RG32F ? 8 : 4) / (1024.0 * 1024.0);
    char line[256];
    std::snprintf(line, sizeof line,
                  "OpenGL error 0x%04X allocating a shadow map of %d x %d texels x %d layer(s) (%.0f MiB)%s", err, size, size,
                  layers, mib, err == GL_OUT_OF_MEMORY ? ": more than the GL holds in one texture; a smaller --shadow-map-size fits" : "");
    throw GlError(line);
  }
  entries_.push_back({true, internal_format, size, layers, t, true});
  return t;
}

GLuint MapStoragePool::renderbuffer(GLenum internal_format, int size) {
  if (const Entry* e = reuse(false, internal_format, size, 1)) {
    gl_.BindRenderbuffer(GL_RENDERBUFFER, e->id);
    return e->id;
  }
  GLuint r = 0;
  gl_.GenRenderbuffers(1, &r);
  gl_.BindRenderbuffer(GL_RENDERBUFFER, r);
  gl_.RenderbufferStorage(GL_RENDERBUFFER, internal_format, size, size);
  entries_.push_back({false, internal_format, size, 1, r, true});
  return r;
}

void MapStoragePool::give_back(GLuint id, bool is_texture) {
  // At most kKept unused entries stay (the maps of one render of the largest scene, with room): the
  // oldest unused one goes first.
  constexpr std::size_t kKept = 8;
  for (Entry& e : entries_)
    if (e.id == id && e.is_texture == is_texture) e.in_use = false;
  std::size_t unused = 0;
  for (const Entry& e : entries_) unused += !e.in_use;
  for (auto it = entries_.begin(); unused > kKept && it != entries_.end();) {
    if (it->in_use) {
      ++it;
      continue;
    }
    if (it->is_texture) gl_.DeleteTextures(1, &it->id);
    else gl_.DeleteRenderbuffers(1, &it->id);
    it = entries_.erase(it);
    --unused;
  }
}

}  // namespace shadowref::renderer
