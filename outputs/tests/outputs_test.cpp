// outputs_test.cpp — the output contract's naming rule, image round trip, staged folder, atomic
// file write and interruption. (A full disk, kills and signals in a real run: reliability/faults/.)
#include <gtest/gtest.h>
#include <png.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <thread>
#include <vector>

#include "shadowref/outputs/atomic_file.hpp"
#include "shadowref/outputs/candidate.hpp"
#include "shadowref/outputs/cause.hpp"
#include "shadowref/outputs/file_names.hpp"
#include "shadowref/outputs/image.hpp"
#include "shadowref/outputs/image_io.hpp"
#include "shadowref/outputs/errors.hpp"
#include "shadowref/outputs/interruption.hpp"
#include "shadowref/outputs/spare_cores.hpp"
#include "shadowref/outputs/staged_folder.hpp"
#include "shadowref/outputs/techniques.hpp"

namespace shadowref::outputs {
namespace {

namespace fs = std::filesystem;

fs::path fresh_dir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("shadowref_outputs_test_" + std::to_string(::getpid())) / name;
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

// What read_declaration says of `json` as dir/candidate.json: its refusal, or "(accepted)".
std::string refusal_of(const fs::path& dir, const std::string& json) {
  std::ofstream(dir / kCandidateFile) << json;
  try {
    read_declaration(dir, "shadowmap");
  } catch (const InputError& e) {
    return e.what();
  }
  return "(accepted)";
}

// candidate.json's `lights`: each entry overrides the top-level keys for its light, the rest take
// the top level, and the writer gives back only what differs.
TEST(Declaration, PerLightEntriesOverrideTheTopLevel) {
  const fs::path dir = fs::temp_directory_path() / ("shadowref-declaration-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  std::ofstream(dir / kCandidateFile) << R"({"technique": "pcss", "shadow_map_size": 2048, "slope_bias_texels": 1.5,
    "lights": [{"shadow_map_size": 683, "sampling": "random", "light_taps": 4}, {"depth_bias": 0.001}]})";
  const CandidateDeclaration d = read_declaration(dir, "pcss");
  ASSERT_EQ(d.lights.size(), 2u);
  EXPECT_EQ(d.for_light(0).shadow_map_size, 683);
  EXPECT_EQ(d.for_light(0).sampling, Sampling::Random);
  EXPECT_EQ(d.for_light(0).light_taps, 4);
  EXPECT_EQ(d.for_light(0).slope_bias_texels, 1.5) << "not overridden: the top level's";
  EXPECT_EQ(d.for_light(1).shadow_map_size, 2048);
  EXPECT_EQ(d.for_light(1).depth_bias, 0.001);
  EXPECT_EQ(d.for_light(2).shadow_map_size, 2048) << "no entry: the top level";
  EXPECT_EQ(d.for_light(2).sampling, Sampling::Grid);
  // Written back: the entries hold only their overrides, and reading that gives the same lights.
  const std::string text = declaration_text(d);
  EXPECT_NE(text.find("\"lights\""), std::string::npos);
  std::ofstream(dir / kCandidateFile) << text;
  const CandidateDeclaration again = read_declaration(dir, "pcss");
  ASSERT_EQ(again.lights.size(), 2u);
  EXPECT_EQ(again.for_light(0).shadow_map_size, 683);
  EXPECT_EQ(again.for_light(1).depth_bias, 0.001);
  EXPECT_EQ(declaration_text(again), text);
  fs::remove_all(dir);
}

// "environment": where the render came from, read in kEnvironmentKeys' order and written back the
// same; another key, a non-string or an environment per light is refused with its JSON path.
TEST(Declaration, AnEnvironmentIsRecordedAndMalformedOnesAreRefused) {
  const fs::path dir = fresh_dir("environment");
  std::ofstream(dir / kCandidateFile) << R"({"environment": {"engine": "three.js r187", "api": "webgpu",
    "adapter": "google swiftshader"}})";
  const CandidateDeclaration d = read_declaration(dir, "shadowmap");
  const Environment want{{"api", "webgpu"}, {"adapter", "google swiftshader"}, {"engine", "three.js r187"}};
  EXPECT_EQ(d.environment, want);
  EXPECT_EQ(environment_text(d.environment), "api webgpu · adapter google swiftshader · engine three.js r187");
  const std::string text = declaration_text(d);
  std::ofstream(dir / kCandidateFile) << text;
  EXPECT_EQ(read_declaration(dir, "shadowmap").environment, want);
  EXPECT_TRUE(read_declaration(fresh_dir("no-environment"), "shadowmap").environment.empty());
  const auto refusal = [&](const std::string& json) { return refusal_of(dir, json); };
  EXPECT_NE(refusal(R"({"environment": {"gpu": "x"}})").find("environment.gpu: unknown key"), std::string::npos);
  EXPECT_NE(refusal(R"({"environment": {"api": 3}})").find("environment.api: must be a non-empty string"), std::string::npos);
  EXPECT_NE(refusal(R"({"environment": "webgpu"})").find("environment: must be a JSON object"), std::string::npos);
  EXPECT_NE(refusal(R"({"lights": [{"environment": {"api": "webgpu"}}]})").find("lights[0].environment: not a per-light key"),
            std::string::npos);
}

