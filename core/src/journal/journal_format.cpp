#include "twister/journal/journal_format.hpp"

#include <cstring>

#include "twister/base/checksum.hpp"
#include "twister/base/internal/byte_cursor.hpp"

namespace twister::journal {
namespace {

using twister::internal::ByteReader;
using twister::internal::ByteWriter;

constexpr std::size_t kIdBytes = 4;
constexpr std::uint8_t kTypeCount = 4;

std::uint32_t load_u32(std::span<const std::byte> bytes) { return ByteReader(bytes).u32(); }

// Why a CRC-valid record did not decode: its type, its version, or its values.
TailProblem undecodable(std::uint8_t version, std::uint8_t type) {
  if (type < 1 || type > kTypeCount) return TailProblem::unknown_type;
  const bool stroke = type == static_cast<std::uint8_t>(RecordType::stroke);
  const bool known =
      version == kRecordVersion ||
      (stroke && (version == kRecordVersionLongTurns || version == kRecordVersionRefined ||
                  version == kRecordVersionRefinedLocal || version == kRecordVersionSymmetric));
  return known ? TailProblem::bad_payload : TailProblem::unknown_version;
}

}  // namespace

std::array<std::byte, kMaxFileHeaderBytes> file_header(const JournalFormat& format) {
  std::array<std::byte, kMaxFileHeaderBytes> header{};
  std::memcpy(header.data(), kFileMagic.data(), kFileMagic.size());
  ByteWriter w(std::span<std::byte>(header).subspan(4));
  w.u32(format.version);
  if (format.version != kFileVersion1) {
    w.u32(format.id);
    w.u32(crc32(std::span<const std::byte>(header).first(12)));
  }
  return header;
}

const char* header_check_name(HeaderCheck check) {
  switch (check) {
    case HeaderCheck::ok:
      return "ok";
    case HeaderCheck::torn:
      return "torn header";
    case HeaderCheck::not_a_journal:
      return "not a journal";
    case HeaderCheck::damaged:
      return "damaged header";
    case HeaderCheck::too_new:
      return "a newer journal format";
  }
  return "unknown";
}

HeaderCheck check_file_header(std::span<const std::byte> first, JournalFormat& format) {
  const std::size_t magic = first.size() < kFileMagic.size() ? first.size() : kFileMagic.size();
  if (std::memcmp(first.data(), kFileMagic.data(), magic) != 0) return HeaderCheck::not_a_journal;
  if (first.size() < kFilePrefixBytes) {
    // A prefix of either version's header (the version's low byte may be there).
    const bool prefix = first.size() <= 4 || first[4] == std::byte{kFileVersion1} ||
                        first[4] == std::byte{kFileVersion2};
    for (std::size_t i = 5; prefix && i < first.size(); ++i) {
      if (first[i] != std::byte{0}) return HeaderCheck::not_a_journal;
    }
    return prefix ? HeaderCheck::torn : HeaderCheck::not_a_journal;
  }
  const std::uint32_t version = load_u32(first.subspan(4));
  if (version == 0) return HeaderCheck::not_a_journal;
  if (version > kNewestFileVersion) return HeaderCheck::too_new;
  JournalFormat found{version, 0};
  if (version == kFileVersion2) {
    if (first.size() < found.header_bytes()) return HeaderCheck::torn;
    found.id = load_u32(first.subspan(8));
    if (crc32(first.first(12)) != load_u32(first.subspan(12))) return HeaderCheck::damaged;
  }
  format = found;
  return HeaderCheck::ok;
}

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
    case TailProblem::unknown_version:
      return "unknown_version";
    case TailProblem::unknown_type:
      return "unknown_type";
    case TailProblem::other_journal:
      return "other_journal";
    case TailProblem::duplicate:
      return "duplicate";
    case TailProblem::out_of_order:
      return "out_of_order";
    case TailProblem::sequence_gap:
      return "sequence_gap";
  }
  return "unknown";
}

