// write_images.cpp — the reference's images through the output contract's writers (write_images.hpp).
#include "shadowref/reference/write_images.hpp"

#include <algorithm>
#include <system_error>

#include "shadowref/outputs/errors.hpp"
#include "shadowref/outputs/file_names.hpp"
#include "shadowref/outputs/image_io.hpp"

namespace shadowref::reference {

std::vector<std::string> write_images(const Images& images, const std::filesystem::path& dir) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw outputs::FileError(dir.string() + ": cannot create the folder: " + ec.message());
  const int w = images.width, h = images.height;
  const std::size_t n = images.lights.size();
  std::vector<std::string> names;
  const auto grey = [&](const std::string& name, const std::vector<std::uint8_t>& px) {
    outputs::write_png(outputs::Image8{w, h, 1, px}, dir / name);
    names.push_back(name);
  };
  const auto exr = [&](const std::string& name, const std::vector<float>& px) {
    outputs::write_exr(w, h, px.data(), dir / name);
    names.push_back(name);
  };
  for (std::size_t i = 0; i < n; ++i) {
    grey(outputs::mask_name(i, n), images.lights[i].mask);
    if (n > 1) {
      grey(outputs::decided_name(i, n), images.lights[i].decided);
      exr(outputs::per_light_name("visibility", "exr", i, n), images.lights[i].visibility);
    }
  }
  // The aggregates (equal to the one light's images for one light).
  grey(outputs::decided_name(0, 1), images.decided);
  grey(outputs::kCoveredName, images.covered);
  exr(outputs::per_light_name("visibility", "exr", 0, 1), images.visibility);
  outputs::write_png(outputs::Image8{w, h, 3, images.shaded}, dir / "shaded.png");
  names.push_back("shaded.png");
  std::sort(names.begin(), names.end());
  return names;
}

}  // namespace shadowref::reference
