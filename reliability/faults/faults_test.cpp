// faults_test.cpp — what a `shadowref conform` run leaves when its environment fails it: a full disk
// at several fill levels, a kill at ten points followed by a resume, SIGINT and SIGTERM, and every
// kind of reference cache file truncated and bit-flipped. Each fault is judged beside its no-fault
// control, the baseline run (docs/output-contract.md, "What you can rely on after a crash"):
//   - every file under --out is whole: no zero-length file, every PNG and EXR decodes, every JSON
//     parses; no file under a final name is half-written (a hidden `.<name>.partial-…` may remain
//     only after a SIGKILL, which no code can clean up after);
//   - a full disk is exit 4 with one line naming a path and "No space left on device";
//   - SIGINT / SIGTERM: exit 130 / 143, one line, nothing published after the signal, no partial names;
//   - a rerun after any of them gives the baseline's statuses;
//   - a damaged cache entry is recomputed, said so on one line naming the file, and heals to the
//     baseline's bytes.
// Fault points are counted (the n-th rename, the n-th write: fault_shim.cpp), never timed, so no test
// depends on the machine's speed. The run is small: 2 scenes (one and two lights) × 2 techniques at
// 64 × 64.
#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "run_command.hpp"

namespace shadowref::test {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const fs::path kRoot = SHADOWREF_FAULTS_DIR;
const fs::path kBaseline = kRoot / "baseline";

// --------------------------------------------------------------------------------------- the run

std::vector<std::string> conform_argv(const fs::path& out, const fs::path& cache = {}) {
  std::vector<std::string> a = {SHADOWREF_EXE, "conform", "--catalogue", SHADOWREF_SCENES_DIR, "--scenes", "ground_sphere,two_lights",
                                "--techniques", "planar,shadowmap", "--resolution", "64x64", "--jobs", "1", "--out", out.string()};
  if (!cache.empty()) a.insert(a.end(), {"--cache", cache.string()});
  return a;
}

// The environment of a run under the fault shim, counting only files under `under`.
std::vector<std::string> shim(const fs::path& under, std::vector<std::string> more = {}) {
  const char* asan = std::getenv("ASAN_OPTIONS");
  more.insert(more.end(), {"LD_PRELOAD=" SHADOWREF_FAULT_SHIM, "SHADOWREF_FAULT_UNDER=" + under.string(),
                           // Mesa's shader cache is written by threads of its own: off, so that only the
                           // run's own writes happen while a fault is armed
                           "MESA_SHADER_CACHE_DISABLE=true",
                           // a shim before the sanitizer runtime is fine for this test (the asan preset)
                           "ASAN_OPTIONS=" + std::string(asan ? asan : "") + ":verify_asan_link_order=0"});
  return more;
}

std::string read_text(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), {});
}

std::string last_line(const std::string& s) {
  std::string t = s;
  while (!t.empty() && t.back() == '\n') t.pop_back();
  const auto nl = t.rfind('\n');
  return nl == std::string::npos ? t : t.substr(nl + 1);
}

// "scene x technique" → status, from report.json.
std::map<std::string, std::string> statuses(const fs::path& out) {
  std::map<std::string, std::string> m;
  const json r = json::parse(read_text(out / "report.json"), nullptr, false);
  if (!r.is_object()) return m;
  for (const json& c : r["cases"]) m[c["scene"].get<std::string>() + " x " + c["technique"].get<std::string>()] = c["status"];
  return m;
}

bool is_partial(const fs::path& p) { return p.filename().string().find(".partial-") != std::string::npos; }

