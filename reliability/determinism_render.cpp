// determinism_render.cpp — a small driver for determinism_test.cpp: renders one scene with every
// technique on llvmpipe at a reduced resolution, writes the outputs as `shadowref render` does
// (renderer::write_outputs), and prints one line per image file: "<technique>/<file> <FNV-1a 64>",
// then the number of llvmpipe rasteriser threads the process has ("llvmpipe threads: N"; the
// renderer asks for none, whatever LP_NUM_THREADS says: renderer/gl_context.cpp). llvmpipe reads its
// environment once, at context creation, so the test runs this driver as a child with the
// environment it wants.
//
// Usage: determinism_render SCENE.json MAX_SIDE OUT_DIR
#include <cstdint>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <string>

#include "reduced_resolution.hpp"
#include "shadowref/renderer/renderer.hpp"
#include "shadowref/scene/load_scene.hpp"

namespace {

std::uint64_t fnv1a(const std::string& bytes) {
  std::uint64_t h = 1469598103934665603ull;
  for (unsigned char c : bytes) h = (h ^ c) * 1099511628211ull;
  return h;
}

std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace

int main(int argc, char** argv) {
  using namespace shadowref;
  if (argc != 4) {
    std::fprintf(stderr, "usage: determinism_render SCENE.json MAX_SIDE OUT_DIR\n");
    return 4;
  }
  try {
    scene::Scene s = scene::load_scene(argv[1]);
    reliability::reduce_resolution(s, std::stoi(argv[2]));
    renderer::Renderer r(renderer::GlApi::OSMesa, renderer::Driver::Llvmpipe);
    for (const renderer::Technique& t : renderer::techniques()) {
      const std::filesystem::path dir = std::filesystem::path(argv[3]) / std::string(t.name);
      renderer::write_outputs(r.render(s, t.name), r.info(), s, dir);
      std::set<std::string> files;  // sorted: the output is comparable line by line
      for (const auto& e : std::filesystem::directory_iterator(dir))
        if (e.path().extension() == ".png") files.insert(e.path().filename().string());
      for (const std::string& f : files)
        std::printf("%s/%s %016llx\n", std::string(t.name).c_str(), f.c_str(),
                    static_cast<unsigned long long>(fnv1a(slurp(dir / f))));
    }
    // llvmpipe names its rasteriser threads "llvmpipe-<i>" (each task's comm in /proc).
    int llvmpipe_threads = 0;
    for (const auto& task : std::filesystem::directory_iterator("/proc/self/task"))
      llvmpipe_threads += slurp(task.path() / "comm").rfind("llvmpipe", 0) == 0;
    std::printf("llvmpipe threads: %d\n", llvmpipe_threads);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "determinism_render: %s\n", e.what());
    return 4;
  }
  return 0;
}
