// shadowref/conform/judge.hpp — the one judge: everything a case's verdict needs, assembled in one
// place that `shadowref conform`, `shadowref compare` and every test that judges call.
//
// For one candidate folder against one reference folder of a prepared scene it
//   1. reads the candidate's declaration (candidate.json, outputs/candidate.hpp; its defaults
//      when absent) and takes the technique judged from the caller, else from that file;
//   2. picks the technique's threshold (compare/thresholds.hpp);
//   3. for a technique with texel and bias bands, explains wrong pixels by the scene's cause model
//      (reference/causes.hpp) under that declaration — a hard map's size on the pack's grid first
//      checked against the candidate's own staircases (staircases.hpp);
//   4. for a soft technique, judges the lit fraction of every light with an area in visibility
//      units (compare/visibility.hpp) with the same cause model's bands;
//   5. asks what the verdict could have seen: the known blatant errors of the reference's own masks
//      under the same declaration (resolving_power.hpp);
//   6. gives the case's status under the scene file's expectation (status.hpp), and for an expected
//      failure checks its signature: the errors' predicted kind, and, for a candidate that is not
//      our own render, the technique's own model of its failure (our renderer's masks of it).
// Nothing else decides a verdict: the same folders, reference and scene give the same verdict,
// counts and causes whoever asks.
#pragma once

#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>

#include "shadowref/compare/compare.hpp"
#include "shadowref/tolerance/resolving_power.hpp"
#include "shadowref/conform/status.hpp"
#include "shadowref/outputs/candidate.hpp"
#include "shadowref/scene/prepared_scene.hpp"

namespace shadowref::reference {
class CauseModel;
}
namespace shadowref::renderer {
class Renderer;
}

namespace shadowref::conform {

class CauseMemo;

// One case: which folders, judged as which technique.
struct CaseToJudge {
  std::filesystem::path reference_dir;  // the reference's masks and decided pixels for the prepared scene
  std::filesystem::path candidate_dir;  // the candidate's masks (and candidate.json)
  // The technique whose threshold, causes and expectation judge; empty: candidate.json's
  // "technique"; empty there too: judged by the strictest threshold, as expected to pass.
  std::string technique;
  // Our own renderer drew the candidate: it is the technique's model of its failure, so an
  // expected failure's model signature is not drawn again.
  bool candidate_is_ours = false;
  // Where the technique's model of its failure is drawn when an expected failure needs it; empty:
  // the model signature is not checked (and the status says so).
  std::filesystem::path model_dir;
};

struct CaseJudgement {
  std::string technique;                       // judged as
  std::string technique_source;                // "the caller", "candidate.json", or "none: the strictest"
  outputs::CandidateDeclaration declaration;   // what the candidate declares (defaults marked)
  compare::FolderComparison comparison;
  scene::Expectation expectation;              // the scene file's, for `technique` (default: pass)
  Status status = Status::Error;
  std::string signature;                       // how an expected failure was checked to be the predicted one
  std::string unmet_expectation;               // status.hpp's unmet_expectation
  std::string causes;                          // which causes may explain wrong pixels, in words
  double model_seconds = 0;                    // spent drawing the technique's model (inside the judging)
  // What the verdict could have seen under this declaration (resolving_power.hpp); absent when the
  // scene is not known or the judge was asked not to probe (Judge's `probe`).
  std::optional<tolerance::ResolvingPower> resolving_power;
};

// The judge of a run: the cause model of each prepared scene (its BVH) and the renderer that draws
// the techniques' models of their failures, each built when a case first needs it.
class Judge {
 public:
  // `probe`: compute each case's resolving power (the probes cost most of the judging; a run that
  // reads only the verdicts, such as a sweep, may leave them out: the verdicts are the same).
  explicit Judge(bool probe = true);
  ~Judge();
  Judge(const Judge&) = delete;
  Judge& operator=(const Judge&) = delete;

  // Judges `c` on `prepared` (at the reference's resolution, in the run convention); `prepared`
  // must outlive the Judge. Null when the scene is not known: nothing explains a wrong pixel (the
  // strictest reading) and nothing is expected; a soft technique, whose lit fraction cannot be
  // judged without its lights, is then refused. Throws outputs::InputError for a missing,
  // unreadable or malformed candidate file or that refusal (BadInput) or a mask of another size
  // (SizeMismatch), renderer::GlError when the model needs a GL context and none can be made.
  CaseJudgement judge(const scene::PreparedScene* prepared, const CaseToJudge& c);

 private:
  reference::CauseModel& causes_of(const scene::PreparedScene& prepared);
  std::filesystem::path draw_model(const scene::PreparedScene& prepared, const std::string& technique,
                                   const std::filesystem::path& reference_dir, const std::filesystem::path& dir);
  std::map<const scene::PreparedScene*, std::unique_ptr<reference::CauseModel>> causes_;
  // The cause model's answers per scene and declaration, asked before the model (cause_memo.hpp).
  std::unique_ptr<CauseMemo> memo_;
  // Per reference folder, threshold and declaration as judged: the probes do not depend on the candidate.
  std::map<std::string, tolerance::ResolvingPower> resolving_;
  std::unique_ptr<renderer::Renderer> model_gl_;
  bool probe_ = true;
};

}  // namespace shadowref::conform