const char* tail_problem_text(TailProblem problem) {
  switch (problem) {
    case TailProblem::none:
      return "no problem";
    case TailProblem::torn_header:
    case TailProblem::torn_record:
      return "the file ends inside a record";
    case TailProblem::bad_length:
      return "an impossible record length";
    case TailProblem::bad_crc:
      return "a record whose CRC does not match";
    case TailProblem::bad_payload:
      return "a complete record with invalid values";
    case TailProblem::unknown_version:
      return "a complete record of a version this program does not know (a newer station?)";
    case TailProblem::unknown_type:
      return "a complete record of a type this program does not know (a newer station?)";
    case TailProblem::other_journal:
      return "a complete record of another journal (spliced in)";
    case TailProblem::duplicate:
      return "a duplicated record (the sequence of the record before it)";
    case TailProblem::out_of_order:
      return "a record out of order (a sequence earlier than the record before it)";
    case TailProblem::sequence_gap:
      return "a sequence gap (records missing before it)";
  }
  return "unknown";
}

bool may_be_torn(TailProblem problem) {
  return problem == TailProblem::torn_header || problem == TailProblem::torn_record ||
         problem == TailProblem::bad_length || problem == TailProblem::bad_crc;
}

bool is_order_problem(TailProblem problem) {
  return problem == TailProblem::duplicate || problem == TailProblem::out_of_order ||
         problem == TailProblem::sequence_gap;
}

TailProblem check_record_header(std::span<const std::byte> head, const JournalFormat& format,
                                std::size_t& total) {
  const std::uint32_t payload = load_u32(head);
  if (payload > kMaxPayloadBytes || head[6] != std::byte{0} || head[7] != std::byte{0}) {
    return TailProblem::bad_length;
  }
  total = format.record_header_bytes() + payload + kRecordCrcBytes;
  return TailProblem::none;
}

TailProblem check_record(std::span<const std::byte> bytes, const JournalFormat& format,
                         JournalRecord& record) {
  const std::size_t body = bytes.size() - kRecordCrcBytes;
  if (crc32(bytes.first(body)) != load_u32(bytes.subspan(body))) return TailProblem::bad_crc;
  if (format.proves_order() && load_u32(bytes.subspan(8)) != format.id) {
    return TailProblem::other_journal;
  }
  const auto version = static_cast<std::uint8_t>(bytes[4]);
  const auto type = static_cast<std::uint8_t>(bytes[5]);
  const std::size_t head = format.record_header_bytes();
  auto decoded = decode_payload(version, type, bytes.subspan(head, body - head));
  if (!decoded.ok()) return undecodable(version, type);
  record = *decoded;
  return TailProblem::none;
}

Result<std::size_t> encode_record(const JournalRecord& record, std::span<std::byte> out,
                                  const JournalFormat& format) {
  if (!format.proves_order()) return encode_record(record, out);
  if (out.size() < kIdBytes) return StatusCode::resource_exhausted;
  // The version 1 encoding, shifted by the id's 4 bytes; then the header moves back
  // in front of the id and the CRC covers the id too.
  TWISTER_TRY_ASSIGN(const std::size_t n, encode_record(record, out.subspan(kIdBytes)));
  std::memmove(out.data(), out.data() + kIdBytes, kRecordHeaderBytes);
  ByteWriter id(out.subspan(kRecordHeaderBytes, kIdBytes));
  id.u32(format.id);
  const std::size_t body = n + kIdBytes - kRecordCrcBytes;
  ByteWriter crc(out.subspan(body, kRecordCrcBytes));
  crc.u32(crc32(out.first(body)));
  return n + kIdBytes;
}

TailProblem SequenceCheck::check(std::uint32_t sequence) const {
  const std::uint32_t expected = any_ ? last_ + 1 : 0;
  if (sequence == expected) return TailProblem::none;
  if (any_ && sequence == last_) return TailProblem::duplicate;
  if (any_ && sequence < last_) return TailProblem::out_of_order;
  return after_damage_ ? TailProblem::none : TailProblem::sequence_gap;
}

}  // namespace twister::journal
