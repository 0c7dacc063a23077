// Strict OBJ reader, the words and numbers of a line (see obj_reader.hpp).
#include "obj_reader.hpp"

#include <charconv>
#include <cmath>
#include <limits>

namespace twister::meshio::internal {

bool blank(char c) { return c == ' ' || c == '\t'; }

bool Words::next(std::string_view& word) {
  std::size_t i = 0;
  while (i < rest_.size() && blank(rest_[i])) ++i;
  rest_.remove_prefix(i);
  if (rest_.empty() || rest_.front() == '#') return false;  // the end, or a comment
  std::size_t n = 0;
  while (n < rest_.size() && !blank(rest_[n])) ++n;
  word = rest_.substr(0, n);
  rest_.remove_prefix(n);
  return true;
}

bool parse_number(std::string_view word, float& out) {
  if (word.size() > 1 && word.front() == '+' && word[1] != '-' && word[1] != '+') {
    word.remove_prefix(1);
  }
  if (word.empty()) return false;
  const auto [end, ec] = std::from_chars(word.data(), word.data() + word.size(), out);
  return ec == std::errc() && end == word.data() + word.size() && std::isfinite(out);
}

Kind kind_of(std::string_view keyword) {
  if (keyword == "v") return Kind::vertex;
  if (keyword == "vt") return Kind::texture;
  if (keyword == "vn") return Kind::normal;
  if (keyword == "vp") return Kind::param;
  if (keyword == "f") return Kind::face;
  if (keyword == "o" || keyword == "g" || keyword == "s" || keyword == "usemtl" ||
      keyword == "mtllib") {
    return Kind::ignored;
  }
  return Kind::skipped;
}

hal::Error ObjReader::error() const {
  if (!lines_.error().empty()) return hal::make_error(StatusCode::invalid_argument, lines_.error());
  return hal::make_error(StatusCode::invalid_argument,
                         "line " + std::to_string(lines_.line_number()) + ": " + problem_);
}

bool ObjReader::check_numbers(Words& words, std::string_view keyword, float* xyz) {
  std::string_view word;
  std::size_t count = 0;
  while (words.next(word)) {
    float value = 0.0f;
    if (!parse_number(word, value)) {
      problem_ = std::string(keyword) + " value '" + std::string(word.substr(0, 40)) +
                 "' is not a finite number";
      return false;
    }
    if (xyz != nullptr && count < 3) xyz[count] = value;
    if (++count > 7) break;
  }
  const bool vertex = keyword == "v";
  const bool ok =
      vertex ? (count == 3 || count == 4 || count == 6 || count == 7) : (count >= 1 && count <= 3);
  if (!ok) {
    problem_ = vertex ? "a vertex needs x y z (and optionally w, or r g b)"
                      : std::string(keyword) + " needs 1 to 3 numbers";
  }
  return ok;
}

bool ObjReader::element(std::string_view text, std::int64_t defined, std::int64_t total,
                        const char* what, std::int64_t& index) {
  std::int64_t value = 0;
  const char* first = text.data();
  const char* last = text.data() + text.size();
  const auto [end, ec] = std::from_chars(first, last, value);
  if (text.empty() || (ec != std::errc() && ec != std::errc::result_out_of_range) || end != last) {
    problem_ = std::string(what) + " index '" + std::string(text.substr(0, 40)) +
               "' is not a whole number";
    return false;
  }
  constexpr std::int64_t kMax = std::numeric_limits<std::uint32_t>::max();
  if (ec == std::errc::result_out_of_range || value == 0 || value > kMax || value < -kMax) {
    problem_ =
        std::string(what) + " index " + std::string(text.substr(0, 40)) +
        (value == 0 && ec == std::errc() ? " is 0 (indices start at 1)" : " is beyond 32 bits");
    return false;
  }
  // Relative indices count back from the elements defined so far; absolute ones may
  // name any element of the file.
  const std::int64_t limit = value > 0 ? total : defined;
  index = value > 0 ? value - 1 : defined + value;
  if (index < 0 || index >= limit) {
    problem_ = std::string(what) + " index " + std::string(text) + " refers to a " + what +
               " that does not exist (there are " + std::to_string(limit) + ")";
    return false;
  }
  return true;
}

bool ObjReader::reference(std::string_view word, std::uint32_t& vertex) {
  constexpr auto kNpos = std::string_view::npos;
  const std::size_t s1 = word.find('/');
  const std::size_t s2 = s1 == kNpos ? kNpos : word.find('/', s1 + 1);
  // Before the count is known, positive indices are checked against the whole file
  // in the next pass.
  const std::int64_t any = std::numeric_limits<std::int64_t>::max();
  std::int64_t index = 0;
  if (!element(word.substr(0, s1), defined_.v, counted_ ? total_.v : any, "vertex", index)) {
    return false;
  }
  vertex = static_cast<std::uint32_t>(index);
  if (s1 == kNpos) return true;
  const std::string_view vt = word.substr(s1 + 1, s2 == kNpos ? kNpos : s2 - s1 - 1);
  const std::string_view vn = s2 == kNpos ? std::string_view{} : word.substr(s2 + 1);
  if ((s2 == kNpos && vt.empty()) || (s2 != kNpos && vn.empty())) {
    problem_ = "face reference '" + std::string(word.substr(0, 40)) + "' is incomplete";
    return false;
  }
  std::int64_t ignored = 0;
  if (!vt.empty() && !element(vt, defined_.vt, counted_ ? total_.vt : any, "texture", ignored)) {
    return false;
  }
  return vn.empty() || element(vn, defined_.vn, counted_ ? total_.vn : any, "normal", ignored);
}

}  // namespace twister::meshio::internal
