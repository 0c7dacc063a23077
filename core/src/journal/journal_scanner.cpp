#include "twister/journal/journal_scanner.hpp"

#include <algorithm>
#include <span>

namespace twister::journal {
namespace {

// The smallest record: a version 1 header, a 4-byte payload (the sequence), CRC.
constexpr std::size_t kMinRecordBytes = kRecordHeaderBytes + 4 + kRecordCrcBytes;
static_assert(kMaxRecordBytes <= 4096);

}  // namespace

Status JournalScanner::open() {
  opened_ = false;
  storage_failed_ = false;
  window_bytes_ = 0;
  format_ = {};
  header_ = HeaderCheck::ok;
  order_ = {};
  TWISTER_TRY_ASSIGN(file_size_, storage_.size());
  pos_ = 0;
  if (file_size_ > 0) {
    const auto header =
        static_cast<std::size_t>(std::min<std::uint64_t>(file_size_, kMaxFileHeaderBytes));
    if (!load(0, header)) return StatusCode::io_error;
    header_ = check_file_header(std::span<const std::byte>(window_).first(header), format_);
    if (header_ == HeaderCheck::too_new) return StatusCode::not_supported;
    if (header_ == HeaderCheck::not_a_journal || header_ == HeaderCheck::damaged) {
      return StatusCode::data_loss;
    }
    // A complete header is skipped; a torn one is reported as damage by next().
    if (header_ == HeaderCheck::ok) pos_ = format_.header_bytes();
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
  const std::size_t head = format_.record_header_bytes();
  if (left < head) return TailProblem::torn_header;
  if (!load(offset, head)) return TailProblem::torn_header;
  const std::byte* at = window_.data() + (offset - window_offset_);
  const TailProblem length =
      check_record_header(std::span<const std::byte>(at, head), format_, total);
  if (length != TailProblem::none) return length;
  if (left < total) return TailProblem::torn_record;
  if (!load(offset, total)) return TailProblem::torn_record;
  at = window_.data() + (offset - window_offset_);
  return check_record(std::span<const std::byte>(at, total), format_, record);
}

Result<std::uint64_t> JournalScanner::resync() {
  std::uint64_t q = pos_ + 1;
  std::size_t total = 0;
  JournalRecord candidate;
  for (; q + kMinRecordBytes <= file_size_; ++q) {
    // A complete CRC-valid record ends the damage even when it is refused itself.
    if (!may_be_torn(parse_at(q, candidate, total))) return q;
    if (storage_failed_) return StatusCode::io_error;
  }
  return file_size_;
}

Result<ScanItem> JournalScanner::next() {
  if (!opened_) return StatusCode::failed_precondition;
  if (pos_ >= file_size_) return StatusCode::unavailable;
  ScanItem item;
  item.offset = pos_;
  if (header_ == HeaderCheck::torn) {  // a torn file header: all of the (short) file
    item.kind = ScanItem::Kind::damage;
    item.problem = TailProblem::torn_header;
    item.bytes = file_size_ - pos_;
    pos_ = file_size_;
    return item;
  }
  std::size_t total = 0;
  item.problem = parse_at(pos_, item.record, total);
  if (storage_failed_) return StatusCode::io_error;
  if (may_be_torn(item.problem)) {
    item.kind = ScanItem::Kind::damage;
    order_.damaged();
    TWISTER_TRY_ASSIGN(const std::uint64_t end, resync());
    item.bytes = end - pos_;
    pos_ = end;
    return item;
  }
  item.bytes = total;
  pos_ += total;
  if (item.problem != TailProblem::none) {  // complete but refused: exactly this record
    item.kind = ScanItem::Kind::damage;
    order_.damaged();
    return item;
  }
  if (format_.proves_order()) {
    item.problem = order_.check(item.record.sequence);
    // A gap is reported once; the order goes on from the record after it.
    if (item.problem == TailProblem::none || item.problem == TailProblem::sequence_gap) {
      order_.accept(item.record.sequence);
    }
    if (item.problem != TailProblem::none) item.kind = ScanItem::Kind::damage;
  }
  return item;
}

namespace {

void note_damage(JournalSurvey& s, const ScanItem& item) {
  if (s.problem == TailProblem::none) s.problem = item.problem;
  s.damaged_bytes += item.bytes;
  if (may_be_torn(item.problem)) return;
  if (s.refused_records == 0) {
    s.first_refused_offset = item.offset;
    s.first_refused = item.problem;
  }
  ++s.refused_records;
}

}  // namespace

Result<JournalSurvey> survey_journal(ports::Storage& storage, std::uint64_t probe) {
  JournalScanner scanner(storage);
  TWISTER_TRY(scanner.open());
  JournalSurvey s;
  s.file_size = scanner.file_size();
  s.format = scanner.format();
  s.good_end = scanner.header() == HeaderCheck::ok ? s.format.header_bytes() : 0;
  if (s.file_size == 0) s.good_end = 0;
  for (;;) {
    auto item = scanner.next();
    if (item.status().code() == StatusCode::unavailable) break;
    TWISTER_TRY(item.status());
    if (item->kind == ScanItem::Kind::damage) {
      note_damage(s, *item);
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
  if (probe == s.good_end && s.good_end >= s.format.header_bytes() && s.good_end > 0) {
    s.probe_is_boundary = true;
    s.probe_records = s.records;
  }
  return s;
}

}  // namespace twister::journal