TEST(Declaration, AnAtlasTileIsItsSizeLessItsGuardBands) {
  const fs::path dir = fs::temp_directory_path() / ("shadowref-atlas-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  std::ofstream(dir / kCandidateFile) << R"({"atlas_tile": {"size": 683, "guard_band": 8},
    "lights": [{}, {"shadow_map_size": 1024}, {"atlas_tile": {"size": 512}}]})";
  const CandidateDeclaration d = read_declaration(dir, "shadowmap");
  EXPECT_EQ(d.shadow_map_size, 683 - 2 * 8) << "the view spans the tile less its guard bands";
  EXPECT_EQ(d.atlas_tile_size, 683);
  EXPECT_EQ(d.for_light(0).shadow_map_size, 667);
  EXPECT_EQ(d.for_light(1).shadow_map_size, 1024);
  EXPECT_EQ(d.for_light(1).atlas_tile_size, 0) << "a light's own map size replaces the tile";
  EXPECT_EQ(d.for_light(2).shadow_map_size, 512) << "no guard band: the whole tile";
  EXPECT_EQ(std::count(d.defaulted.begin(), d.defaulted.end(), std::string("shadow_map_size")), 0);
  // Written back as a tile (never beside shadow_map_size, which the reader refuses), read the same.
  const std::string text = declaration_text(d);
  EXPECT_EQ(text.find("\"shadow_map_size\": 667"), std::string::npos);
  std::ofstream(dir / kCandidateFile) << text;
  const CandidateDeclaration again = read_declaration(dir, "shadowmap");
  EXPECT_EQ(again.shadow_map_size, 667);
  EXPECT_EQ(again.for_light(1).shadow_map_size, 1024);
  EXPECT_EQ(again.for_light(2).shadow_map_size, 512);
  EXPECT_EQ(declaration_text(again), text);
  fs::remove_all(dir);
}

// "light_views": "declared": each light's views (view and projection, column-major) and, for
// cascades, their splits, read and written back the same; everything malformed refused with the
// JSON path that is wrong.
TEST(Declaration, DeclaredLightMatricesRoundTripAndMalformedOnesAreRefused) {
  const fs::path dir = fresh_dir("declared");
  const std::string identity = "[1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1]";
  const std::string shifted = "[1,0,0,0, 0,1,0,0, 0,0,1,0, 0.25,0,-3,1]";  // column-major: the translation last
  std::ofstream(dir / kCandidateFile) << R"({"shadow_map_size": 1024, "light_views": "declared", "lights": [
    {"views": [{"view": )" << shifted << R"(, "projection": )" << identity << R"(}]},
    {"views": [{"view": )" << identity << R"(, "projection": )" << identity << R"(},
               {"view": )" << identity << R"(, "projection": )" << identity << R"(}], "cascade_splits": [0.1, 5, 40],
     "cascade_blend": 0.1}]})";
  const CandidateDeclaration d = read_declaration(dir, "csm");
  ASSERT_EQ(d.lights.size(), 2u);
  EXPECT_EQ(d.for_light(0).light_views, LightViews::Declared);
  ASSERT_EQ(d.for_light(0).views.size(), 1u);
  EXPECT_EQ(d.for_light(0).views[0].view[12], 0.25) << "element [4 c + r]: column 3, row 0";
  EXPECT_EQ(d.for_light(0).views[0].view[14], -3.0);
  EXPECT_EQ(d.for_light(1).views.size(), 2u);
  EXPECT_EQ(d.for_light(1).cascade_splits, (std::vector<double>{0.1, 5, 40}));
  EXPECT_EQ(d.for_light(1).cascade_blend, 0.1);
  EXPECT_EQ(d.for_light(0).cascade_blend, 0.0) << "a hard switch unless declared";
  const std::string text = declaration_text(d);
  std::ofstream(dir / kCandidateFile) << text;
  EXPECT_EQ(declaration_text(read_declaration(dir, "csm")), text);

  const auto refused = [&](const std::string& json) { return refusal_of(dir, json); };
  const std::string one = R"({"view": )" + identity + R"(, "projection": )" + identity + "}";
  EXPECT_NE(refused(R"({"views": [)" + one + "]}").find("views: given, but light_views is not \"declared\""), std::string::npos);
  EXPECT_NE(refused(R"({"light_views": "declared", "views": [{"view": [1,2,3], "projection": )" + identity + "}]}")
                .find("views[0].view: must be an array of 16 numbers"),
            std::string::npos);
  EXPECT_NE(refused(R"({"light_views": "declared", "views": [{"view": )" + identity + R"(, "projection": [1,0,0,0, 0,1,0,0, 0,0,0,0, 0,0,0,0]}]})")
                .find("views[0]: projection x view is singular"),
            std::string::npos);
  EXPECT_NE(refused(R"({"light_views": "declared", "lights": [{"views": [)" + one + R"(], "cascade_splits": [1, 1]}]})")
                .find("lights[0].cascade_splits[1]: must be a finite depth >= 0, larger than the one before"),
            std::string::npos);
  EXPECT_NE(refused(R"({"light_views": "declared", "lights": [{"views": [)" + one + R"(], "cascade_splits": [1, 2], "cascade_blend": 1}]})")
                .find("lights[0].cascade_blend: must be a number in [0, 1)"),
            std::string::npos);
  EXPECT_NE(refused(R"({"light_views": "seen"})").find("light_views: must be \"own\", \"pack\" or \"declared\""), std::string::npos);
}

