#include "twister/journal/journal_reader.hpp"

#include <algorithm>
#include <cstring>

#include "twister/base/checksum.hpp"
#include "twister/base/internal/byte_cursor.hpp"

namespace twister::journal {
namespace {

std::uint32_t load_u32(std::span<const std::byte> bytes) {
  return twister::internal::ByteReader(bytes).u32();
}

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

const char* tail_problem_name(TailProblem problem) {
  switch (problem) {
    case TailProblem::none:
      return "none";
    case TailProblem::torn_header:
      return "torn_header";
    case TailProblem::torn_record:
      return "torn_record";
    case TailProblem::bad_length:
      return "bad_length";
    case TailProblem::bad_crc:
      return "bad_crc";
    case TailProblem::bad_payload:
      return "bad_payload";
  }
  return "unknown";
}

Status JournalReader::open() {
  opened_ = false;
  problem_ = TailProblem::none;
  good_end_ = 0;
  TWISTER_TRY_ASSIGN(file_size_, storage_.size());
  if (file_size_ == 0) {
    opened_ = true;
    return ok_status();
  }
  const std::size_t header =
      static_cast<std::size_t>(std::min<std::uint64_t>(file_size_, kFileHeaderBytes));
  TWISTER_TRY(read_exact(storage_, 0, std::span(buffer_).first(header)));
  // A file that is a prefix of a header is a header torn by a power cut at creation.
  if (std::memcmp(buffer_.data(), kFileHeader.data(), header) != 0) return StatusCode::data_loss;
  opened_ = true;
  if (header < kFileHeaderBytes) {
    problem_ = TailProblem::torn_header;
    return ok_status();
  }
  good_end_ = kFileHeaderBytes;
  return ok_status();
}

Status JournalReader::seek(std::uint64_t offset) {
  if (!opened_) return StatusCode::failed_precondition;
  if (offset < kFileHeaderBytes || offset > file_size_) return StatusCode::out_of_range;
  good_end_ = offset;
  problem_ = TailProblem::none;
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
  if (left < kRecordHeaderBytes) return fail(TailProblem::torn_header);
  TWISTER_TRY(read_exact(storage_, good_end_, std::span(buffer_).first(kRecordHeaderBytes)));
  const std::uint32_t payload = load_u32(buffer_);
  if (payload > kMaxPayloadBytes || buffer_[6] != std::byte{0} || buffer_[7] != std::byte{0}) {
    return fail(TailProblem::bad_length);
  }
  const std::size_t total = kRecordHeaderBytes + payload + kRecordCrcBytes;
  if (left < total) return fail(TailProblem::torn_record);
  TWISTER_TRY(
      read_exact(storage_, good_end_ + kRecordHeaderBytes,
                 std::span(buffer_).subspan(kRecordHeaderBytes, payload + kRecordCrcBytes)));
  const std::size_t body = kRecordHeaderBytes + payload;
  if (crc32(std::span(buffer_).first(body)) != load_u32(std::span(buffer_).subspan(body))) {
    return fail(TailProblem::bad_crc);
  }
  auto record =
      decode_payload(static_cast<std::uint8_t>(buffer_[4]), static_cast<std::uint8_t>(buffer_[5]),
                     std::span<const std::byte>(buffer_).subspan(kRecordHeaderBytes, payload));
  if (!record.ok()) return fail(TailProblem::bad_payload);
  good_end_ += total;
  return record;
}

Status JournalReader::truncate_tail() {
  if (!opened_) return StatusCode::failed_precondition;
  if (problem_ == TailProblem::none) return ok_status();
  TWISTER_TRY(storage_.truncate(good_end_));
  TWISTER_TRY(storage_.sync());
  file_size_ = good_end_;
  problem_ = TailProblem::none;
  return ok_status();
}

}  // namespace twister::journal
