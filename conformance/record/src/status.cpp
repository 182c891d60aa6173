// status.cpp — the names of a case's status and outcome (status.hpp).
#include "shadowref/record/status.hpp"

namespace shadowref::record {

const char* to_string(Status s) {
  switch (s) {
    case Status::Pass: return "PASS";
    case Status::Warn: return "WARN";
    case Status::Fail: return "FAIL";
    case Status::XFail: return "XFAIL";
    case Status::XPass: return "XPASS";
    case Status::Error: return "ERROR";
  }
  return "?";
}

std::optional<Status> status_from_string(std::string_view name) {
  for (Status s : kStatuses)
    if (name == to_string(s)) return s;
  return std::nullopt;
}

bool is_failure(Status s) { return s == Status::Fail || s == Status::XPass || s == Status::Error; }

const char* to_string(Outcome o) {
  switch (o) {
    case Outcome::Green: return "green";
    case Outcome::Expected: return "expected";
    case Outcome::NewFailure: return "new-failure";
    case Outcome::NewWarning: return "new-warning";
    case Outcome::Improvement: return "improvement";
    case Outcome::Flake: return "flake";
  }
  return "?";
}

std::optional<Outcome> outcome_from_string(std::string_view name) {
  for (Outcome o : kOutcomes)
    if (name == to_string(o)) return o;
  return std::nullopt;
}

}  // namespace shadowref::record
