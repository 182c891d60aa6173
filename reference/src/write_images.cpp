// write_images.cpp — OpenImageIO output with write-then-rename (write_images.hpp).
#include "shadowref/reference/write_images.hpp"

#include <OpenImageIO/imageio.h>
#include <unistd.h>

#include <algorithm>
#include <functional>
#include <stdexcept>
#include <utility>

namespace shadowref::reference {
namespace {

namespace fs = std::filesystem;

// Writes one image to `tmp`, in the format of `final_name`'s extension.
void write_one(const fs::path& tmp, const fs::path& final_name, int width, int height, int channels,
               OIIO::TypeDesc type, const void* data) {
  auto out = OIIO::ImageOutput::create(final_name.string());
  if (!out) throw std::runtime_error(final_name.string() + ": no image writer: " + OIIO::geterror());
  OIIO::ImageSpec spec(width, height, channels, type);
  if (channels == 1) spec.channelnames = {"Y"};
  if (type == OIIO::TypeDesc::FLOAT) spec.attribute("compression", "zip");
  // OpenEXR output stamps the wall-clock time into the header unless DateTime is set; an empty
  // value suppresses it, so that two runs write byte-identical files (determinism is tested).
  spec.attribute("DateTime", "");
  if (!out->open(tmp.string(), spec) || !out->write_image(type, data) || !out->close()) {
    throw std::runtime_error(final_name.string() + ": cannot write: " + out->geterror());
  }
}

}  // namespace

std::vector<std::string> write_images(const Images& images, const fs::path& dir) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw std::runtime_error(dir.string() + ": cannot create the folder: " + ec.message());
  const int w = images.width, h = images.height;
  // (final name, writer) pairs, written to temporaries first.
  std::vector<std::pair<std::string, std::function<void(const fs::path&, const fs::path&)>>> files;
  auto grey = [&](const std::string& name, const std::vector<std::uint8_t>& px) {
    files.emplace_back(name, [&, w, h](const fs::path& t, const fs::path& f) { write_one(t, f, w, h, 1, OIIO::TypeDesc::UINT8, px.data()); });
  };
  auto fl = [&](const std::string& name, const std::vector<float>& px) {
    files.emplace_back(name, [&, w, h](const fs::path& t, const fs::path& f) { write_one(t, f, w, h, 1, OIIO::TypeDesc::FLOAT, px.data()); });
  };
  if (images.lights.size() == 1) {
    grey("mask.png", images.lights[0].mask);
  } else {
    for (std::size_t i = 0; i < images.lights.size(); ++i) {
      const std::string s = std::to_string(i);
      grey("mask_" + s + ".png", images.lights[i].mask);
      grey("decided_" + s + ".png", images.lights[i].decided);
      fl("visibility_" + s + ".exr", images.lights[i].visibility);
    }
  }
  grey("decided.png", images.decided);
  fl("visibility.exr", images.visibility);
  files.emplace_back("shaded.png", [&](const fs::path& t, const fs::path& f) { write_one(t, f, w, h, 3, OIIO::TypeDesc::UINT8, images.shaded.data()); });

  const std::string tag = ".tmp" + std::to_string(::getpid());
  std::vector<std::pair<fs::path, fs::path>> written;
  try {
    for (const auto& [name, writer] : files) {
      const fs::path final_path = dir / name;
      const fs::path stem = fs::path(name).stem(), ext = fs::path(name).extension();
      const fs::path tmp = dir / ("." + stem.string() + tag + ext.string());
      written.emplace_back(tmp, final_path);
      writer(tmp, final_path);
    }
    for (const auto& [tmp, final_path] : written) {
      fs::rename(tmp, final_path, ec);
      if (ec) throw std::runtime_error(final_path.string() + ": cannot rename: " + ec.message());
    }
  } catch (...) {
    for (const auto& [tmp, final_path] : written) fs::remove(tmp, ec);
    throw;
  }
  std::vector<std::string> names;
  for (const auto& f : files) names.push_back(f.first);
  std::sort(names.begin(), names.end());
  return names;
}

}  // namespace shadowref::reference
