#include "twister/journal/journal_reader.hpp"

#include <algorithm>

namespace twister::journal {
namespace {

// Reads exactly dest.size() bytes at offset; a short read is an io_error here
// because the caller already checked the file size.
Status read_exact(ports::Storage& storage, std::uint64_t offset, std::span<std::byte> dest) {
  std::size_t done = 0;
  while (done < dest.size()) {
    TWISTER_TRY_ASSIGN(const std::size_t n, storage.read_at(offset + done, dest.subspan(done)));
    if (n == 0) return StatusCode::io_error;
    done += n;
  }
  return ok_status();
}

}  // namespace

Status JournalReader::open() {
  opened_ = false;
  problem_ = TailProblem::none;
  good_end_ = 0;
  format_ = {};
  header_ = HeaderCheck::ok;
  order_ = {};
  TWISTER_TRY_ASSIGN(file_size_, storage_.size());
  if (file_size_ == 0) {
    opened_ = true;
    return ok_status();
  }
  const std::size_t header =
      static_cast<std::size_t>(std::min<std::uint64_t>(file_size_, kMaxFileHeaderBytes));
  TWISTER_TRY(read_exact(storage_, 0, std::span(buffer_).first(header)));
  header_ = check_file_header(std::span<const std::byte>(buffer_).first(header), format_);
  switch (header_) {
    case HeaderCheck::ok:
      break;
    case HeaderCheck::torn:  // a power cut at creation: cut to zero by truncate_tail()
      opened_ = true;
      problem_ = TailProblem::torn_header;
      return ok_status();
    case HeaderCheck::too_new:
      return StatusCode::not_supported;
    case HeaderCheck::not_a_journal:
    case HeaderCheck::damaged:
      return StatusCode::data_loss;
  }
  opened_ = true;
  good_end_ = format_.header_bytes();
  return ok_status();
}

Status JournalReader::seek(std::uint64_t offset) {
  if (!opened_) return StatusCode::failed_precondition;
  if (offset < format_.header_bytes() || offset > file_size_) return StatusCode::out_of_range;
  good_end_ = offset;
  problem_ = TailProblem::none;
  order_.resume();
  return ok_status();
}

Result<JournalRecord> JournalReader::fail(TailProblem problem) {
  problem_ = problem;
  return StatusCode::data_loss;
}

Result<JournalRecord> JournalReader::next() {
  if (!opened_) return StatusCode::failed_precondition;
  if (problem_ != TailProblem::none) return StatusCode::data_loss;
  if (good_end_ == file_size_) return StatusCode::unavailable;
  const std::uint64_t left = file_size_ - good_end_;
  const std::size_t head = format_.record_header_bytes();
  if (left < head) return fail(TailProblem::torn_header);
  TWISTER_TRY(read_exact(storage_, good_end_, std::span(buffer_).first(head)));
  std::size_t total = 0;
  if (const TailProblem p = check_record_header(buffer_, format_, total); p != TailProblem::none) {
    return fail(p);
  }
  if (left < total) return fail(TailProblem::torn_record);
  TWISTER_TRY(
      read_exact(storage_, good_end_ + head, std::span(buffer_).subspan(head, total - head)));
  JournalRecord record;
  const TailProblem p =
      check_record(std::span<const std::byte>(buffer_).first(total), format_, record);
  if (p != TailProblem::none) return fail(p);
  if (format_.proves_order()) {
    if (const TailProblem order = order_.check(record.sequence); order != TailProblem::none) {
      return fail(order);
    }
    order_.accept(record.sequence);
  }
  good_end_ += total;
  return record;
}

Status JournalReader::truncate_tail() {
  if (!opened_) return StatusCode::failed_precondition;
  if (problem_ == TailProblem::none) return ok_status();
  // Only what an interrupted append leaves is cut; a complete record never is.
  if (!may_be_torn(problem_)) return StatusCode::data_loss;
  TWISTER_TRY(storage_.truncate(good_end_));
  TWISTER_TRY(storage_.sync());
  file_size_ = good_end_;
  problem_ = TailProblem::none;
  return ok_status();
}

}  // namespace twister::journal
