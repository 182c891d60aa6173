// wrong_variants.cpp — the table of deliberately wrong techniques (wrong_variants.hpp).
#include "wrong_variants.hpp"

#include "frame.hpp"

namespace shadowref::wrong {
namespace {

using renderer::Technique;

const WrongVariant kVariants[] = {
    {Technique{"wrong-zpass-eye-inside",
               "depth-pass volumes used where the eye is inside a shadow volume (the counts start wrong)",
               renderer::render_volume_zpass},
     "volume-zfail", "camera_in_shadow"},
    {Technique{"wrong-zfail-without-caps", "depth-fail volumes without their light and dark caps", render_zfail_without_caps},
     "volume-zfail", "any scene whose volumes are seen through a cap"},
    {Technique{"wrong-shadowmap-without-bias", "shadow map compared through P_light V_light without the bias matrix",
               render_shadowmap_without_bias},
     "shadowmap", "every scene with a shadow"},
    {Technique{"wrong-shadowmap-compare-reversed", "shadow map compare GL_GEQUAL instead of GL_LEQUAL",
               render_shadowmap_compare_reversed},
     "shadowmap", "every scene with a shadow"},
    {Technique{"wrong-half-pixel-offset", "the camera shifted by half a pixel (Direct3D 9's pixel centres)",
               render_zfail_half_pixel_offset},
     "volume-zfail", "scenes with long edges on decided pixels"},
    {Technique{"wrong-planar-transposed", "the planar shadow matrix transposed (D3DX layout in a column-vector pipeline)",
               render_planar_transposed},
     "planar", "ground_sphere"},
    // Our stencil is 8 bits and wraps: right for the catalogue's volume techniques, whose
    // expectations say so on nested_256_volumes. Judged as a technique claiming exact counts
    // (no catalogue expectation: expected to pass everywhere), the wrap must be caught there.
    {Technique{"wrong-stencil-8bit-wraps", "depth-fail volumes counted in an 8-bit wrapping stencil, claiming exact counts",
               renderer::render_volume_zfail},
     "volume-exact-count", "nested_256_volumes"},
};

}  // namespace

std::span<const WrongVariant> wrong_variants() { return kVariants; }

}  // namespace shadowref::wrong
