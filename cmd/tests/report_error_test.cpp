// report_error_test.cpp — which escaped exception is the user's input (exit 4, or 3 for a size
// mismatch) and which is an internal failure (exit 5, said to be one), with the real exception
// types the libraries throw.
#include <gtest/gtest.h>

#include <cerrno>
#include <filesystem>
#include <stdexcept>
#include <system_error>

#include "command.hpp"
#include "shadowref/outputs/errors.hpp"
#include "shadowref/reference/embree_scene.hpp"
#include "shadowref/renderer/gl_context.hpp"
#include "shadowref/scene/load_scene.hpp"
#include "shadowref/scene/mesh_file.hpp"

namespace shadowref::cli {
namespace {

TEST(ReportError, TheUsersInputIsExit4) {
  EXPECT_EQ(report_error(BadInput("--scene: no such file")).exit_code, kExitBadInput);
  EXPECT_EQ(report_error(scene::SceneError("a.json: camera.near: must be > 0")).exit_code, kExitBadInput);
  EXPECT_EQ(report_error(scene::MeshFileError("bad OBJ")).exit_code, kExitBadInput);
  EXPECT_EQ(report_error(outputs::FileError("out/mask.png: cannot write")).exit_code, kExitBadInput);
  EXPECT_EQ(report_error(outputs::InputError(outputs::InputError::Kind::BadInput, "m.png: truncated")).exit_code, kExitBadInput);
  EXPECT_EQ(report_error(std::invalid_argument("unknown technique 'x'")).exit_code, kExitBadInput);
  const std::filesystem::filesystem_error fs("cannot create", std::filesystem::path("/root/x"),
                                             std::make_error_code(std::errc::permission_denied));
  const ErrorReport r = report_error(fs);
  EXPECT_EQ(r.exit_code, kExitBadInput);
  EXPECT_NE(r.line.find("/root/x"), std::string::npos) << r.line;
}

// A full disk, a quota, a read-only file system, no permission, a failing device: the environment's
// doing, exit 4 with the path and the system's reason, never "please report it".
TEST(ReportError, TheEnvironmentIsExit4WithThePathAndTheSystemsReason) {
  const ErrorReport full = report_error(outputs::FileError(std::filesystem::path("out/report.json"), "write", ENOSPC));
  EXPECT_EQ(full.exit_code, kExitBadInput);
  EXPECT_EQ(full.line, "out/report.json: cannot write: No space left on device");
  for (int e : {ENOSPC, EDQUOT, EROFS, EACCES, EIO}) {
    const ErrorReport r = report_error(std::system_error(e, std::generic_category(), "out/x.png"));
    EXPECT_EQ(r.exit_code, kExitBadInput) << r.line;
    EXPECT_EQ(r.line.find("internal error"), std::string::npos) << r.line;
  }
  // A call our code got wrong stays ours.
  EXPECT_EQ(report_error(std::system_error(EBADF, std::generic_category(), "fd")).exit_code, kExitInternal);
}

TEST(ReportError, ASizeMismatchIsExit3) {
  EXPECT_EQ(report_error(outputs::InputError(outputs::InputError::Kind::SizeMismatch, "64x64 vs 32x32")).exit_code,
            kExitSizeMismatch);
}

TEST(ReportError, InternalFailuresAreExit5AndSaySo) {
  for (const ErrorReport& r : {report_error(renderer::GlError("no OpenGL 3.3 context")),
                               report_error(reference::EmbreeError("Embree: rtcNewDevice failed")),
                               report_error(std::logic_error("broken invariant")), report_error(std::bad_alloc())}) {
    EXPECT_EQ(r.exit_code, kExitInternal);
    EXPECT_NE(r.line.find("internal error"), std::string::npos) << r.line;
    EXPECT_NE(r.line.find("not caused by your input"), std::string::npos) << r.line;
  }
}

}  // namespace
}  // namespace shadowref::cli
