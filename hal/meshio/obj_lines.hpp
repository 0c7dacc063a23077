// Line sources for the OBJ reader (private to hal/meshio): the lines of a text in
// memory, or of a file read through a fixed buffer (a file is never held whole).
// A line comes without its '\n' (and a '\r' before it); one longer than the buffer
// is an error. rewind() starts over (the reader makes several passes).
#pragma once

#include <cstddef>
#include <cstdio>
#include <string>
#include <string_view>
#include <vector>

namespace twister::meshio::internal {

class LineSource {
 public:
  virtual ~LineSource() = default;
  // The next line; false at the end or on an error (error() then says which).
  virtual bool next(std::string_view& line) = 0;
  virtual bool rewind() = 0;
  const std::string& error() const { return error_; }
  std::size_t line_number() const { return line_number_; }

 protected:
  static std::string_view trim_cr(std::string_view line) {
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    return line;
  }
  std::string error_;
  std::size_t line_number_ = 0;
};

class TextLines final : public LineSource {
 public:
  explicit TextLines(std::string_view text) : text_(text) {}
  bool next(std::string_view& line) override {
    if (pos_ >= text_.size()) return false;
    const std::size_t end = text_.find('\n', pos_);
    const std::size_t stop = end == std::string_view::npos ? text_.size() : end;
    line = trim_cr(text_.substr(pos_, stop - pos_));
    pos_ = stop + 1;
    ++line_number_;
    return true;
  }
  bool rewind() override {
    pos_ = 0;
    line_number_ = 0;
    return true;
  }

 private:
  std::string_view text_;
  std::size_t pos_ = 0;
};

class FileLines final : public LineSource {
 public:
  static constexpr std::size_t kBufferBytes = std::size_t{64} << 10;  // longest line
  explicit FileLines(std::FILE* file) : file_(file), buffer_(kBufferBytes) {}
  bool next(std::string_view& line) override;
  bool rewind() override;

 private:
  bool refill();

  std::FILE* file_;
  std::vector<char> buffer_;
  std::size_t begin_ = 0;
  std::size_t end_ = 0;
  bool eof_ = false;
};

}  // namespace twister::meshio::internal