TEST(FileNames, OneLightHasNoIndexSeveralDo) {
  EXPECT_EQ(mask_name(0, 1), "mask.png");
  EXPECT_EQ(mask_name(0, 2), "mask_0.png");
  EXPECT_EQ(mask_name(1, 2), "mask_1.png");
  EXPECT_EQ(decided_name(0, 1), "decided.png");
  EXPECT_EQ(per_light_name("visibility", "exr", 3, 4), "visibility_3.exr");
}

TEST(FileNames, FindsTheMasksOfAFolderAndRefusesAmbiguity) {
  const fs::path d = fresh_dir("names");
  EXPECT_THROW(find_mask_names(d), InputError);
  const Image8 m{2, 1, 1, {kMaskLit, kMaskShadowed}};
  write_png(m, d / "mask_0.png");
  write_png(m, d / "mask_1.png");
  EXPECT_EQ(find_mask_names(d), (std::vector<std::string>{"mask_0.png", "mask_1.png"}));
  write_png(m, d / "mask.png");
  EXPECT_THROW(find_mask_names(d), InputError);
}

TEST(ImageIo, PngRoundTripsAndWrongChannelCountIsRefused) {
  const fs::path d = fresh_dir("io");
  const Image8 m{3, 2, 1, {kMaskLit, kMaskShadowed, kMaskNoSurface, 0, 255, 128}};
  write_png(m, d / "m.png");
  const Image8 back = read_image8(d / "m.png", 1);
  EXPECT_EQ(back.width, 3);
  EXPECT_EQ(back.height, 2);
  EXPECT_EQ(back.pixels, m.pixels);
  EXPECT_THROW(read_image8(d / "m.png", 3), InputError);
  EXPECT_THROW(read_image8(d / "missing.png", 1), InputError);
}

