// diff_command_test.cpp — `shadowref diff RUN_A RUN_B`: a run against itself lists nothing (exit 0);
// against a copy with one candidate mask changed it lists exactly that case, with the number of
// mask pixels that differ counted here independently, and --out writes a page whose images lie in
// its folder; a case missing from one run is listed; a missing report.json or a field of the wrong
// type is one line naming the file (and the JSON path), exit 4.
//
// The run is a real `conform` of one two-light scene with two techniques (two cases, two masks
// each), judged in a few seconds; the reference is cached across the tests, which CTest runs side by
// side.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "run_command.hpp"
#include "shadowref/outputs/cause.hpp"
#include "shadowref/outputs/image_io.hpp"

namespace shadowref {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

class DiffCommand : public ::testing::Test {
 protected:
  void SetUp() override {
    // One folder per test (CTest runs them side by side); one reference cache for all of them.
    root_ = fs::path(::testing::TempDir()) /
            ("shadowref_diff_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(root_);
    fs::create_directories(root_);
    const test::CommandResult r =
        test::run_command({SHADOWREF_EXE, "conform", "--scenes", "two_lights", "--techniques", "planar,shadowmap", "--out",
                           run_a().string(), "--cache", (fs::path(::testing::TempDir()) / "shadowref_diff_cache").string(),
                           "--jobs", "1", "--quiet"});
    // Any verdict will do: diff compares runs, whatever they found.
    ASSERT_TRUE(r.exit_code == 0 || r.exit_code == 1 || r.exit_code == 2) << r.out << r.err;
  }
  void TearDown() override {
    if (!HasFailure()) fs::remove_all(root_);
  }

  fs::path run_a() const { return root_ / "a"; }
  // A copy of run A, to change.
  fs::path copy_of_a(const std::string& name) const {
    fs::copy(run_a(), root_ / name, fs::copy_options::recursive);
    return root_ / name;
  }
  static json read_json(const fs::path& f) { return json::parse(std::ifstream(f)); }
  static void write_json(const fs::path& f, const json& j) { std::ofstream(f) << j.dump(2); }
  static test::CommandResult diff(const std::vector<std::string>& args) {
    std::vector<std::string> argv = {SHADOWREF_EXE, "diff"};
    argv.insert(argv.end(), args.begin(), args.end());
    return test::run_command(argv);
  }
  static std::vector<std::string> lines_starting(const std::string& text, const std::string& prefix) {
    std::vector<std::string> out;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);)
      if (line.rfind(prefix, 0) == 0) out.push_back(line);
    return out;
  }

  fs::path root_;
};

TEST_F(DiffCommand, ARunAgainstItselfListsNothing) {
  const test::CommandResult r = diff({run_a().string(), run_a().string(), "--out", (root_ / "page").string()});
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("2 cases compared, 0 changed"), std::string::npos) << r.out;
  EXPECT_TRUE(lines_starting(r.out, "changed").empty()) << r.out;
  EXPECT_TRUE(lines_starting(r.out, "only").empty()) << r.out;
  std::ifstream page(root_ / "page" / "diff.html");
  const std::string html((std::istreambuf_iterator<char>(page)), std::istreambuf_iterator<char>());
  EXPECT_NE(html.find("Nothing changed"), std::string::npos);
}

// One light's candidate mask of one case changed in B's report: exactly that case is listed, with
// the pixels that differ as counted here from the two files.
TEST_F(DiffCommand, OneChangedMaskListsExactlyThatCase) {
  const fs::path b = copy_of_a("b");
  const json report = read_json(b / "report.json");
  const json& changed = report["cases"][1];
  ASSERT_EQ(changed["lights"].size(), 2u);
  const std::string rel = changed["lights"][1]["candidate"];
  outputs::Image8 mask = outputs::read_image8(b / "report" / rel, 1);
  for (int y = 40; y < 47; ++y)
    for (int x = 100; x < 110; ++x) {
      std::uint8_t& v = mask.pixels[static_cast<std::size_t>(y * mask.width + x)];
      v = v == 255 ? 0 : 255;
    }
  outputs::write_png(mask, b / "report" / rel);
  // The independent count: every light's mask of every case, byte by byte.
  std::size_t differ = 0;
  for (const json& c : report["cases"])
    for (const json& l : c["lights"]) {
      const outputs::Image8 ia = outputs::read_image8(run_a() / "report" / l["candidate"].get<std::string>(), 1);
      const outputs::Image8 ib = outputs::read_image8(b / "report" / l["candidate"].get<std::string>(), 1);
      for (std::size_t i = 0; i < ia.pixels.size(); ++i) differ += ia.pixels[i] != ib.pixels[i];
    }
  ASSERT_EQ(differ, 70u);

  const std::string name = changed["scene"].get<std::string>() + "@" + changed["technique"].get<std::string>();
  const test::CommandResult r = diff({run_a().string(), b.string(), "--out", (root_ / "page").string()});
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
  const std::vector<std::string> listed = lines_starting(r.out, "changed");
  ASSERT_EQ(listed.size(), 1u) << r.out;
  EXPECT_NE(listed[0].find(name + ": masks differ in 70 of " + std::to_string(2 * mask.pixel_count()) + " px"), std::string::npos)
      << listed[0];
  EXPECT_NE(r.out.find("2 cases compared, 1 changed"), std::string::npos) << r.out;

  const test::CommandResult j = diff({run_a().string(), b.string(), "--json"});
  EXPECT_EQ(j.exit_code, 1) << j.err;
  const json out = json::parse(j.out);
  ASSERT_EQ(out["cases"].size(), 1u);
  EXPECT_EQ(out["cases"][0]["mask_pixels_differ"], differ);
  EXPECT_EQ(out["cases"][0]["mask_pixels_differ_per_light"], json::array({0, 70}));
}

