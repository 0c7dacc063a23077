#include "twister/journal/journal_scanner.hpp"

#include <algorithm>
#include <cstring>
#include <span>

#include "twister/base/checksum.hpp"
#include "twister/base/internal/byte_cursor.hpp"

namespace twister::journal {
namespace {

// The smallest record: header, a 4-byte payload (the sequence), CRC.
constexpr std::size_t kMinRecordBytes = kRecordHeaderBytes + 4 + kRecordCrcBytes;
static_assert(kMaxRecordBytes <= 4096);

}  // namespace

Status JournalScanner::open() {
  opened_ = false;
  storage_failed_ = false;
  window_bytes_ = 0;
  TWISTER_TRY_ASSIGN(file_size_, storage_.size());
  pos_ = 0;
  if (file_size_ > 0) {
    const auto header =
        static_cast<std::size_t>(std::min<std::uint64_t>(file_size_, kFileHeaderBytes));
    if (!load(0, header)) return StatusCode::io_error;
    if (std::memcmp(window_.data(), kFileHeader.data(), header) != 0) return StatusCode::data_loss;
    // A complete header is skipped; a torn one is reported as damage by next().
    if (header == kFileHeaderBytes) pos_ = kFileHeaderBytes;
  }
  opened_ = true;
  return ok_status();
}

bool JournalScanner::load(std::uint64_t offset, std::size_t bytes) {
  if (offset >= window_offset_ && offset + bytes <= window_offset_ + window_bytes_) return true;
  const auto want =
      static_cast<std::size_t>(std::min<std::uint64_t>(window_.size(), file_size_ - offset));
  std::size_t done = 0;
  while (done < want) {
    const auto n = storage_.read_at(offset + done, std::span(window_).subspan(done, want - done));
    if (!n.ok() || *n == 0) break;
    done += *n;
  }
  window_offset_ = offset;
  window_bytes_ = done;
  if (done < bytes) storage_failed_ = true;
  return done >= bytes;
}

TailProblem JournalScanner::parse_at(std::uint64_t offset, JournalRecord& record,
                                     std::size_t& total) {
  const std::uint64_t left = file_size_ - offset;
  if (left < kRecordHeaderBytes) return TailProblem::torn_header;
  if (!load(offset, kRecordHeaderBytes)) return TailProblem::torn_header;
  const std::byte* at = window_.data() + (offset - window_offset_);
  const std::uint32_t payload =
      twister::internal::ByteReader(std::span<const std::byte>(at, 4)).u32();
  if (payload > kMaxPayloadBytes || at[6] != std::byte{0} || at[7] != std::byte{0}) {
    return TailProblem::bad_length;
  }
  total = kRecordHeaderBytes + payload + kRecordCrcBytes;
  if (left < total) return TailProblem::torn_record;
  if (!load(offset, total)) return TailProblem::torn_record;
  at = window_.data() + (offset - window_offset_);
  const std::size_t body = kRecordHeaderBytes + payload;
  const std::span<const std::byte> bytes(at, total);
  if (crc32(bytes.first(body)) != twister::internal::ByteReader(bytes.subspan(body)).u32()) {
    return TailProblem::bad_crc;
  }
  auto decoded = decode_payload(static_cast<std::uint8_t>(at[4]), static_cast<std::uint8_t>(at[5]),
                                bytes.subspan(kRecordHeaderBytes, payload));
  if (!decoded.ok()) return TailProblem::bad_payload;
  record = *decoded;
  return TailProblem::none;
}

Result<ScanItem> JournalScanner::next() {
  if (!opened_) return StatusCode::failed_precondition;
  if (pos_ >= file_size_) return StatusCode::unavailable;
  ScanItem item;
  item.offset = pos_;
  if (pos_ < kFileHeaderBytes) {  // a torn file header: all of the (short) file
    item.kind = ScanItem::Kind::damage;
    item.problem = TailProblem::torn_header;
    item.bytes = file_size_ - pos_;
    pos_ = file_size_;
    return item;
  }
  std::size_t total = 0;
  item.problem = parse_at(pos_, item.record, total);
  if (storage_failed_) return StatusCode::io_error;
  if (item.problem == TailProblem::none) {
    item.bytes = total;
    pos_ += total;
    return item;
  }
  // Resynchronise: the next offset where a whole valid record starts.
  item.kind = ScanItem::Kind::damage;
  std::uint64_t q = pos_ + 1;
  JournalRecord candidate;
  for (; q + kMinRecordBytes <= file_size_; ++q) {
    if (parse_at(q, candidate, total) == TailProblem::none) break;
    if (storage_failed_) return StatusCode::io_error;
  }
  if (q + kMinRecordBytes > file_size_) q = file_size_;
  item.bytes = q - pos_;
  pos_ = q;
  return item;
}

Result<JournalSurvey> survey_journal(ports::Storage& storage, std::uint64_t probe) {
  JournalScanner scanner(storage);
  TWISTER_TRY(scanner.open());
  JournalSurvey s;
  s.file_size = scanner.file_size();
  s.good_end = s.file_size >= kFileHeaderBytes ? kFileHeaderBytes : 0;
  for (;;) {
    auto item = scanner.next();
    if (item.status().code() == StatusCode::unavailable) break;
    TWISTER_TRY(item.status());
    if (item->kind == ScanItem::Kind::damage) {
      if (s.problem == TailProblem::none) s.problem = item->problem;
      s.damaged_bytes += item->bytes;
      continue;
    }
    if (s.problem == TailProblem::none) {
      if (item->offset == probe) {
        s.probe_is_boundary = true;
        s.probe_records = s.records;
      }
      ++s.records;
      s.good_end = item->offset + item->bytes;
      s.has_records = true;
      s.last_sequence = item->record.sequence;
    } else {
      if (s.later_records == 0) s.first_later_offset = item->offset;
      ++s.later_records;
    }
  }
  if (probe == s.good_end && s.good_end >= kFileHeaderBytes) {
    s.probe_is_boundary = true;
    s.probe_records = s.records;
  }
  return s;
}

}  // namespace twister::journal