// A grey PNG written by libpng's own writer, not by ours: `bit_depth` bits per sample, each row
// already packed as PNG stores it, and a gAMA chunk when `gamma` > 0. False when libpng fails.
bool write_grey_png_with_libpng(const fs::path& file, int width, int height, int bit_depth,
                                const std::vector<std::vector<png_byte>>& rows, double gamma) {
  std::FILE* f = std::fopen(file.c_str(), "wb");
  if (!f) return false;
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  std::vector<png_bytep> pointers;
  for (const auto& r : rows) pointers.push_back(const_cast<png_bytep>(r.data()));
  bool ok = png && info;
  if (ok && setjmp(png_jmpbuf(png))) ok = false;
  else if (ok) {
    png_init_io(png, f);
    png_set_IHDR(png, info, static_cast<png_uint_32>(width), static_cast<png_uint_32>(height), bit_depth,
                 PNG_COLOR_TYPE_GRAY, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    if (gamma > 0) png_set_gAMA(png, info, gamma);
    png_write_info(png, info);
    png_write_image(png, pointers.data());
    png_write_end(png, nullptr);
  }
  png_destroy_write_struct(&png, &info);
  std::fclose(f);
  return ok;
}

// The samples are the file's own: a gAMA chunk (here linear light, 1.0) changes none of them, as
// OpenImageIO's reader left them; 1-bit grey reads as 0 and 255, as OpenImageIO expanded it.
TEST(ImageIo, PngSamplesAreTheFilesOwnWhateverItsGammaAnd1BitGreyIs0And255) {
  const fs::path d = fresh_dir("png_kinds");
  ASSERT_TRUE(write_grey_png_with_libpng(d / "linear.png", 4, 1, 8, {{0, 64, 128, 255}}, 1.0));
  EXPECT_EQ(read_image8(d / "linear.png", 1).pixels, (std::vector<std::uint8_t>{0, 64, 128, 255}));
  // 0b1010'0000: lit, shadowed, lit, shadowed (the row's last four bits are padding).
  ASSERT_TRUE(write_grey_png_with_libpng(d / "one_bit.png", 4, 1, 1, {{0xA0}}, 0.0));
  EXPECT_EQ(read_image8(d / "one_bit.png", 1).pixels, (std::vector<std::uint8_t>{255, 0, 255, 0}));
  // 16-bit samples are refused by name, not narrowed.
  ASSERT_TRUE(write_grey_png_with_libpng(d / "sixteen.png", 1, 1, 16, {{0xff, 0xff}}, 0.0));
  try {
    read_image8(d / "sixteen.png", 1);
    ADD_FAILURE() << "a 16-bit PNG was read";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("pixel format uint16, expected 8-bit unsigned"), std::string::npos) << e.what();
  }
}

// A file named .png is read by the PNG reader only. These bytes (found by mask_compare_fuzzer,
// reliability/fuzz/corpus/mask_compare/rla_abort_in_oiio, minus its 4-byte length header) are no
// PNG; OpenImageIO's fallback to its other readers reached the RLA reader, which aborted the process
// in OpenImageIO 2.4. They must be one refused file, not a crash.
TEST(ImageIo, ABrokenPngIsAPngErrorNotAnotherFormatsAbort) {
  const fs::path d = fresh_dir("rla");
  std::ifstream in(SHADOWREF_RLA_ABORT_INPUT, std::ios::binary);
  ASSERT_TRUE(in) << SHADOWREF_RLA_ABORT_INPUT;
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_GT(bytes.size(), 4u);
  std::ofstream(d / "mask.png", std::ios::binary) << bytes.substr(4);
  EXPECT_THROW(read_image8(d / "mask.png", 1), InputError);
}

// PNG bytes in memory (a glTF's embedded mask): the same reader, the file's own channels, one-line
// errors naming what the caller names.
TEST(ImageIo, PngBytesInMemoryDecodeAsTheFileWould) {
  const Image8 ga{3, 2, 2, {255, 0, 255, 10, 255, 20, 255, 30, 255, 40, 255, 250}};
  const Image8 back = decode_png8(encode_png(ga), "embedded");
  EXPECT_EQ(back.width, 3);
  EXPECT_EQ(back.height, 2);
  EXPECT_EQ(back.channels, 2);
  EXPECT_EQ(back.pixels, ga.pixels);
  for (const std::string& bad : {std::string(), std::string("not a png"), encode_png(ga).substr(0, 40)}) {
    try {
      (void)decode_png8(bad, "level.gltf: image 0");
      ADD_FAILURE() << "decoded " << bad.size() << " bytes of garbage";
    } catch (const InputError& e) {
      EXPECT_EQ(std::string(e.what()).rfind("level.gltf: image 0: ", 0), 0u) << e.what();
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
    }
  }
}

TEST(StagedFolder, CommitReplacesAndAbandonLeavesTheOldFolder) {
  const fs::path d = fresh_dir("staged");
  const fs::path target = d / "result";
  fs::create_directories(target);
  std::ofstream(target / "old.txt") << "old";
  {
    StagedFolder s(target);
    std::ofstream(s.path() / "new.txt") << "new";
    EXPECT_TRUE(fs::exists(target / "old.txt"));  // nothing visible before commit
  }  // abandoned
  EXPECT_TRUE(fs::exists(target / "old.txt"));
  EXPECT_FALSE(fs::exists(target / "new.txt"));
  EXPECT_EQ(std::distance(fs::directory_iterator(d), fs::directory_iterator()), 1) << "the staging folder was left behind";
  {
    StagedFolder s(target);
    std::ofstream(s.path() / "new.txt") << "new";
    s.commit();
  }
  EXPECT_FALSE(fs::exists(target / "old.txt"));
  EXPECT_TRUE(fs::exists(target / "new.txt"));
}

