// numbers.cpp — strict numeric parsing and round-trip formatting for the command line.
#include "numbers.hpp"

#include <charconv>
#include <cmath>
#include <string>

#include "command.hpp"

namespace shadowref::cli {

namespace {

std::string quoted(std::string_view s) { return "'" + std::string(s) + "'"; }

}  // namespace

double parse_number(std::string_view option, std::string_view text) {
  std::string_view t = text;
  if (!t.empty() && t.front() == '+') t.remove_prefix(1);  // from_chars refuses a leading '+'
  double value = 0.0;
  const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), value);
  if (t.empty() || ec == std::errc::invalid_argument || end != t.data() + t.size())
    throw BadInput(std::string(option) + " " + quoted(text) + ": not a number");
  if (ec == std::errc::result_out_of_range || !std::isfinite(value))
    throw BadInput(std::string(option) + " " + quoted(text) + ": not a finite number");
  return value;
}

Size2 parse_size(std::string_view option, std::string_view text, int max_side) {
  const auto bad = [&] {
    return BadInput(std::string(option) + " " + quoted(text) + ": expected WxH with both in [1, " + std::to_string(max_side) +
                    "], e.g. 1024x768");
  };
  const std::size_t x = text.find('x');
  if (x == std::string_view::npos) throw bad();
  const auto whole = [&](std::string_view t) {
    int v = 0;
    const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
    // from_chars takes a leading '-' for int: refused by the range check below.
    if (t.empty() || ec != std::errc() || end != t.data() + t.size() || v < 1 || v > max_side) throw bad();
    return v;
  };
  return {whole(text.substr(0, x)), whole(text.substr(x + 1))};
}

std::vector<double> parse_numbers(std::string_view option, std::string_view text, std::size_t count) {
  std::vector<std::string_view> fields;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = text.find(',', start);
    fields.push_back(text.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start));
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  if (fields.size() != count)
    throw BadInput(std::string(option) + " " + quoted(text) + ": expected " + std::to_string(count) +
                   " comma-separated numbers, got " + std::to_string(fields.size()));
  std::vector<double> values;
  values.reserve(count);
  for (std::size_t i = 0; i < fields.size(); ++i) {
    try {
      values.push_back(parse_number(option, fields[i]));
    } catch (const BadInput&) {
      throw BadInput(std::string(option) + " " + quoted(text) + ": value " + std::to_string(i + 1) + " " +
                     quoted(fields[i]) + " is not a finite number");
    }
  }
  return values;
}

std::string format_number(double value) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, value);
  return std::string(buf, r.ptr);
}

std::string format_number(float value) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, value);
  return std::string(buf, r.ptr);
}

}  // namespace shadowref::cli