// The page of that diff: every image it shows lies in its folder (a relative path, no ".."), no
// script, and the mask-difference picture highlights exactly the pixels that differ.
TEST_F(DiffCommand, ThePageShowsItsOwnImages) {
  const fs::path b = copy_of_a("b");
  const json report = read_json(b / "report.json");
  const std::string rel = report["cases"][0]["lights"][0]["candidate"];
  outputs::Image8 mask = outputs::read_image8(b / "report" / rel, 1);
  for (std::size_t i = 0; i < 25; ++i) mask.pixels[i * 997] = mask.pixels[i * 997] == 0 ? 255 : 0;
  outputs::write_png(mask, b / "report" / rel);
  const fs::path page = root_ / "page";
  const test::CommandResult r = diff({run_a().string(), b.string(), "--out", page.string()});
  ASSERT_EQ(r.exit_code, 1) << r.out << r.err;

  std::ifstream in(page / "diff.html");
  const std::string html((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(html.find("<script"), std::string::npos);
  const std::regex src("src=\"([^\"]*)\"");
  std::vector<std::string> images;
  for (auto it = std::sregex_iterator(html.begin(), html.end(), src); it != std::sregex_iterator(); ++it) images.push_back((*it)[1]);
  EXPECT_EQ(images.size(), 10u);  // per light: A's mask and error, B's, and the difference
  std::string difference;
  for (const std::string& s : images) {
    EXPECT_FALSE(fs::path(s).is_absolute()) << s;
    EXPECT_EQ(s.find(".."), std::string::npos) << s;
    EXPECT_TRUE(fs::is_regular_file(page / s)) << s;
    if (s.find("difference_mask_0.png") != std::string::npos) difference = s;
  }
  ASSERT_FALSE(difference.empty());
  const outputs::Image8 picture = outputs::read_image8(page / difference, 3);
  std::size_t highlighted = 0;
  for (std::size_t i = 0; i < picture.pixel_count(); ++i) {
    const outputs::Rgb px{picture.pixels[3 * i], picture.pixels[3 * i + 1], picture.pixels[3 * i + 2]};
    highlighted += px != outputs::kDimmedLit && px != outputs::kDimmedShadowed && px != outputs::kDimmedNoSurface;
  }
  EXPECT_EQ(highlighted, 25u);
  // Only diff.html and its images' folder are written there.
  std::vector<std::string> written;
  for (const auto& e : fs::directory_iterator(page)) written.push_back(e.path().filename().string());
  std::sort(written.begin(), written.end());
  EXPECT_EQ(written, (std::vector<std::string>{"diff-images", "diff.html"}));
}

TEST_F(DiffCommand, ACaseInOneRunOnlyIsListed) {
  const fs::path b = copy_of_a("b");
  json report = read_json(b / "report.json");
  const std::string gone = report["cases"][0]["scene"].get<std::string>() + "@" + report["cases"][0]["technique"].get<std::string>();
  report["cases"].erase(0);
  write_json(b / "report.json", report);
  const test::CommandResult r = diff({run_a().string(), b.string()});
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
  const std::vector<std::string> listed = lines_starting(r.out, "only A");
  ASSERT_EQ(listed.size(), 1u) << r.out;
  EXPECT_NE(listed[0].find(gone), std::string::npos) << listed[0];
  EXPECT_TRUE(lines_starting(r.out, "changed").empty()) << r.out;
  EXPECT_NE(r.out.find("2 cases compared, 1 changed (1 only in A, 0 only in B)"), std::string::npos) << r.out;
  const test::CommandResult back = diff({b.string(), run_a().string()});
  EXPECT_EQ(back.exit_code, 1);
  EXPECT_EQ(lines_starting(back.out, "only B").size(), 1u) << back.out;
}

TEST_F(DiffCommand, AMissingReportIsOneLineNamingIt) {
  const fs::path nowhere = root_ / "nowhere";
  const test::CommandResult r = diff({run_a().string(), nowhere.string(), "--out", (root_ / "page").string()});
  EXPECT_EQ(r.exit_code, 4) << r.out << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_NE(r.err.find((nowhere / "report.json").string()), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(root_ / "page"));

  // A field of the wrong type: the file and its JSON path.
  const fs::path b = copy_of_a("b");
  json report = read_json(b / "report.json");
  report["cases"][1]["status"] = 5;
  write_json(b / "report.json", report);
  const test::CommandResult t = diff({run_a().string(), b.string()});
  EXPECT_EQ(t.exit_code, 4) << t.out << t.err;
  EXPECT_EQ(std::count(t.err.begin(), t.err.end(), '\n'), 1) << t.err;
  EXPECT_NE(t.err.find((b / "report.json").string() + ": cases[1].status"), std::string::npos) << t.err;
}

TEST(DiffCommandHelp, DescribesIt) {
  const test::CommandResult r = test::run_command({SHADOWREF_EXE, "diff", "--help"});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  for (const char* needle : {"RUN_A", "RUN_B", "--out", "--json", "Exit: 0 nothing changed, 1 changes found, 4 bad input"})
    EXPECT_NE(r.out.find(needle), std::string::npos) << needle << "\n" << r.out;
  const test::CommandResult top = test::run_command({SHADOWREF_EXE, "--help"});
  EXPECT_NE(top.out.find("diff"), std::string::npos) << top.out;
}

}  // namespace
}  // namespace shadowref