TEST(StagedFolder, RefusesToReplaceASymlink) {
  const fs::path d = fresh_dir("link");
  fs::create_directories(d / "elsewhere");
  fs::create_directory_symlink(d / "elsewhere", d / "result");
  StagedFolder s(d / "result");
  std::ofstream(s.path() / "new.txt") << "new";
  EXPECT_THROW(s.commit(), std::runtime_error);
  EXPECT_TRUE(fs::is_symlink(d / "result"));
  EXPECT_FALSE(fs::exists(d / "elsewhere" / "new.txt"));
}

std::size_t entries(const fs::path& d) {
  return static_cast<std::size_t>(std::distance(fs::directory_iterator(d), fs::directory_iterator()));
}

std::string text_of(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), {});
}

TEST(StagedFolder, ReplacingLeavesNoPartialName) {
  const fs::path d = fresh_dir("exchange");
  for (const char* content : {"first", "second"}) {
    StagedFolder s(d / "result");
    std::ofstream(s.path() / "f.txt") << content;
    s.commit();
  }
  EXPECT_EQ(text_of(d / "result" / "f.txt"), "second");
  EXPECT_EQ(entries(d), 1u) << "the old folder was left under a partial name";
}

TEST(AtomicFile, ReplacesTheWholeFileAndLeavesNoPartialName) {
  const fs::path d = fresh_dir("atomic");
  write_file_atomically(d / "a.json", "{\"old\": 1}");
  write_file_atomically(d / "a.json", "{}");
  EXPECT_EQ(text_of(d / "a.json"), "{}");
  copy_file_atomically(d / "a.json", d / "b.json");
  EXPECT_EQ(text_of(d / "b.json"), "{}");
  EXPECT_EQ(entries(d), 2u);
}

// The final path and the system's reason, one line; the temporary file is gone.
TEST(AtomicFile, AFailedWriteNamesThePathAndTheReasonAndLeavesNothing) {
  const fs::path d = fresh_dir("atomic_fail");
  fs::create_directories(d / "taken");  // a folder where the file should go: the rename fails
  try {
    write_file_atomically(d / "taken", "bytes");
    ADD_FAILURE() << "no error";
  } catch (const FileError& e) {
    EXPECT_EQ(std::string(e.what()), (d / "taken").string() + ": cannot move the written file into place: Is a directory");
    EXPECT_EQ(e.errno_value(), EISDIR);
  }
  EXPECT_EQ(entries(d), 1u) << "the temporary file was left";
  try {
    write_png(Image8{1, 1, 1, {kMaskLit}}, d / "no_such_folder" / "mask.png");
    ADD_FAILURE() << "no error";
  } catch (const FileError& e) {
    EXPECT_EQ(std::string(e.what()), (d / "no_such_folder" / "mask.png").string() + ": cannot write: No such file or directory");
  }
}

TEST(AtomicFile, ReplacesASymlinkInsteadOfWritingThroughIt) {
  const fs::path d = fresh_dir("atomic_link");
  std::ofstream(d / "target.txt") << "kept";
  fs::create_symlink(d / "target.txt", d / "link.txt");
  write_file_atomically(d / "link.txt", "new");
  EXPECT_FALSE(fs::is_symlink(d / "link.txt"));
  EXPECT_EQ(text_of(d / "link.txt"), "new");
  EXPECT_EQ(text_of(d / "target.txt"), "kept");
}

// After SIGINT (the handlers installed, as the command line does) nothing more is published: a
// staged folder and a file in flight are removed, and Interrupted carries the signal. In a child
// process (the flag stays set for the rest of a process).
TEST(Interruption, ASignalStopsAtTheNextCommitPointAndLeavesNothing) {
  const fs::path d = fresh_dir("interrupted");
  EXPECT_EXIT(
      {
        install_interrupt_handlers();
        std::raise(SIGINT);  // handled: the process goes on
        int stopped = 0;
        try {
          StagedFolder s(d / "folder");
          std::ofstream(s.path() / "f.txt") << "x";
          s.commit();
        } catch (const Interrupted& i) {
          stopped += i.signal() == SIGINT;
        }
        try {
          write_file_atomically(d / "file.txt", "x");
        } catch (const Interrupted& i) {
          stopped += i.signal() == SIGINT;
        }
        ::_exit(stopped == 2 && entries(d) == 0 ? 0 : 1);  // not exit(): the fork has none of the parent's threads to join
      },
      ::testing::ExitedWithCode(0), "");
}