// Whatever is not whole under `dir`, one line each. `partials_allowed`: after a SIGKILL, hidden
// partial names may remain (their content is never read).
std::vector<std::string> problems(const fs::path& dir, bool partials_allowed) {
  std::vector<std::string> p;
  std::error_code ec;
  for (auto it = fs::recursive_directory_iterator(dir, ec); it != fs::recursive_directory_iterator(); it.increment(ec)) {
    const fs::path& f = it->path();
    if (is_partial(f)) {
      if (!partials_allowed) p.push_back(f.string() + ": a partial name was left");
      if (it->is_directory()) it.disable_recursion_pending();
      continue;
    }
    if (!it->is_regular_file()) continue;
    const std::string ext = f.extension().string();
    if (fs::file_size(f) == 0) {
      p.push_back(f.string() + ": zero-length");
    } else if (ext == ".png" || ext == ".exr") {
      auto in = OIIO::ImageInput::open(f.string());
      std::vector<float> px;
      if (in) px.resize(static_cast<std::size_t>(in->spec().image_pixels()) * static_cast<std::size_t>(in->spec().nchannels));
      if (!in || !in->read_image(0, 0, 0, in->spec().nchannels, OIIO::TypeDesc::FLOAT, px.data()) || !in->close())
        p.push_back(f.string() + ": does not decode: " + (in ? in->geterror() : OIIO::geterror()));
    } else if (ext == ".json") {
      if (json::parse(read_text(f), nullptr, false).is_discarded()) p.push_back(f.string() + ": does not parse");
    } else if (ext == ".html") {
      if (read_text(f).find("</html>") == std::string::npos) p.push_back(f.string() + ": truncated");
    }
  }
  return p;
}

std::string joined(const std::vector<std::string>& v) {
  std::string s;
  for (const std::string& x : v) s += x + "\n";
  return s;
}

struct Baseline {
  int exit_code = -1;
  std::map<std::string, std::string> statuses;
  long renames = 0, writes = 0;  // the run's fault points (fault_shim.cpp)
  fs::path out = kBaseline / "out";
};

// The baseline written by Baseline.AnUninterruptedRunIsWholeAndCounted (the CTest fixture).
Baseline baseline() {
  Baseline b;
  std::istringstream points(read_text(kBaseline / "points"));
  points >> b.renames >> b.writes;
  b.exit_code = std::stoi("0" + read_text(kBaseline / "exit_code"));
  b.statuses = statuses(b.out);
  return b;
}

fs::path fresh(const fs::path& dir) {
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// A run resumed in `out` after a fault gives the baseline's statuses and leaves whole files.
void expect_resume_equals_baseline(const fs::path& out, const Baseline& b) {
  const CommandResult r = run_command(conform_argv(out));
  EXPECT_EQ(r.exit_code, b.exit_code) << r.err;
  EXPECT_EQ(statuses(out), b.statuses);
  // A kill publishes nothing half-written: no entry it left can fail verification.
  EXPECT_EQ(r.err.find("failed verification"), std::string::npos) << r.err;
  EXPECT_EQ(problems(out, true), std::vector<std::string>{});
}

// --------------------------------------------------------------------------------- the baseline

TEST(Baseline, AnUninterruptedRunIsWholeAndCounted) {
  fresh(kBaseline);
  const CommandResult r =
      run_command(conform_argv(kBaseline / "out"), shim(kBaseline, {"SHADOWREF_FAULT_COUNT=" + (kBaseline / "points").string()}));
  ASSERT_TRUE(r.exit_code >= 0 && r.exit_code <= 2) << r.err;
  std::ofstream(kBaseline / "exit_code") << r.exit_code;
  const Baseline b = baseline();
  EXPECT_EQ(b.statuses.size(), 4u);
  EXPECT_GT(b.renames, 10);
  EXPECT_GT(b.writes, 10);
  EXPECT_EQ(problems(b.out, false), std::vector<std::string>{});
}

// ------------------------------------------------------------------------------------ full disk

// The bytes a tmpfs needs for `dir`'s files (each file takes whole 4 KiB pages; folders take none).
std::uintmax_t pages_used(const fs::path& dir) {
  std::uintmax_t n = 0;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file()) n += (e.file_size() + 4095) / 4096 * 4096;
  return n;
}

std::uintmax_t bytes_used(const fs::path& dir) {
  std::uintmax_t n = 0;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file()) n += e.file_size();
  return n;
}

