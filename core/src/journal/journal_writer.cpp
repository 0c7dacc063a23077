#include "twister/journal/journal_writer.hpp"

#include <algorithm>

#include "twister/base/internal/byte_cursor.hpp"

namespace twister::journal {

Status JournalWriter::open() {
  opened_ = false;
  broken_ = false;
  appended_ = 0;
  last_crc_ = 0;
  TWISTER_TRY_ASSIGN(size_, storage_.size());
  if (size_ == 0) {
    format_ = version2_format(new_id_);
    const auto header = file_header(format_);
    Status s = storage_.append(std::span<const std::byte>(header).first(format_.header_bytes()));
    if (s.ok()) s = storage_.sync();
    if (!s.ok()) {
      (void)storage_.truncate(0);  // no torn header left behind (a full disk)
      return s;
    }
    size_ = format_.header_bytes();
  } else {
    std::array<std::byte, kMaxFileHeaderBytes> header{};
    const auto want = static_cast<std::size_t>(std::min<std::uint64_t>(size_, header.size()));
    TWISTER_TRY_ASSIGN(const std::size_t n, storage_.read_at(0, std::span(header).first(want)));
    if (n != want) return StatusCode::io_error;
    switch (check_file_header(std::span<const std::byte>(header).first(want), format_)) {
      case HeaderCheck::ok:
        break;
      case HeaderCheck::too_new:
        return StatusCode::not_supported;
      default:
        return StatusCode::data_loss;
    }
    if (size_ >= format_.header_bytes() + format_.record_header_bytes() + kRecordCrcBytes) {
      std::array<std::byte, kRecordCrcBytes> crc{};
      TWISTER_TRY_ASSIGN(const std::size_t got, storage_.read_at(size_ - crc.size(), crc));
      if (got != crc.size()) return StatusCode::io_error;
      last_crc_ = twister::internal::ByteReader(crc).u32();
    }
  }
  opened_ = true;
  return ok_status();
}

Status JournalWriter::restart(std::uint32_t id) {
  TWISTER_TRY(storage_.truncate(0));  // failed: the journal is as it was, still open
  opened_ = false;
  new_id_ = id;
  TWISTER_TRY(storage_.sync());
  return open();
}

Status JournalWriter::append(const JournalRecord& record) {
  if (!opened_ || broken_) return StatusCode::failed_precondition;
  TWISTER_TRY_ASSIGN(const std::size_t n, encode_record(record, buffer_, format_));
  Status status = storage_.append(std::span<const std::byte>(buffer_).first(n));
  if (status.ok()) status = storage_.sync();
  if (status.ok()) {
    size_ += n;
    ++appended_;
    last_crc_ =
        twister::internal::ByteReader(std::span<const std::byte>(buffer_).subspan(n - 4)).u32();
    return ok_status();
  }
  // Leave no torn record behind a later good one: cut back to the last good end.
  if (!storage_.truncate(size_).ok() || !storage_.sync().ok()) broken_ = true;
  return StatusCode::io_error;
}

Status JournalWriter::repair() {
  if (!opened_) return StatusCode::failed_precondition;
  if (!broken_) return ok_status();
  TWISTER_TRY(storage_.truncate(size_));
  TWISTER_TRY(storage_.sync());
  broken_ = false;
  return ok_status();
}

}  // namespace twister::journal
