// Small helpers shared by the structure scans of the text mesh formats: lines, tokens, numbers
// and printable quotes of untrusted text for one-line messages.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace posekit::detail {

/// True for the blanks that separate tokens on a line: space, tab, CR, VT, FF ('\n' ends lines).
constexpr bool is_blank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

/// True for a blank or '\n'.
constexpr bool is_space(char c) { return is_blank(c) || c == '\n'; }

/// True when `text` holds nothing but blanks and line ends.
bool is_all_space(std::string_view text);

/// Walks a text line by line; lines are views into the text without their '\n'.
class LineReader {
 public:
  explicit LineReader(std::string_view text) : text_(text) {}
  /// Moves to the next line; false at the end of the text.
  bool next(std::string_view& line);
  /// 1-based number of the line last returned by next().
  long line_number() const { return line_number_; }
  /// Offset of the first byte after the line last returned (after its '\n').
  std::size_t offset() const { return position_; }
  /// True when the line last returned is the last one and has no '\n': the text may be cut short.
  bool at_unterminated_line() const { return unterminated_; }

 private:
  std::string_view text_;
  std::size_t position_ = 0;
  long line_number_ = 0;
  bool unterminated_ = false;
};

/// Splits `line` at blanks into `tokens` (views into `line`); `tokens` is cleared first.
void split_tokens(std::string_view line, std::vector<std::string_view>& tokens);

/// The part of `line` before the first '#'.
std::string_view strip_comment(std::string_view line);

/// How a token reads as a number.
enum class NumberStatus {
  ok,            ///< the whole token is a number of the requested kind
  not_a_number,  ///< not a number, or trailing characters after it
  non_finite,    ///< nan or infinity, or beyond the range of the floating-point type
  out_of_range,  ///< an integer too large for 64 bits
};

/// Reads the whole token as a double (a leading '+' is accepted, as iostreams do).
NumberStatus parse_double(std::string_view token, double& value);
/// Reads the whole token as a float.
NumberStatus parse_float(std::string_view token, float& value);
/// Reads the whole token as a decimal integer (a leading '+' is accepted).
NumberStatus parse_integer(std::string_view token, long long& value);

/// `text` in single quotes, cut to 24 characters, with control and non-ASCII bytes written as \xNN,
/// so that untrusted file content keeps an error message on one printable line.
std::string quote(std::string_view text);

/// "1 vertex", "3 vertices": `count` followed by the singular or plural noun.
std::string count_of(long long count, const char* singular, const char* plural);

/// `message` with every line break replaced by a space (messages of posekit are one line).
std::string one_line(std::string message);

}  // namespace posekit::detail
