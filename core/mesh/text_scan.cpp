#include "mesh/text_scan.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <string>
#include <system_error>

namespace posekit::detail {

bool is_all_space(std::string_view text) { return std::all_of(text.begin(), text.end(), is_space); }

bool LineReader::next(std::string_view& line) {
  if (position_ >= text_.size()) return false;
  const std::size_t end = text_.find('\n', position_);
  ++line_number_;
  if (end == std::string_view::npos) {
    line = text_.substr(position_);
    position_ = text_.size();
    unterminated_ = true;
  } else {
    line = text_.substr(position_, end - position_);
    position_ = end + 1;
  }
  return true;
}

void split_tokens(std::string_view line, std::vector<std::string_view>& tokens) {
  tokens.clear();
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && is_blank(line[i])) ++i;
    const std::size_t begin = i;
    while (i < line.size() && !is_blank(line[i])) ++i;
    if (i > begin) tokens.push_back(line.substr(begin, i - begin));
  }
}

std::string_view strip_comment(std::string_view line) {
  const std::size_t hash = line.find('#');
  return hash == std::string_view::npos ? line : line.substr(0, hash);
}

namespace {

// std::from_chars rejects a leading '+', which iostreams (and so CGAL) accept.
std::string_view without_plus(std::string_view token) {
  if (token.size() > 1 && token.front() == '+' && token[1] != '-' && token[1] != '+') {
    return token.substr(1);
  }
  return token;
}

template <typename Real>
NumberStatus parse_real(std::string_view token, Real& value) {
  token = without_plus(token);
  if (token.empty()) return NumberStatus::not_a_number;
  const char* const end = token.data() + token.size();
  const auto result = std::from_chars(token.data(), end, value);
  if (result.ptr != end) return NumberStatus::not_a_number;
  if (result.ec == std::errc::result_out_of_range) {
    // from_chars also reports underflow to zero as out of range; iostreams accept it, so only a
    // value that overflows is refused.
    const std::string copy(token);
    const double rounded = std::strtod(copy.c_str(), nullptr);
    if (std::isfinite(rounded) && std::abs(rounded) <= static_cast<double>(std::numeric_limits<Real>::max())) {
      value = static_cast<Real>(rounded);
      return NumberStatus::ok;
    }
    return NumberStatus::non_finite;
  }
  if (result.ec != std::errc()) return NumberStatus::not_a_number;
  return std::isfinite(value) ? NumberStatus::ok : NumberStatus::non_finite;
}

}  // namespace

NumberStatus parse_double(std::string_view token, double& value) { return parse_real(token, value); }

NumberStatus parse_float(std::string_view token, float& value) { return parse_real(token, value); }

NumberStatus parse_integer(std::string_view token, long long& value) {
  token = without_plus(token);
  if (token.empty()) return NumberStatus::not_a_number;
  const char* const end = token.data() + token.size();
  const auto result = std::from_chars(token.data(), end, value);
  if (result.ptr != end) return NumberStatus::not_a_number;
  if (result.ec == std::errc::result_out_of_range) return NumberStatus::out_of_range;
  if (result.ec != std::errc()) return NumberStatus::not_a_number;
  return NumberStatus::ok;
}

std::string quote(std::string_view text) {
  constexpr std::size_t kMaxShown = 24;
  static const char* const kHex = "0123456789abcdef";
  std::string quoted = "'";
  for (std::size_t i = 0; i < text.size() && i < kMaxShown; ++i) {
    const auto byte = static_cast<unsigned char>(text[i]);
    if (byte >= 0x20 && byte < 0x7f) {
      quoted += static_cast<char>(byte);
    } else {
      quoted += "\\x";
      quoted += kHex[byte >> 4];
      quoted += kHex[byte & 0xf];
    }
  }
  if (text.size() > kMaxShown) quoted += "...";
  quoted += "'";
  return quoted;
}

std::string count_of(long long count, const char* singular, const char* plural) {
  return std::to_string(count) + " " + (count == 1 ? singular : plural);
}

std::string one_line(std::string message) {
  for (char& c : message) {
    if (c == '\n' || c == '\r') c = ' ';
  }
  return message;
}

}  // namespace posekit::detail
