// Journal file formats, and the checks every reader of a record shares.
//
// Version 1 (journals written before issue 21; read exactly as before, appended to in
// version 1):
//   file header (8 B):  "TWJL" | u32 1
//   record:             u32 payload_length | u8 record_version | u8 type | u16 0 |
//                       payload | u32 CRC-32 of everything before it in the record
// Version 2 (every new journal): the journal proves its own order.
//   file header (16 B): "TWJL" | u32 2 | u32 journal id | u32 CRC-32 of the 12 bytes before
//   record:             u32 payload_length | u8 record_version | u8 type | u16 0 |
//                       u32 journal id | payload | u32 CRC-32 of everything before it
//   Every record carries the journal's identity (the header's id), and sequences run
//   0, 1, 2, ... in file order. A CRC-valid record with another id was spliced in from
//   another journal; a sequence that repeats, goes back or skips is a duplicate, a
//   record out of order or a gap. Each is refused with its offset (never a torn tail).
// The payload (it starts with the u32 sequence) and the record versions are the same in
// both (journal_record.hpp). All integers little-endian.
//
// Why an identity in each record rather than chained CRCs: each record stays checkable
// on its own, so a damaged record costs that record only (a chained CRC makes the record
// after a flipped CRC field fail too, and the damage at the end of a file would then be
// cut as a torn tail with a good record in it), a record from another journal is told
// apart from a torn one even when it is the last record (its own CRC holds, the id does
// not), and the sequence check finds duplicates and gaps. A checkpoint's anchor (offset,
// record count, the CRC of the record before) together with the scan's sequence check
// pins the prefix it stands for.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "twister/journal/journal_record.hpp"

namespace twister::journal {

inline constexpr std::uint32_t kFileVersion1 = 1;
inline constexpr std::uint32_t kFileVersion2 = 2;
// What new journals are written in.
inline constexpr std::uint32_t kNewestFileVersion = kFileVersion2;
// Magic and version: the part of the header every version shares.
inline constexpr std::size_t kFilePrefixBytes = 8;
inline constexpr std::size_t kMaxFileHeaderBytes = 16;

struct JournalFormat {
  std::uint32_t version = kFileVersion1;
  std::uint32_t id = 0;  // version 2: the journal's identity

  std::size_t header_bytes() const { return version == kFileVersion1 ? 8 : kMaxFileHeaderBytes; }
  std::size_t record_header_bytes() const { return version == kFileVersion1 ? 8 : 12; }
  // Version 2: identity and sequences are checked.
  bool proves_order() const { return version >= kFileVersion2; }
  friend bool operator==(const JournalFormat&, const JournalFormat&) = default;
};
inline constexpr JournalFormat kVersion1Format{};
constexpr JournalFormat version2_format(std::uint32_t id) { return {kFileVersion2, id}; }

// The file header of `format` (its first header_bytes() bytes).
std::array<std::byte, kMaxFileHeaderBytes> file_header(const JournalFormat& format);

enum class HeaderCheck : std::uint8_t {
  ok,
  torn,           // the file is a proper prefix of a header (a power cut at creation)
  not_a_journal,  // wrong magic
  damaged,        // version 2 header whose CRC does not match
  too_new,        // a journal of a newer format version than this program reads
};
const char* header_check_name(HeaderCheck check);
// Checks the first bytes of a file (all of a file shorter than kMaxFileHeaderBytes);
// on ok, `format` is the file's.
HeaderCheck check_file_header(std::span<const std::byte> first, JournalFormat& format);

// Every kind of trouble at a record's offset. The first four can be an interrupted
// append (and are cut when nothing valid follows); the others are complete, CRC-valid
// records that are refused wherever they are, never cut.
enum class TailProblem : std::uint8_t {
  none = 0,
  torn_header,      // the file ends inside a record header (or the file header)
  torn_record,      // the file ends inside a record's payload or CRC
  bad_length,       // payload length above kMaxPayloadBytes or reserved bits set
  bad_crc,          // CRC mismatch
  bad_payload,      // CRC fine but invalid values (wrong length, NaN, field out of range)
  unknown_version,  // CRC fine but a record version this program does not know
  unknown_type,     // CRC fine but a record type this program does not know
  other_journal,    // CRC fine but another journal's identity (spliced in)
  duplicate,        // CRC fine but the sequence of the record before it again
  out_of_order,     // CRC fine but a sequence earlier than the record before it
  sequence_gap,     // CRC fine but sequences are missing before it (nothing damaged there)
};
const char* tail_problem_name(TailProblem problem);
// What a problem means, for messages ("a duplicated record", ...).
const char* tail_problem_text(TailProblem problem);
// Trouble an interrupted append can leave (torn_*, bad_length, bad_crc).
bool may_be_torn(TailProblem problem);
// Refused for its place in the order alone (the record itself decodes).
bool is_order_problem(TailProblem problem);

// Reads the record header at the start of `head` (record_header_bytes() bytes):
// none and the record's whole length, or bad_length.
TailProblem check_record_header(std::span<const std::byte> head, const JournalFormat& format,
                                std::size_t& total);
// Checks a whole record (`bytes`, the length check_record_header gave): CRC, identity,
// content. none: `record` holds it.
TailProblem check_record(std::span<const std::byte> bytes, const JournalFormat& format,
                         JournalRecord& record);

// Writes the whole record in `format` into out; returns its size (as encode_record).
Result<std::size_t> encode_record(const JournalRecord& record, std::span<std::byte> out,
                                  const JournalFormat& format);

// The order of a version 2 journal: sequences 0, 1, 2, ...; after a damaged range any
// later sequence may follow (the damage held the missing ones).
class SequenceCheck {
 public:
  // none, duplicate, out_of_order or sequence_gap for a record of `sequence` next.
  TailProblem check(std::uint32_t sequence) const;
  // The record is taken as the order's last (in order, or after a gap it was reported).
  void accept(std::uint32_t sequence) {
    any_ = true;
    last_ = sequence;
    after_damage_ = false;
  }
  void damaged() { after_damage_ = true; }
  // Continue at a record boundary whose sequence is known to be right (a checkpoint).
  void resume() {
    any_ = false;
    after_damage_ = true;
  }

 private:
  bool any_ = false;
  bool after_damage_ = false;
  std::uint32_t last_ = 0;
};

}  // namespace twister::journal
