// shadowref/record/case_record.hpp — a case of report.json as one typed record: the names of its
// keys (written nowhere else), the record every reader gets back, and the writer of its keys.
//
// report.json (docs/output-contract.md) holds "cases", one object per scene × technique. The record
// types what the readers of a run act on — who the case is, its status and why, its outcome
// against the expectations files, its resolving power, where its candidate was rendered, and the
// comparison's counts and lit fraction the page shows (comparison_record.hpp; written whole by
// report/comparison_json.cpp). A text or number key added to a case is added here (the key, the
// field and its row in kTextKeys or kNumberKeys), where its value is made, and in the schema
// (docs/architecture.md, "Where a case key goes").
#pragma once

#include <cstddef>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "shadowref/outputs/candidate.hpp"
#include "shadowref/record/comparison_record.hpp"
#include "shadowref/record/status.hpp"

namespace shadowref::record {

// The keys of a case, and of the objects the record types inside it.
namespace key {
inline constexpr char kCases[] = "cases";  // the report's array of cases
inline constexpr char kScene[] = "scene";
inline constexpr char kSceneFile[] = "scene_file";
inline constexpr char kTechnique[] = "technique";
inline constexpr char kStatus[] = "status";
inline constexpr char kExpected[] = "expected";  // the catalogue's "pass", "warn" or "fail"
inline constexpr char kWhy[] = "why";
inline constexpr char kExpectedFromHeight[] = "expected_from_height";
inline constexpr char kSignature[] = "signature";
inline constexpr char kReferenceDir[] = "reference_dir";
inline constexpr char kCandidateDir[] = "candidate_dir";
inline constexpr char kFrameMs[] = "frame_ms";
inline constexpr char kSeconds[] = "seconds";
inline constexpr char kNotes[] = "notes";
inline constexpr char kCauses[] = "causes";
inline constexpr char kResolvingPower[] = "resolving_power";
inline constexpr char kHost[] = "host";
inline constexpr char kShard[] = "shard";
inline constexpr char kExpectation[] = "expectation";
inline constexpr char kUnmetExpectation[] = "unmet_expectation";
inline constexpr char kError[] = "error";
inline constexpr char kReadThroughLinks[] = "read_through_links";
inline constexpr char kCandidate[] = "candidate";
inline constexpr char kDefaulted[] = "defaulted";  // inside "candidate": the keys the candidate left out
inline constexpr char kComparison[] = "comparison";
inline constexpr char kLights[] = "lights";
inline constexpr char kShaded[] = "shaded";
inline constexpr char kReferenceShaded[] = "reference_shaded";
// `compare --json` only: where the technique came from, the error images --out holds, the exit code.
inline constexpr char kTechniqueSource[] = "technique_source";
inline constexpr char kErrorImages[] = "error_images";
inline constexpr char kExitCode[] = "exit_code";
// Inside "expectation".
inline constexpr char kOutcome[] = "outcome";
inline constexpr char kLine[] = "line";  // also a stale line's place, "fails.txt:3"
inline constexpr char kCaseName[] = "case";  // `compare --json` only: the case's name in the files
// Inside "resolving_power".
inline constexpr char kSummary[] = "summary";
inline constexpr char kBlindTo[] = "blind_to";
inline constexpr char kUnseen[] = "unseen";
inline constexpr char kProbes[] = "probes";
// Inside "comparison" and "candidate".
inline constexpr char kReasons[] = "reasons";
inline constexpr char kEnvironment[] = "environment";
inline constexpr char kTotal[] = "total";  // "comparison"."total": every light's counts summed
inline constexpr char kWrong[] = "wrong";
inline constexpr char kUnexplained[] = "unexplained";
// Inside each of "lights": the mask's name and the page's copies of its images (under report/).
inline constexpr char kMask[] = "mask";
inline constexpr char kReference[] = "reference";
inline constexpr char kDecided[] = "decided";
inline constexpr char kErrorImage[] = "error";
inline constexpr char kCandidateVisibility[] = "candidate_visibility";  // soft shadows: the lit fractions
inline constexpr char kVisibilityError[] = "visibility_error";
}  // namespace key

// A case's place in the expectations files (present when the run was given any).
struct ExpectationRecord {
  Outcome outcome = Outcome::Green;
  std::string status;  // the status a line gives the case ("FAIL"); "" when no line names it
  std::string line;    // that line's place, "fails.txt:3"; "" when none
  // "FAIL at fails.txt:3", "green" when no line names the case.
  std::string expected_by() const;
};

// What the probes of the reference's own masks showed (tolerance/resolving_power.hpp writes it).
struct ResolvingPowerRecord {
  std::string summary;                      // "resolves 1-px shifts, ..." or "blind to ..."
  std::vector<std::string> blind_to, unseen;  // the probe kinds' names
};

// One light of a judged case as the page shows it: its mask's name (a plain file name, as
// outputs/file_names.hpp gives) and the report folder's copies of its images, each a path relative to
// report/ that stays in it ("" when there is none: a case that ended before its image was written).
struct LightRecord {
  std::string mask;
  std::string reference, decided, candidate, error;
  std::string candidate_visibility, visibility_error;  // soft shadows' lit fractions ("" none)
  std::optional<MaskMetricsRecord> metrics;        // the light's counts ("metrics")
  std::optional<VisibilityRecord> visibility;      // a soft technique's lit fraction of the light
};

struct CaseRecord {
  std::string scene, technique;
  Status status = Status::Pass;
  std::string expected = "pass";   // the catalogue's expectation: "pass", "warn" or "fail"
  std::string why;                 // why the catalogue expects a failure; "" when it expects none
  int expected_from_height = 0;    // the failure is expected from this image height (0: at every height)
  std::string signature;           // the expected failure's errors as seen ("" none)
  std::string error;               // why an ERROR case could not be judged ("" none)
  std::string unmet_expectation;   // a catalogue expectation the verdict did not meet ("" none)
  std::string causes;              // the causes the judge weighed
  std::optional<std::string> host; // the machine that judged the case
  std::optional<int> shard;        // its shard, in a sharded run (1-based)
  double seconds = 0;              // wall time of the case
  double frame_ms = 0;             // our renderer's frame time (0: not drawn by us, or not timed)
  std::vector<std::string> notes;  // what the run noted of the case (a cache miss, a read-through link)
  std::vector<std::string> reasons;  // the verdict's reasons ("comparison"."reasons")
  // "comparison"."total": every light's counts; absent before a verdict. Its `wrong` and
  // `unexplained`, the counts two runs are compared by, are always there.
  std::optional<MaskMetricsRecord> total;
  std::optional<VisibilityRecord> visibility;    // "comparison"."visibility": the lights' lit fraction together
  std::string threshold;                         // the threshold's name ("comparison"."threshold"."name"; "" none)
  std::vector<LightRecord> lights;     // empty before a verdict
  std::string shaded, reference_shaded;  // the page's shaded views, under report/ ("" none)
  std::optional<ExpectationRecord> expectation;
  std::optional<ResolvingPowerRecord> resolving_power;
  outputs::Environment environment;  // where the candidate was rendered (empty: none declared);
                                     // outputs::environment_text says it in one line
  // The candidate's declaration ("candidate", read back by outputs::declaration_from_json; its
  // `defaulted` the keys the candidate left out, as the case recorded them); absent when the case
  // has none.
  std::optional<outputs::CandidateDeclaration> candidate;
};

// When write_case writes a key of the tables below: always, only when it is set (a text not empty,
// a number not 0), or never (the run writes it: `compare --json` has no value for it).
enum class Written { Always, WhenSet, ByTheRun };

// The case's plain keys, one row each. read_case reads each into its field (an absent or null key
// leaves the field's default above; a text must be a string, a number one >= 0) and write_case
// writes each back as `written` says, so that a key of this kind is a constant, a field and a row,
// all in this header. `CaseRecord.EveryPlainKeyIsInTheSchema` holds the rows to report.schema.json.
struct TextKey {
  const char* name;
  std::string CaseRecord::*field;
  Written written;
};
inline constexpr TextKey kTextKeys[] = {
    {key::kExpected, &CaseRecord::expected, Written::Always},
    {key::kWhy, &CaseRecord::why, Written::Always},
    {key::kSignature, &CaseRecord::signature, Written::WhenSet},
    {key::kError, &CaseRecord::error, Written::WhenSet},
    {key::kUnmetExpectation, &CaseRecord::unmet_expectation, Written::WhenSet},
    {key::kCauses, &CaseRecord::causes, Written::Always},
};
struct NumberKey {
  const char* name;
  double CaseRecord::*field;
  Written written;
};
inline constexpr NumberKey kNumberKeys[] = {
    {key::kSeconds, &CaseRecord::seconds, Written::Always},
    {key::kFrameMs, &CaseRecord::frame_ms, Written::ByTheRun},
};

// A case or report whose JSON is not the shape above: one line naming the JSON path
// ("cases[3].status: \"MAYBE\" is not a status (PASS, WARN, FAIL, XFAIL, XPASS, ERROR)").
class RecordError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

// The record of case `c`, the `index`-th of its report (for the path in a RecordError). "scene",
// "technique" and "status" must be there; every other key may be absent (its default above), but a
// key that is there must have its type ("seconds" a number >= 0, a count a whole number, an image
// path one that stays in report/). Cost: one pass over the case's keys and its lights.
CaseRecord read_case(const nlohmann::json& c, std::size_t index);

// Whether `rel`, an image path of a case, is relative and has no ".." part (it stays in report/):
// a report.json from elsewhere (a CI artefact) must not make a reader open files beside it.
bool inside_report_folder(const std::string& rel);

// Every case of `report` (an object whose "cases" is an array; none when it has no "cases").
std::vector<CaseRecord> read_cases(const nlohmann::json& report);

// The keys of `r` written into `k` as read_case reads them back: absent optionals are not written,
// the tables' keys as their rows say. Some fields are not written from here: `frame_ms` and `notes`
// are the run's, which `compare --json` has not (the
// run writes them); `candidate` and its `environment` are written whole from the candidate's
// declaration (outputs::declaration_text); the resolving power carries its probes besides
// (resolving_power_json); the totals, counts, threshold and reasons lie in "comparison" and the
// lights carry their counts, each written whole by the comparison's writer
// (report/comparison_json.hpp) and the report's, which copies the images.
void write_case(const CaseRecord& r, nlohmann::json& k);

}  // namespace shadowref::record
