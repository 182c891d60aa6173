// math_properties_test.cpp — every math property, in float and in double, on the adapter that
// shadowref_add_math_properties() linked in (math_adapter_under_test()).
#include "math_properties.hpp"

namespace shadowref::prop {
namespace {

template <class T>
class MathProperties : public ::testing::Test {
 protected:
  const MathFunctions<T>& f() const { return math_adapter_under_test().get<T>(); }
};
using Scalars = ::testing::Types<float, double>;
TYPED_TEST_SUITE(MathProperties, Scalars);

#define SHADOWREF_MATH_PROPERTY(name) \
  TYPED_TEST(MathProperties, name) { check_property([&] { name<TypeParam>(this->f()); }); }

// A property of an optional projection: skipped, saying so, when the adapter does not have it.
#define SHADOWREF_MATH_PROPERTY_OF(name, conventions)                                                \
  TYPED_TEST(MathProperties, name) {                                                                 \
    if (this->f().conventions.empty()) GTEST_SKIP() << "the adapter lists no " #conventions;        \
    check_property([&] { name<TypeParam>(this->f()); });                                            \
  }

SHADOWREF_MATH_PROPERTY(projected_point_lies_on_plane)
SHADOWREF_MATH_PROPERTY(points_on_plane_stay)
SHADOWREF_MATH_PROPERTY(point_light_and_projection_are_collinear)
SHADOWREF_MATH_PROPERTY(directional_light_projects_along_its_direction)
SHADOWREF_MATH_PROPERTY(light_is_in_the_kernel)
SHADOWREF_MATH_PROPERTY(projecting_twice_is_projecting_once)
SHADOWREF_MATH_PROPERTY(scaling_the_plane_changes_nothing)
SHADOWREF_MATH_PROPERTY(d3dx_layout_is_the_transpose)
SHADOWREF_MATH_PROPERTY(finite_projection_tends_to_infinite)
SHADOWREF_MATH_PROPERTY(directions_survive_the_infinite_far_plane)
SHADOWREF_MATH_PROPERTY(depth_is_monotonic_along_a_view_ray)
SHADOWREF_MATH_PROPERTY(near_maps_to_the_conventions_depth)
SHADOWREF_MATH_PROPERTY(perspective_maps_the_field_of_view_onto_the_ndc_square)
SHADOWREF_MATH_PROPERTY_OF(frustum_maps_its_near_rectangle_onto_the_ndc_square, frustum_conventions)
SHADOWREF_MATH_PROPERTY_OF(ortho_maps_its_box_onto_the_ndc_square, ortho_conventions)
SHADOWREF_MATH_PROPERTY(points_in_front_of_the_eye_are_in_front)
SHADOWREF_MATH_PROPERTY(ndc_xy_do_not_depend_on_the_depth_parameters)

}  // namespace
}  // namespace shadowref::prop