// A mount namespace of our own: as root, `unshare --mount`; otherwise with a user namespace, as
// cmake/install_test/install_test.sh does. Empty where none can be made (a container without the
// capability): the tmpfs tests skip, the shim's full disk still runs.
std::vector<std::string> namespace_argv() {
  for (const char* unshare : {"/usr/bin/unshare", "/bin/unshare"}) {
    if (!fs::exists(unshare)) continue;
    std::vector<std::string> a = {unshare, "--mount"};
    if (::getuid() == 0) a.insert(a.end(), {"--propagation", "private"});
    else a.push_back("--map-root-user");
    fresh(kRoot / "probe");
    std::vector<std::string> probe = a;
    probe.insert(probe.end(), {"/bin/sh", "-c", "mount -t tmpfs -o size=4k none '" + (kRoot / "probe").string() + "'"});
    if (run_command(probe).exit_code == 0) return a;
  }
  return {};
}

std::string quoted(const std::vector<std::string>& argv) {
  std::string s;
  for (const std::string& a : argv) s += " '" + a + "'";
  return s;
}

// The checks of a run that ran out of space: exit 4, one line naming a path under `mnt` and the
// system's reason, whole files, nothing partial, no report.
void expect_full_disk_handled(const CommandResult& r, const fs::path& kept, const fs::path& mnt) {
  EXPECT_EQ(r.exit_code, 4) << r.err;
  const std::string line = last_line(r.err);
  EXPECT_NE(line.find("No space left on device"), std::string::npos) << r.err;
  EXPECT_NE(line.find(mnt.string()), std::string::npos) << "the line names no path of the run: " << line;
  EXPECT_EQ(line.find("internal error"), std::string::npos) << line;
  EXPECT_EQ(r.out, "");
  EXPECT_EQ(problems(kept, false), std::vector<std::string>{});
  EXPECT_FALSE(fs::exists(kept / "report.json")) << "a failed run left a report";
}

TEST(FullDisk, AtFourFillLevelsOfASizeLimitedFileSystem) {
  const Baseline b = baseline();
  const std::vector<std::string> ns = namespace_argv();
  if (ns.empty()) GTEST_SKIP() << "no mount namespace can be made here (unshare): the shim's full disk is the test";
  const std::uintmax_t need = pages_used(b.out);
  // Fill levels as fractions of what the finished run occupies; the last is the control.
  for (const double level : {0.1, 0.4, 0.7, 0.95, 3.0}) {
    SCOPED_TRACE("tmpfs of " + std::to_string(level) + " x the run's " + std::to_string(need) + " bytes");
    const fs::path dir = fresh(kRoot / "disk" / std::to_string(static_cast<int>(level * 100)));
    const fs::path mnt = dir / "mnt", kept = dir / "kept";
    fs::create_directories(mnt);
    const std::uintmax_t size = std::max<std::uintmax_t>(4096, static_cast<std::uintmax_t>(static_cast<double>(need) * level));
    std::vector<std::string> argv = ns;
    // The tmpfs lives as long as the namespace: what the run left is copied out, as it is, to be judged.
    argv.insert(argv.end(), {"/bin/sh", "-c",
                             "mount -t tmpfs -o size=" + std::to_string(size) + " none '" + mnt.string() + "' || exit 97;" +
                                 quoted(conform_argv(mnt / "out")) + "; rc=$?; cp -a '" + (mnt / "out").string() + "' '" +
                                 kept.string() + "' 2>/dev/null; exit $rc"});
    const CommandResult r = run_command(argv);
    ASSERT_NE(r.exit_code, 97) << r.err;
    if (level < 1) {
      expect_full_disk_handled(r, kept, mnt);
    } else {
      EXPECT_EQ(r.exit_code, b.exit_code) << r.err;
      EXPECT_EQ(statuses(kept), b.statuses);
      EXPECT_EQ(problems(kept, false), std::vector<std::string>{});
    }
  }
}

