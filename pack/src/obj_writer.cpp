// obj_writer.cpp — one object as OBJ (obj_writer.hpp).
#include "shadowref/pack/obj_writer.hpp"

#include <cstdio>

namespace shadowref::pack {

std::string obj_text(const scene::Object& o) {
  std::string t = "# shadowref export: " + o.name + " in world space, counter-clockwise = outside\no " + o.name + "\n";
  char buf[128];
  for (const auto& p : o.mesh.positions) {
    std::snprintf(buf, sizeof buf, "v %.9g %.9g %.9g\n", static_cast<double>(p.x()), static_cast<double>(p.y()),
                  static_cast<double>(p.z()));
    t += buf;
  }
  for (const auto& tri : o.mesh.triangles) {
    std::snprintf(buf, sizeof buf, "f %u %u %u\n", tri[0] + 1, tri[1] + 1, tri[2] + 1);
    t += buf;
  }
  return t;
}

}  // namespace shadowref::pack