TEST(Techniques, NamesAreUniqueAndFindable) {
  for (const TechniqueName& t : kTechniques) {
    EXPECT_EQ(find_technique_name(t.name), &t);
  }
  EXPECT_EQ(find_technique_name("no-such-technique"), nullptr);
}

// --jobs 0: the cores not busy, rounded, never fewer than one; this machine's answer lies in
// [1, hardware_concurrency].
TEST(SpareCores, TheCoresTheLoadLeavesAtLeastOne) {
  EXPECT_EQ(spare_cores(8, 0.0), 8);
  EXPECT_EQ(spare_cores(8, 6.3), 2);
  EXPECT_EQ(spare_cores(8, 6.6), 1);
  EXPECT_EQ(spare_cores(2, 5.0), 1);
  EXPECT_EQ(spare_cores(0, 0.0), 1);
  const int here = spare_cores();
  EXPECT_GE(here, 1);
  EXPECT_LE(here, static_cast<int>(std::max(1u, std::thread::hardware_concurrency())));
}


// The error classes: one row per class, in their enum's order (error_class() indexes by it), each
// colour and name once, the explained ones exactly the explaining causes.
TEST(ErrorClasses, OneRowPerClassInOrderWithDistinctColoursAndNames) {
  for (std::size_t i = 0; i < kErrorClasses.size(); ++i) {
    const ErrorClassRow& r = kErrorClasses[i];
    EXPECT_EQ(static_cast<std::size_t>(r.id), i) << r.name;
    EXPECT_EQ(&error_class(r.id), &r);
    EXPECT_EQ(find_error_class(r.name), &r);
    for (std::size_t j = 0; j < i; ++j) {
      EXPECT_NE(kErrorClasses[j].colour, r.colour) << r.name;
      EXPECT_NE(kErrorClasses[j].name, r.name);
      if (!r.json_key.empty()) {
        EXPECT_NE(kErrorClasses[j].json_key, r.json_key);
      }
    }
    for (const Rgb& dim : {kDimmedShadowed, kDimmedNoSurface, kDimmedLit}) EXPECT_NE(dim, r.colour) << r.name;
  }
  EXPECT_TRUE(explains(Cause::TexelFootprint));
  EXPECT_TRUE(explains(Cause::DepthBias));
  EXPECT_FALSE(explains(Cause::Acne));
  EXPECT_FALSE(explains(Cause::Unexplained));
  for (const ErrorClassRow& r : kErrorClasses)
    EXPECT_EQ(r.explained, r.id == ErrorClass::Texel || r.id == ErrorClass::Bias) << r.name;
  EXPECT_EQ(error_class_of(Cause::Acne)->id, ErrorClass::Acne);
  EXPECT_EQ(error_class_of(Cause::Unexplained), nullptr);
}

TEST(ErrorClasses, TheHelpLineNamesEveryColourAndMeaning) {
  const std::string line = error_colours_line();
  for (const ErrorClassRow& r : kErrorClasses)
    EXPECT_NE(line.find(std::string(r.colour_name) + " = " + std::string(r.legend)), std::string::npos) << r.name;
  EXPECT_EQ(rgb_text({1, 22, 255}), "rgb(1, 22, 255)");
}

// One reading of a mask's values and of a flag: the class thresholds, nearest_mask_value through them.
TEST(MaskValues, OneReadingOfTheThreeValuesAndOfAFlag) {
  for (int v = 0; v < 256; ++v) {
    const auto b = static_cast<std::uint8_t>(v);
    const std::uint8_t expected = v < 64 ? kMaskShadowed : v < 192 ? kMaskNoSurface : kMaskLit;
    EXPECT_EQ(nearest_mask_value(b), expected) << v;
    EXPECT_EQ(mask_class(b), v < 64 ? kClassShadowed : v < 192 ? kClassNoSurface : kClassLit) << v;
    EXPECT_EQ(is_flag_set(b), v >= 128) << v;
    EXPECT_EQ(flag_bit(b), v >= 128 ? 1 : 0) << v;
  }
  EXPECT_TRUE(is_flag_set(kFlagSet));
  EXPECT_FALSE(is_flag_set(kFlagClear));
}

}  // namespace
}  // namespace shadowref::outputs
