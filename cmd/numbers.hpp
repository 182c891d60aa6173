// numbers.hpp — strict parsing of numeric command-line values ("1.5", "a,b,c,d").
//
// Strict means: the whole text is a finite decimal number (no trailing garbage, no NaN or
// infinity, no empty fields). Errors throw BadInput naming the option, e.g.
//   --plane '0,1,x,0': value 3 'x' is not a number
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace shadowref::cli {

// One finite number from `text`, for option `option`.
double parse_number(std::string_view option, std::string_view text);

// Exactly `count` comma-separated finite numbers.
std::vector<double> parse_numbers(std::string_view option, std::string_view text, std::size_t count);

// "WxH": two whole numbers in [1, max_side] joined by 'x' (e.g. "1024x768"), nothing else: no
// sign, no spaces, no leading or trailing text. Returns {W, H}.
struct Size2 {
  int width, height;
};
Size2 parse_size(std::string_view option, std::string_view text, int max_side);

// A number as the shortest text that reads back to the same value (std::to_chars).
std::string format_number(double value);
std::string format_number(float value);

}  // namespace shadowref::cli