// The same where no file system can be mounted: the shim fails writes with ENOSPC past a budget.
TEST(FullDisk, AtTwoFillLevelsOfAWriteBudget) {
  const Baseline b = baseline();
  const std::uintmax_t need = bytes_used(b.out);
  for (const double level : {0.3, 0.9, 3.0}) {
    SCOPED_TRACE("a budget of " + std::to_string(level) + " x the run's " + std::to_string(need) + " bytes");
    const fs::path dir = fresh(kRoot / "budget" / std::to_string(static_cast<int>(level * 100)));
    const CommandResult r = run_command(
        conform_argv(dir / "out"),
        shim(dir, {"SHADOWREF_FAULT_DISK_BYTES=" + std::to_string(static_cast<std::uintmax_t>(static_cast<double>(need) * level))}));
    if (level < 1) {
      expect_full_disk_handled(r, dir / "out", dir);
    } else {
      EXPECT_EQ(r.exit_code, b.exit_code) << r.err;
      EXPECT_EQ(statuses(dir / "out"), b.statuses);
      EXPECT_EQ(problems(dir / "out", false), std::vector<std::string>{});
    }
  }
}

// ------------------------------------------------------------------------------------ kills

// Ten points spread over the run: five just before a result is renamed into place, five in the
// middle of a file's bytes. Each killed run leaves whole files; its resume gives the baseline.
TEST(Kill, AtTenPointsThenAResumeGivesTheUninterruptedStatuses) {
  const Baseline b = baseline();
  for (int i = 0; i < 10; ++i) {
    const bool in_write = i % 2 == 1;
    const long total = in_write ? b.writes : b.renames;
    const long point = std::max(1L, total * (2 * (i / 2) + 1) / 10);
    const std::string where = std::string(in_write ? "in write " : "before rename ") + std::to_string(point) + " of " + std::to_string(total);
    SCOPED_TRACE("SIGKILL " + where);
    const fs::path dir = fresh(kRoot / "kill" / std::to_string(i));
    const CommandResult r = run_command(
        conform_argv(dir / "out"), shim(dir, {std::string(in_write ? "SHADOWREF_FAULT_IN_WRITE=" : "SHADOWREF_FAULT_AT_RENAME=") +
                                                  std::to_string(point)}));
    ASSERT_EQ(r.exit_code, 128 + 9) << "the fault did not happen: " << r.err;
    EXPECT_FALSE(fs::exists(dir / "out" / "report.json")) << "a killed run left a report";
    EXPECT_EQ(problems(dir / "out", true), std::vector<std::string>{});
    expect_resume_equals_baseline(dir / "out", b);
  }
}

// ---------------------------------------------------------------------------------- signals

// SIGINT before a rename in the middle of the run, SIGTERM in the middle of a file's bytes: the
// run stops at its next commit point (nothing is published after the signal: the prompt stop),
// removes what was in flight, exits 128 + the signal with one line, and a rerun resumes.
TEST(Signal, SigintAndSigtermStopPromptlyLeaveNothingPartialAndResume) {
  const Baseline b = baseline();
  struct Stop {
    int signal;
    bool in_write;
    const char* name;
  };
  for (const Stop s : {Stop{2, false, "SIGINT"}, Stop{15, true, "SIGTERM"}}) {
    SCOPED_TRACE(s.name);
    const fs::path dir = fresh(kRoot / "signal" / s.name);
    const long point = (s.in_write ? b.writes : b.renames) / 2;
    const CommandResult r = run_command(
        conform_argv(dir / "out"),
        shim(dir, {std::string(s.in_write ? "SHADOWREF_FAULT_IN_WRITE=" : "SHADOWREF_FAULT_AT_RENAME=") + std::to_string(point),
                   "SHADOWREF_FAULT_SIGNAL=" + std::to_string(s.signal), "SHADOWREF_FAULT_COUNT=" + (dir / "points").string()}));
    EXPECT_EQ(r.exit_code, 128 + s.signal) << r.err;
    const std::string line = last_line(r.err);
    EXPECT_EQ(line.rfind("shadowref conform: interrupted by " + std::string(s.name), 0), 0u) << r.err;
    EXPECT_EQ(r.out, "");
    // The shim's counts at exit and when it raised the signal.
    long renames = 0, writes = 0, renames_then = -1, writes_then = -1;
    std::istringstream(read_text(dir / "points")) >> renames >> writes >> renames_then >> writes_then;
    EXPECT_EQ(renames, renames_then) << "results were published after the signal";
    // The file being written when the signal came may take one more write (its rest), then is dropped.
    EXPECT_LE(writes, writes_then + 1) << "files were written after the signal";
    EXPECT_FALSE(fs::exists(dir / "out" / "report.json"));
    EXPECT_EQ(problems(dir / "out", false), std::vector<std::string>{});
    expect_resume_equals_baseline(dir / "out", b);
  }
}

