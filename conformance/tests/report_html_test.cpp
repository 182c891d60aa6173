// report_html_test.cpp — the HTML report loaded in headless Chromium (Debian's /usr/bin/chromium):
// after the page's load event its script marks every image that did not resolve
// (img.complete && naturalWidth == 0) and writes the counts into <body data-images data-broken
// data-checked>; --dump-dom prints the DOM, and we count the case rows and read the marks.
// Skipped (not failed) where Chromium is not installed.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <regex>
#include <string>

#include "run_command.hpp"
#include "shadowref/outputs/image_io.hpp"
#include "shadowref/report/html.hpp"

namespace shadowref {
namespace {

namespace fs = std::filesystem;
constexpr const char* kChromium = "/usr/bin/chromium";

struct Dom {
  std::string html;
  int images = -1, broken = -1, rows = 0;
  bool checked = false;
};

int attribute(const std::string& body, const std::string& name) {
  std::smatch m;
  if (std::regex_search(body, m, std::regex(name + "=\"([0-9]+)\""))) return std::stoi(m[1]);
  return -1;
}

Dom load(const fs::path& page) {
  const fs::path profile = fs::temp_directory_path() / ("shadowref-chromium-" + std::to_string(::getpid()));
  fs::remove_all(profile);
  const test::CommandResult r = test::run_command(
      {kChromium, "--headless", "--no-sandbox", "--disable-gpu", "--no-first-run", "--disable-background-networking",
       "--disable-component-update", "--disable-sync", "--user-data-dir=" + profile.string(),
       "--virtual-time-budget=10000", "--dump-dom", "file://" + fs::absolute(page).string()});
  fs::remove_all(profile);
  Dom d;
  d.html = r.out;
  EXPECT_EQ(r.exit_code, 0) << r.err;
  std::smatch m;
  if (std::regex_search(r.out, m, std::regex("<body[^>]*>"))) {
    const std::string body = m[0];
    d.images = attribute(body, "data-images");
    d.broken = attribute(body, "data-broken");
    d.checked = body.find("data-checked=\"1\"") != std::string::npos;
  }
  for (std::size_t p = 0; (p = r.out.find("<tr class=\"case\"", p)) != std::string::npos; ++p) ++d.rows;
  return d;
}

void write_mask(const fs::path& file, std::uint8_t v, int channels = 1) {
  fs::create_directories(file.parent_path());
  outputs::write_png(outputs::Image8{8, 8, channels, std::vector<std::uint8_t>(static_cast<std::size_t>(64 * channels), v)}, file);
}

// A report.json-shaped object with `n` cases, each with its three mask images and a shaded one.
nlohmann::json synthetic(const fs::path& dir, int n) {
  nlohmann::json r;
  r["backend"] = "llvmpipe";
  r["scenes"] = {"alpha", "beta"};
  r["techniques"] = nlohmann::json::array();
  r["summary"] = {{"cases", n}, {"pass", n}};
  r["plan"] = nlohmann::json::object();  // every report has one: the page reads a run through its record
  r["cases"] = nlohmann::json::array();
  for (int i = 0; i < n; ++i) {
    const std::string t = "tech" + std::to_string(i / 2);
    if (i % 2 == 0) r["techniques"].push_back(t);
    const std::string scene = i % 2 ? "beta" : "alpha";
    const std::string base = "img/" + scene + "/" + t + "/";
    write_mask(dir / base / "reference.png", 255);
    write_mask(dir / base / "candidate.png", 0);
    write_mask(dir / base / "error.png", 90, 3);
    write_mask(dir / base / "shaded.png", 200, 3);
    r["cases"].push_back({{"scene", scene}, {"technique", t}, {"status", i == 1 ? "XFAIL" : "PASS"},
                          {"expected", i == 1 ? "fail" : "pass"}, {"why", i == 1 ? "a <known> limit & its why" : ""},
                          {"comparison", {{"total", {{"wrong", 0}, {"unexplained", 0}, {"wrong_percent", 0.0}}}, {"reasons", nlohmann::json::array()}}},
                          {"lights", {{{"mask", "mask.png"}, {"reference", base + "reference.png"}, {"candidate", base + "candidate.png"},
                                       {"error", base + "error.png"}, {"metrics", {{"wrong", 0}}}}}},
                          {"shaded", base + "shaded.png"}});
  }
  return r;
}

class ReportHtml : public ::testing::Test {
 protected:
  void SetUp() override {
    // scripts/setup.sh installs Debian's chromium: without it the report is unchecked, which fails.
    ASSERT_TRUE(fs::exists(kChromium)) << kChromium << " is not installed (scripts/setup.sh installs it)";
    dir = fs::path(SHADOWREF_TEST_OUT) / ::testing::UnitTest::GetInstance()->current_test_info()->name();
    fs::remove_all(dir);
    fs::create_directories(dir);
  }
  fs::path dir;
};

TEST_F(ReportHtml, SyntheticReportHasEveryImageAndOneRowPerCase) {
  const nlohmann::json r = synthetic(dir, 6);
  report::write_html(r, dir / "index.html");
  const Dom d = load(dir / "index.html");
  ASSERT_TRUE(d.checked) << "the page's image check did not run:\n" << d.html.substr(0, 2000);
  EXPECT_EQ(d.rows, 6);
  // Per case: reference, candidate, error, shaded, and the viewer's two stacked images.
  EXPECT_EQ(d.images, 6 * (4 + 2));
  EXPECT_EQ(d.broken, 0);
  // The why is shown, escaped.
  EXPECT_NE(d.html.find("a &lt;known&gt; limit &amp; its why"), std::string::npos);
}

TEST_F(ReportHtml, AMissingImageIsCaught) {
  nlohmann::json r = synthetic(dir, 2);
  r["cases"][1]["lights"][0]["error"] = "img/does-not-exist.png";
  report::write_html(r, dir / "index.html");
  const Dom d = load(dir / "index.html");
  ASSERT_TRUE(d.checked);
  EXPECT_EQ(d.broken, 1);
  EXPECT_NE(d.html.find("img/does-not-exist.png</pre>"), std::string::npos);
}

// A candidate's declaration is listed with its case; a volume's without the map settings (map size,
// filter, biases, depth faces), which mean nothing for it, and without their defaults.
TEST_F(ReportHtml, AVolumeCandidateListsNoMapSettings) {
  nlohmann::json r = synthetic(dir, 2);
  const nlohmann::json declared = {{"producer", "an-engine"}, {"version", "1"}, {"convention", "gl"}, {"shadow_map_size", 1024},
                                   {"slope_bias_texels", 2.0}, {"defaulted", {"version", "slope_bias_texels", "depth_faces"}}};
  r["cases"][0]["technique"] = "volume-zfail";
  r["cases"][0]["candidate"] = declared;
  r["cases"][1]["technique"] = "shadowmap";
  r["cases"][1]["candidate"] = declared;
  report::write_html(r, dir / "index.html");
  std::ifstream in(dir / "index.html");
  const std::string html((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::size_t first = html.find("<tr class=\"case\"");
  const std::size_t second = html.find("<tr class=\"case\"", first + 1);
  ASSERT_NE(second, std::string::npos);
  const std::string volume = html.substr(first, second - first), map = html.substr(second);
  EXPECT_NE(volume.find("candidate: an-engine 1"), std::string::npos);
  EXPECT_EQ(volume.find("slope bias"), std::string::npos) << volume;
  EXPECT_NE(volume.find("(defaulted: version)"), std::string::npos) << volume;
  EXPECT_NE(map.find("slope bias 2"), std::string::npos);
  EXPECT_NE(map.find("(defaulted: version, slope_bias_texels, depth_faces)"), std::string::npos);
}

TEST_F(ReportHtml, RealConformRunRendersEveryImage) {
  const test::CommandResult c = test::run_command({SHADOWREF_EXE, "conform", "--scenes", "ground_sphere,two_lights",
                                                   "--techniques", "volume-zfail,shadowmap", "--cache", SHADOWREF_TEST_CACHE,
                                                   "--out", dir.string(), "--quiet"});
  ASSERT_TRUE(c.exit_code == 0 || c.exit_code == 2) << c.err;
  EXPECT_NE(c.out.find("report: "), std::string::npos) << c.out;
  std::ifstream in(dir / "report.json");
  const nlohmann::json r = nlohmann::json::parse(in);
  ASSERT_EQ(r["cases"].size(), 4u);
  const Dom d = load(dir / "report" / "index.html");
  ASSERT_TRUE(d.checked);
  EXPECT_EQ(d.rows, 4);
  // ground_sphere: one light (3 masks + shaded + the viewer's reference, candidate and decided
  // overlay); two_lights: two lights (6 masks + shaded + two viewers).
  EXPECT_EQ(d.images, 2 * (4 + 3) + 2 * (7 + 2 * 3));
  EXPECT_EQ(d.broken, 0);
  // The image-diff modes are there for every light: swipe, flicker, amplification, decided overlay.
  for (const char* mode : {"shadowrefView(this,'swipe')", "shadowrefView(this,'flicker')", "shadowrefView(this,'amplify')",
                           "shadowrefOverlay(this)"}) {
    std::size_t n = 0;
    for (std::size_t at = d.html.find(mode); at != std::string::npos; at = d.html.find(mode, at + 1)) ++n;
    EXPECT_EQ(n, 6u) << mode;
  }
}

}  // namespace
}  // namespace shadowref
