// Station::start(): journal recovery. The whole file is scanned first, so nothing is
// applied or cut before we know whether the damage (if any) is a torn tail or
// corruption; only a torn tail is ever cut, only after its bytes are kept, and only in
// begin_appending(), once the program knows the rest of its start-up succeeded.
#include <algorithm>
#include <array>

#include "twister/checkpoint/session_checkpoint.hpp"
#include "twister/journal/journal_reader.hpp"
#include "twister/station/station.hpp"

namespace twister::station {

const char* recovery_outcome_name(JournalRecovery::Outcome outcome) {
  using O = JournalRecovery::Outcome;
  switch (outcome) {
    case O::not_started:
      return "not_started";
    case O::recovered:
      return "recovered";
    case O::ok:
      return "ok";
    case O::not_a_journal:
      return "not_a_journal";
    case O::corrupt:
      return "corrupt";
    case O::too_new:
      return "too_new";
    case O::does_not_fit:
      return "does_not_fit";
    case O::tail_not_kept:
      return "tail_not_kept";
    case O::io_error:
      return "io_error";
  }
  return "unknown";
}

Status Station::start() {
  TWISTER_TRY(recover());
  return begin_appending();
}

Status Station::recover() {
  using O = JournalRecovery::Outcome;
  const auto s0 = config_.hand_station[0];
  const auto s1 = config_.hand_station[1];
  if (s0 < 1 || s0 > tracker::kMaxStations || s1 < 1 || s1 > tracker::kMaxStations || s0 == s1) {
    return StatusCode::failed_precondition;
  }
  if (exhibit_.enabled() && (files_.archive == nullptr || files_.base_model == nullptr)) {
    return StatusCode::failed_precondition;
  }
  recovery_ = {};
  checkpoints_.reset(sculpt_.mesh().checksum(), 0);
  // The checkpoint's anchor is checked against the journal in the same scan.
  Result<checkpoint::CheckpointHeader> header = StatusCode::unavailable;
  if (files_.checkpoint_in != nullptr)
    header = checkpoint::read_checkpoint_header(*files_.checkpoint_in);
  if (files_.checkpoint_in != nullptr && !header.ok()) {
    recovery_.checkpoint = JournalRecovery::Checkpoint::damaged;
  }
  auto survey = journal::survey_journal(storage_, header.ok() ? header->journal_offset : 0);
  if (!survey.ok()) {
    const StatusCode code = survey.status().code();
    recovery_.outcome = code == StatusCode::data_loss       ? O::not_a_journal
                        : code == StatusCode::not_supported ? O::too_new
                                                            : O::io_error;
    return survey.status();
  }
  recovery_.survey = *survey;
  // Valid records after a damaged one, or a complete record that is refused: not an
  // interrupted append. Cutting would delete them; the file stays as it is and the
  // operator decides (salvage).
  if (survey->corrupt()) {
    recovery_.outcome = O::corrupt;
    return StatusCode::data_loss;
  }
  // Replay through the session's own commit path, so the mesh is exactly the one
  // the last run left.
  journal::JournalReader reader(storage_);
  if (const Status s = reader.open(); !s.ok()) {
    recovery_.outcome = s.code() == StatusCode::data_loss ? O::not_a_journal : O::io_error;
    return s;
  }
  if (header.ok()) {
    if (const Status s = use_checkpoint(*header, *survey); !s.ok()) {
      recovery_.outcome = O::io_error;
      return s;
    }
    if (recovery_.checkpoint == JournalRecovery::Checkpoint::used) {
      TWISTER_TRY(reader.seek(header->journal_offset));
    }
  }
  TWISTER_TRY(replay_journal(reader));
  recovery_.outcome = O::recovered;
  return ok_status();
}

Status Station::begin_appending() {
  using O = JournalRecovery::Outcome;
  if (recovery_.outcome != O::recovered || started_) return StatusCode::failed_precondition;
  const journal::JournalSurvey& survey = recovery_.survey;
  // A torn tail (power cut mid-append) is cut so new records follow the last good one.
  if (survey.torn_tail()) {
    if (const Status kept = keep_torn_tail(); !kept.ok()) {
      recovery_.outcome = O::tail_not_kept;
      return kept;
    }
    Status cut = storage_.truncate(survey.good_end);
    if (cut.ok()) cut = storage_.sync();
    if (!cut.ok()) {
      recovery_.outcome = O::io_error;
      return cut;
    }
    recovery_.tail_cut = survey.file_size - survey.good_end;
  }
  writer_.set_new_journal_id(files_.new_journal_id);
  if (const Status opened = writer_.open(); !opened.ok()) {
    recovery_.outcome = O::io_error;
    return opened;
  }
  records_at_start_ = survey.records;
  checkpoints_.reset(checkpoints_.base_checksum(), recovery_.checkpoint_records);
  recovery_.outcome = O::ok;
  started_ = true;
  exhibit_.start(journal_records() > 0, files_.visitors_today, clock_.now_us());
  emit(session::make_event(session::SessionEventKind::journal_recovered, 0,
                           session::payload::JournalRecovered{
                               static_cast<std::uint32_t>(survey.records), recovery_.tail_cut}),
       clock_.now_us());
  return ok_status();
}

const char* checkpoint_use_name(JournalRecovery::Checkpoint use) {
  using C = JournalRecovery::Checkpoint;
  switch (use) {
    case C::none:
      return "none";
    case C::used:
      return "used";
    case C::damaged:
      return "damaged";
    case C::other_model:
      return "made from another model, mesh capacity or history size";
    case C::other_journal:
      return "made for another journal (or a longer one)";
  }
  return "unknown";
}

Status Station::use_checkpoint(const checkpoint::CheckpointHeader& h,
                               const journal::JournalSurvey& survey) {
  using C = JournalRecovery::Checkpoint;
  ports::Storage& file = *files_.checkpoint_in;
  const session::UndoHistory& history = sculpt_.history();
  const mesh::Mesh& m = sculpt_.mesh();
  if (h.base_checksum != checkpoints_.base_checksum() ||
      h.change_capacity != history.change_capacity() ||
      h.entry_capacity != history.entry_capacity() ||
      h.triangle_change_capacity != history.triangle_change_capacity() ||
      h.vertex_capacity != m.vertex_capacity() || h.triangle_capacity != m.triangle_capacity()) {
    recovery_.checkpoint = C::other_model;
    return ok_status();
  }
  // Its anchor: a record boundary of the good prefix, after exactly its records, and
  // the record before it carries the CRC it names.
  bool anchored = survey.probe_is_boundary && survey.probe_records == h.journal_records;
  if (anchored && h.journal_records > 0) {
    std::array<std::byte, journal::kRecordCrcBytes> crc{};
    const auto n = storage_.read_at(h.journal_offset - crc.size(), crc);
    anchored = n.ok() && *n == crc.size() &&
               static_cast<std::uint32_t>(crc[0]) + (static_cast<std::uint32_t>(crc[1]) << 8) +
                       (static_cast<std::uint32_t>(crc[2]) << 16) +
                       (static_cast<std::uint32_t>(crc[3]) << 24) ==
                   h.last_record_crc;
  }
  if (!anchored) {
    recovery_.checkpoint = C::other_journal;
    return ok_status();
  }
  if (!checkpoint::verify_checkpoint(file, h, sculpt_).ok()) {
    recovery_.checkpoint = C::damaged;
    return ok_status();
  }
  // Verified: from here a failure leaves the model half written, so start-up fails.
  TWISTER_TRY(checkpoint::restore_checkpoint(file, h, sculpt_));
  recovery_.checkpoint = C::used;
  recovery_.checkpoint_records = h.journal_records;
  return ok_status();
}

Status Station::replay_journal(journal::JournalReader& reader) {
  for (;;) {
    auto record = reader.next();
    const StatusCode code = record.status().code();
    // Clean end, or the torn tail the survey found (cut by the caller).
    if (code == StatusCode::unavailable || code == StatusCode::data_loss) return ok_status();
    if (!record.ok()) {
      recovery_.outcome = JournalRecovery::Outcome::io_error;
      return record.status();
    }
    if (const Status s = sculpt_.apply_record(*record); !s.ok()) {
      recovery_.outcome = JournalRecovery::Outcome::does_not_fit;
      recovery_.record_index = recovery_.checkpoint_records + recovery_.replayed;
      recovery_.record_sequence = record->sequence;
      recovery_.record_status = s;
      return s;
    }
    ++recovery_.replayed;
  }
}

Status Station::keep_torn_tail() {
  const journal::JournalSurvey& survey = recovery_.survey;
  if (files_.tail_archive == nullptr) return ok_status();
  ports::FileSink& sink = *files_.tail_archive;
  TWISTER_TRY(sink.begin());
  std::array<std::byte, 512> chunk{};
  for (std::uint64_t at = survey.good_end; at < survey.file_size;) {
    auto n = storage_.read_at(at, chunk);
    if (!n.ok() || *n == 0) {
      sink.abort();
      return StatusCode::io_error;
    }
    const auto bytes = static_cast<std::size_t>(std::min<std::uint64_t>(*n, survey.file_size - at));
    if (const Status w = sink.write(std::span(chunk).first(bytes)); !w.ok()) {
      sink.abort();
      return w;
    }
    at += bytes;
  }
  TWISTER_TRY(sink.commit());
  recovery_.tail_kept = true;
  return ok_status();
}

}  // namespace twister::station