// ------------------------------------------------------------------------------ damaged cache

// The baseline's cache entry of `scene`.
fs::path entry_of(const fs::path& cache, const std::string& scene) {
  for (const auto& e : fs::directory_iterator(cache))
    if (e.path().filename().string().rfind(scene + "-", 0) == 0 && !is_partial(e.path())) return e.path();
  return {};
}

// Every kind of file an entry holds (one light: mask, decided, covered, shaded, visibility.exr,
// key.json), cut short and with one byte flipped, and key.json as an older shadowref wrote it: the
// next run says which entry failed and why, recomputes it to the baseline's bytes, and gives the
// baseline's statuses.
TEST(DamagedCache, EveryFileKindTruncatedOrBitFlippedIsRecomputedAndHeals) {
  const Baseline b = baseline();
  const fs::path clean = entry_of(b.out / "reference-cache", "ground_sphere");
  ASSERT_FALSE(clean.empty());
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(clean)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  ASSERT_EQ(names.size(), 6u) << joined(names);
  struct Damage {
    std::string file;
    std::string how;  // "truncated", "flipped", "older"
  };
  std::vector<Damage> damages;
  for (const std::string& n : names)
    for (const char* how : {"truncated", "flipped"}) damages.push_back({n, how});
  damages.push_back({"key.json", "older"});
  for (const Damage& d : damages) {
    SCOPED_TRACE(d.file + " " + d.how);
    const fs::path dir = fresh(kRoot / "cache" / (d.file + "-" + d.how));
    fs::copy(b.out / "reference-cache", dir / "cache", fs::copy_options::recursive);
    const fs::path file = entry_of(dir / "cache", "ground_sphere") / d.file;
    std::string bytes = read_text(file);
    if (d.how == "truncated") {
      bytes.resize(bytes.size() > 600 ? 300 : bytes.size() / 2);  // the 300 bytes, or half a small file
    } else if (d.how == "flipped") {
      bytes[bytes.size() / 2] = static_cast<char>(bytes[bytes.size() / 2] ^ 0x01);
    } else {
      json k = json::parse(bytes);
      for (const char* field : {"format", "files", "key_json_hash", "files_hash"}) k.erase(field);
      bytes = k.dump(2);
    }
    std::ofstream(file, std::ios::binary | std::ios::trunc) << bytes;
    const CommandResult r = run_command(conform_argv(dir / "out", dir / "cache"));
    EXPECT_EQ(r.exit_code, b.exit_code) << r.err;
    EXPECT_EQ(statuses(dir / "out"), b.statuses);
    const std::string said = "reference ground_sphere: the cached entry failed verification (";
    const auto at = r.err.find(said);
    EXPECT_NE(at, std::string::npos) << "the damage went unnoticed:\n" << r.err;
    if (at != std::string::npos) {
      const std::string line = r.err.substr(at, r.err.find('\n', at) - at);
      EXPECT_NE(line.find(d.how == "older" ? "older shadowref" : d.file), std::string::npos) << line;
      EXPECT_NE(line.find("recomputed"), std::string::npos) << line;
    }
    EXPECT_EQ(r.err.find("reference two_lights: the cached entry failed"), std::string::npos) << "an intact entry was recomputed";
    // Healed: the entry holds the baseline's bytes again (the reference is deterministic).
    const fs::path healed = entry_of(dir / "cache", "ground_sphere");
    for (const std::string& n : names) EXPECT_EQ(read_text(healed / n), read_text(clean / n)) << n;
  }
}

}  // namespace
}  // namespace shadowref::test
