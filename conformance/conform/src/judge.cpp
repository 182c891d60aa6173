// judge.cpp — the one judge (judge.hpp): declaration, threshold, causes, lit fraction, resolving
// power, status and the expected failure's signature, in that order.
#include "shadowref/conform/judge.hpp"

#include <chrono>
#include <utility>

#include "cause_memo.hpp"
#include "shadowref/tolerance/staircases.hpp"
#include "shadowref/tolerance/zigzags.hpp"
#include "shadowref/outputs/atomic_file.hpp"
#include "shadowref/outputs/errors.hpp"
#include "shadowref/outputs/file_names.hpp"
#include "shadowref/outputs/image_io.hpp"
#include "shadowref/outputs/techniques.hpp"
#include "shadowref/reference/causes.hpp"
#include "shadowref/renderer/renderer.hpp"

namespace shadowref::conform {
namespace {

// The comparison's options for `technique` under `declared`: the cause model's explainers (bound to
// `model`, `declared`, which must outlive the comparison) and, for a soft technique, the lit
// fraction of every light with an area. `causes` gets them in words.
struct Explainers {
  compare::Explainer mask;
  compare::ImpossiblePixels impossible;
  compare::VisibilityExplainer visibility;
  compare::VisibilityTexelShift texel_shift;
};

// `memo` keeps the model's answers under `declared` (cause_memo.hpp): the case's comparison, its
// probes and every later case of the same declaration ask it first.
compare::CompareOptions options_for(const scene::PreparedScene& prepared, const compare::Threshold& threshold,
                                    const outputs::TechniqueName* technique, const outputs::CandidateDeclaration& declared,
                                    reference::CauseModel* model, CauseMemo::Table* memo, Explainers& explainers,
                                    std::string& causes) {
  const scene::Scene& s = *prepared.scene;
  compare::CompareOptions o;
  o.no_cast_shadow_invariant = s.invariant_no_cast_shadow;
  causes = "none (an exact technique, or one the suite does not know: every wrong pixel is unexplained)";
  if (threshold.bands) {
    explainers.mask = [model, memo, &declared](std::size_t light, int x, int y, bool candidate_lit) {
      outputs::Cause cause;
      if (memo->find(light, x, y, candidate_lit, cause)) return cause;
      cause = model->explain(light, x, y, declared.for_light(light), candidate_lit);
      memo->remember(light, x, y, candidate_lit, cause);
      return cause;
    };
    o.explain = &explainers.mask;
    causes = "texel footprint and depth bias, from the scene and the candidate's declaration";
    bool zigzags = false;
    for (std::size_t i = 0; i < s.lights.size(); ++i) zigzags = zigzags || tolerance::zigzags_apply(prepared, i, technique, declared.for_light(i));
    if (zigzags) {
      explainers.impossible = [model, &prepared, technique, &declared](std::size_t light, const outputs::Image8& reference,
                                                                      const outputs::Image8& candidate, const std::vector<std::size_t>& wrong) {
        const outputs::CandidateDeclaration& d = declared.for_light(light);
        if (!tolerance::zigzags_apply(prepared, light, technique, d)) return std::vector<std::size_t>{};
        return tolerance::find_zigzags(*model, prepared, light, d, reference, candidate, wrong).impossible;
      };
      o.impossible = &explainers.impossible;
      causes += "; a directional light's shadow edges that zigzag faster than any texel grid allows (unexplained)";
    }
  }
  if (technique && technique->family == outputs::TechniqueFamily::SoftShadow) {
    explainers.visibility = [model, &declared](std::size_t light, int x, int y) {
      const reference::CauseModel::Band b = model->visibility_band(light, x, y, declared.for_light(light));
      return std::make_pair(b.lo, b.hi);
    };
    o.explain_visibility = &explainers.visibility;
    explainers.texel_shift = [model, &declared](std::size_t light, int x, int y) {
      return model->visibility_texel_shift(light, x, y, declared.for_light(light));
    };
    o.visibility_texel_shift = &explainers.texel_shift;
    for (std::size_t i = 0; i < s.lights.size(); ++i) {
      const scene::Light& l = s.lights[i];
      const outputs::CandidateDeclaration& d = declared.for_light(i);
      const bool area = l.type == scene::LightType::Rect;
      o.visibility.push_back(area ? compare::visibility_bounds(l.samples, d.light_taps, d.sampling)
                                  : compare::VisibilityBounds{});
    }
    causes += "; the lit fraction of every area light, within its sampling and the filter's footprint";
  }
  return o;
}

// `declared` with the map size of every light whose staircases contradict it (staircases.hpp)
// taken back to the automatic size; `said` gets each checked light's finding. `masks` are the
// candidate's, read with the reference's (compare::read_folder_images).
outputs::CandidateDeclaration checked_against_staircases(const reference::CauseModel& model, const scene::Scene& s,
                                                         const std::vector<outputs::Image8>& masks,
                                                         const outputs::CandidateDeclaration& declared, std::string& said) {
  outputs::CandidateDeclaration judged = declared;
  for (std::size_t i = 0; i < s.lights.size() && i < masks.size(); ++i) {
    const outputs::CandidateDeclaration& d = declared.for_light(i);
    if (!tolerance::staircases_apply(d)) continue;
    const tolerance::StaircaseCheck check = tolerance::check_staircases(model, masks[i], i, d);
    said += (said.empty() ? "" : "; ") + tolerance::describe(check, i, d);
    if (!check.contradicted) continue;
    if (judged.lights.size() <= i) {  // the lights without an entry take the top level's declaration
      outputs::CandidateDeclaration top = declared;
      top.lights.clear();
      judged.lights.resize(s.lights.size(), top);
    }
    if (judged.lights[i].light_views == outputs::LightViews::Declared) {
      // Declared matrices that the staircases contradict are not the grid the map was drawn on: the
      // light is judged as the candidate's own views (turn and phase unknown) at the declared size,
      // which is all an engine declaring "own" gives.
      judged.lights[i].light_views = outputs::LightViews::Own;
      judged.lights[i].views.clear();
      judged.lights[i].cascade_splits.clear();
      continue;
    }
    judged.lights[i].shadow_map_size = 0;
    judged.lights[i].atlas_tile_size = judged.lights[i].atlas_guard_band = 0;
  }
  return judged;
}

// What is wrong with light `light`'s declared views for this scene and run (empty: nothing, or
// the light's views are not declared): the count a light of its kind needs, the map size, the run's
// convention in which the matrices are read.
std::string declared_views_problem(const scene::PreparedScene& prepared, std::size_t light,
                                   const outputs::CandidateDeclaration& top, const std::string& technique_name) {
  const outputs::TechniqueName* technique = outputs::find_technique_name(technique_name);
  const outputs::CandidateDeclaration& d = top.for_light(light);
  if (d.light_views != outputs::LightViews::Declared) return "";
  const std::string at = light < top.lights.size() ? "lights[" + std::to_string(light) + "]." : "";
  if (top.convention != prepared.convention->name)
    return "convention: declared light matrices are read in the run's convention '" + std::string(prepared.convention->name) +
           "', and this candidate declares '" + top.convention + "' (run conform with --convention " + top.convention + ")";
  if (d.views.empty()) return at + "views: light_views \"declared\" needs this light's views (its view and projection matrices)";
  if (d.shadow_map_size <= 0) return at + "shadow_map_size: declared views need the map size they are drawn at";
  const bool positional = prepared.lights[light].w() != 0;
  const std::size_t n = d.views.size();
  if (positional && n != 1 && n != 6)
    return at + "views: a point or spot light has 1 view or a cube's 6 (+x, -x, +y, -y, +z, -z), not " + std::to_string(n);
  if (positional && !d.cascade_splits.empty()) return at + "cascade_splits: only a directional light's cascades have splits";
  const bool cascaded = technique && technique->cascaded;
  if (!positional && n > 1 && !cascaded)
    return at + "views: " + std::to_string(n) + " views for a directional light, but technique '" + technique_name +
           "' is not cascaded (one view)";
  if (!positional && (n > 1 || !d.cascade_splits.empty()) && d.cascade_splits.size() != n + 1)
    return at + "cascade_splits: " + std::to_string(n) + " cascades need " + std::to_string(n + 1) +
           " camera depths (where each begins and the last ends), got " + std::to_string(d.cascade_splits.size());
  return "";
}

// 1. The technique judged (the caller's, else the candidate's, else none: the strictest) and what
// the candidate declares.
void read_what_is_judged(const CaseToJudge& c, CaseJudgement& j) {
  j.technique = c.technique;
  j.technique_source = "the caller";
  j.declaration = outputs::read_declaration(c.candidate_dir, c.technique);
  if (j.technique.empty()) {
    j.technique = j.declaration.technique;
    j.technique_source = j.technique.empty() ? "none given: the strictest" : "candidate.json";
  }
}

// A declaration the scene cannot bear (more lights than it has, views it refuses) is bad input,
// named by the candidate's file; then the catalogue's expectation for the technique.
void check_declaration_against_scene(const scene::PreparedScene& prepared, const CaseToJudge& c, CaseJudgement& j) {
  const scene::Scene& s = *prepared.scene;
  if (j.declaration.lights.size() > s.lights.size())
    throw outputs::InputError(outputs::InputError::Kind::BadInput,
                              (c.candidate_dir / outputs::kCandidateFile).string() + ": lights: " +
                                  std::to_string(j.declaration.lights.size()) + " entries, but scene '" + s.name + "' has " +
                                  std::to_string(s.lights.size()) + " light(s)");
  for (std::size_t i = 0; i < s.lights.size(); ++i)
    if (const std::string p = declared_views_problem(prepared, i, j.declaration, j.technique); !p.empty())
      throw outputs::InputError(outputs::InputError::Kind::BadInput, (c.candidate_dir / outputs::kCandidateFile).string() + ": " + p);
  if (const auto e = s.expect.find(j.technique); e != s.expect.end()) j.expectation = e->second;
}

// What the cause model's answers depend on (the memo's key, and with the reference and threshold
// the probes' verdicts'): not the producer or version, nor the technique's name (the volume
// techniques and planar share one answer per scene, shadowmap and shadowmap-rgba8 another) but
// for what the cause model reads of it: whether it is cascaded, its "cascades": 0 then meaning
// the default count (csm-pcf's declaration text is shadowmap-pcf's otherwise, and a point is
// looked up in its cascade, not in one map).
std::string cause_key_of(const outputs::CandidateDeclaration& judged) {
  const auto cause_relevant = [](const std::string& technique) {
    const outputs::TechniqueName* t = outputs::find_technique_name(technique);
    return t && t->cascaded ? std::string("cascaded") : std::string();
  };
  outputs::CandidateDeclaration keyed = judged;
  keyed.producer = keyed.version = "";
  keyed.technique = cause_relevant(keyed.technique);
  for (outputs::CandidateDeclaration& l : keyed.lights) l.technique = cause_relevant(l.technique);
  return outputs::declaration_text(keyed);
}

// 6. The status under the expectation, the unmet expectation and, for an expected failure that
// predicts its errors' kind, whether the other kind passes. Returns whether the status is still an
// XFAIL that the technique's own model may grant.
bool settle_status(CaseJudgement& j, int height) {
  j.status = status_of(j.comparison.decision.verdict, j.expectation.pass);
  // Below the image height an expected failure shows from, its errors may lie within the bounds.
  if (j.status == Status::XPass && j.comparison.decision.verdict == compare::Verdict::Pass && j.expectation.passes_at(height))
    j.status = Status::Pass;
  j.unmet_expectation = unmet_expectation(j.expectation, j.status);
  if (j.status != Status::XFail) return false;
  if (j.expectation.errors != scene::PredictedErrors::Any) {
    // An expected failure that predicts its errors' kind: granted only when the other kind passes.
    std::string seen;
    const std::string problem = unpredicted_errors(j.comparison, j.expectation.errors, seen);
    if (!problem.empty()) {
      j.status = Status::Fail;
      j.signature = "expected failure seen, but errors of the kind it does not predict fail on their own: " + problem;
      return false;
    }
    j.signature = "the errors are of the predicted kind: " + seen;
  }
  return true;
}

}  // namespace

Judge::Judge(bool probe) : memo_(std::make_unique<CauseMemo>()), probe_(probe) {}
Judge::~Judge() = default;

reference::CauseModel& Judge::causes_of(const scene::PreparedScene& prepared) {
  std::unique_ptr<reference::CauseModel>& m = causes_[&prepared];
  if (!m) m = std::make_unique<reference::CauseModel>(prepared);
  return *m;
}

std::filesystem::path Judge::draw_model(const scene::PreparedScene& prepared, const std::string& technique,
                                        const std::filesystem::path& reference_dir, const std::filesystem::path& dir) {
  if (!model_gl_) model_gl_ = std::make_unique<renderer::Renderer>(renderer::GlApi::OSMesa, renderer::Driver::Llvmpipe);
  const scene::Scene& s = *prepared.scene;
  renderer::write_outputs(model_gl_->render(prepared, technique), model_gl_->info(), s, dir);
  // The model is judged on the reference's decided pixels, with the same causes.
  for (std::size_t l = 0; l < s.lights.size(); ++l) {
    const std::string d = outputs::decided_name(l, s.lights.size());
    outputs::copy_file_atomically(reference_dir / d, dir / d);
  }
  return dir;
}

CaseJudgement Judge::judge(const scene::PreparedScene* prepared, const CaseToJudge& c) {
  CaseJudgement j;
  // 1. The technique judged and what the candidate declares.
  read_what_is_judged(c, j);
  const outputs::TechniqueName* named = outputs::find_technique_name(j.technique);
  const bool soft = named && named->family == outputs::TechniqueFamily::SoftShadow;
  const compare::Threshold& threshold = compare::threshold_for(j.technique);
  if (!prepared) {
    if (soft)
      throw outputs::InputError(outputs::InputError::Kind::BadInput,
                                "technique '" + j.technique + "' (from " + j.technique_source +
                                    "): a soft technique's lit fraction is judged against the scene's lights: give the scene");
    j.causes = "none (the scene is not known: every wrong pixel is unexplained)";
    j.comparison = compare::compare_folders(c.reference_dir, c.candidate_dir, threshold);
    j.status = status_of(j.comparison.decision.verdict, true);
    return j;
  }
  const scene::Scene& s = *prepared->scene;
  check_declaration_against_scene(*prepared, c, j);

  // 2-4. Threshold, causes, lit fraction: the comparison, under the declaration as the pixels bear it
  // out. The masks are read once here, for the staircases, the comparison, the probes and the model.
  compare::FolderImages images = compare::read_folder_images(c.reference_dir, c.candidate_dir);
  reference::CauseModel* model = threshold.bands || soft ? &causes_of(*prepared) : nullptr;
  std::string staircases;
  const outputs::CandidateDeclaration judged =
      model && named && named->family == outputs::TechniqueFamily::ShadowMap
          ? checked_against_staircases(*model, s, images.candidate, j.declaration, staircases)
          : j.declaration;
  const std::string cause_key = cause_key_of(judged);
  CauseMemo::Table* memo = model ? &memo_->table(*prepared, cause_key) : nullptr;
  Explainers explainers;
  const compare::CompareOptions options = options_for(*prepared, threshold, named, judged, model, memo, explainers, j.causes);
  if (!staircases.empty()) j.causes += "; " + staircases;
  compare::add_fractions(images, c.reference_dir, c.candidate_dir, options);
  j.comparison = compare::compare_images(images, threshold, options);

  // 5. What the verdict could have seen, once per reference, threshold and declaration as judged.
  if (probe_) {
    const std::string key = c.reference_dir.string() + '\n' + std::string(threshold.name) + '\n' + cause_key;
    auto known = resolving_.find(key);
    if (known == resolving_.end()) known = resolving_.emplace(key, tolerance::resolving_power(images.reference, images.decided, threshold, options)).first;
    j.resolving_power = known->second;
  }

  // 6. Status and signature.
  if (!settle_status(j, s.height)) return j;
  // An engine's expected failure is granted only when its errors are the ones the technique's own
  // model of its failure predicts: our implementation, which shows the limitation exactly. The
  // candidate is judged against the model's masks (on the reference's decided pixels, with the
  // same causes); what is left is wrong elsewhere.
  if (c.candidate_is_ours || !named || c.model_dir.empty()) return j;
  const auto start = std::chrono::steady_clock::now();
  const std::filesystem::path model_dir = draw_model(*prepared, j.technique, c.reference_dir, c.model_dir);
  // The model is the technique's masks: a soft technique's lit fraction has no model of its
  // failure here (our render's fraction is no ground truth to measure an engine's against).
  compare::CompareOptions model_options = options;
  model_options.visibility.clear();
  // Against the model's masks, on the reference's decided pixels (draw_model copies them beside the
  // model's masks for a person to look at): the candidate as read above.
  compare::FolderImages against = images;
  against.fractions.assign(against.masks.size(), std::nullopt);
  for (std::size_t i = 0; i < against.masks.size(); ++i)
    against.reference[i] = outputs::read_image8(model_dir / against.masks[i], 1, against.candidate[i].width, against.candidate[i].height);
  const compare::FolderComparison against_model = compare::compare_images(against, threshold, model_options);
  j.model_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const std::string ours = " (our " + j.technique + ")";
  if (against_model.decision.verdict == compare::Verdict::Fail) {
    j.status = Status::Fail;
    j.signature = "expected failure seen, but also wrong elsewhere: " + std::to_string(against_model.total.unexplained) +
                  " px unexplained against the technique's own model of its failure" + ours;
  } else {
    j.signature += std::string(j.signature.empty() ? "" : "; ") +
                   "the errors are the ones the technique's own model of its failure predicts" + ours;
  }
  return j;
}

}  // namespace shadowref::conform
