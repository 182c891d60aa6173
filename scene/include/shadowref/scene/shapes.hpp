// shadowref/scene/shapes.hpp — the procedural shapes of the scene format that mathlib lacks.
//
// plane, box, sphere and torus come from mathlib's primitives.hpp (shared with the property
// tests and the benchmarks); only the staircase lives here. Like those, it is built in its local
// frame, in double, counter-clockwise seen from outside (mesh.hpp), welded and closed: every edge
// is shared by exactly two triangles, which the shadow-volume adjacency relies on.
#pragma once

#include "shadowref/conventions.hpp"
#include "shadowref/mesh.hpp"

namespace shadowref::scene {

// A solid staircase of `steps` equal steps (≥ 1) rising toward +z: x in [−W/2, W/2], y in [0, H],
// z in [−D/2, D/2] for size = (W, H, D). Step i (0-based) has its tread at height H (i+1)/steps
// over z in [−D/2 + D i/steps, −D/2 + D (i+1)/steps]. Closed and T-junction free (the side walls
// and the bottom are split at every riser). Precondition: every size component > 0.
TriangleMesh<double> make_stairs(int steps, const Vec3<double>& size);

}  // namespace shadowref::scene
