#include "twister/journal/journal_salvage.hpp"

#include <array>
#include <span>

namespace twister::journal {
namespace {

// What replay needs to continue a freeze chain: the last kept stroke, with no undo or
// redo after it (JournalReplay's chain rule).
struct ChainState {
  bool open = false;
  StrokeRecord last{};

  bool continues(const StrokeRecord& s) const {
    return open && s.chain_step == last.chain_step + 1 && s.hand_mask == last.hand_mask &&
           s.radius_m == last.radius_m && s.method == last.method;
  }
  void kept(const JournalRecord& r) {
    if (r.type == RecordType::stroke) {
      open = true;
      last = r.stroke;
    } else if (r.type == RecordType::undo || r.type == RecordType::redo) {
      open = false;
    }
  }
};

Status copy_record(ports::Storage& in, ports::FileSink& out, const ScanItem& item) {
  std::array<std::byte, kMaxRecordBytes> buffer{};
  if (item.bytes > buffer.size()) return StatusCode::io_error;
  const auto bytes = std::span(buffer).first(static_cast<std::size_t>(item.bytes));
  std::size_t done = 0;
  while (done < bytes.size()) {
    TWISTER_TRY_ASSIGN(const std::size_t n, in.read_at(item.offset + done, bytes.subspan(done)));
    if (n == 0) return StatusCode::io_error;
    done += n;
  }
  return out.write(bytes);
}

Status copy_records(JournalScanner& scanner, ports::Storage& in, ports::FileSink& out,
                    SalvageObserver* observer, RecordFilter* filter, SalvageReport& report) {
  ChainState chain;
  for (;;) {
    auto item = scanner.next();
    if (item.status().code() == StatusCode::unavailable) return ok_status();
    TWISTER_TRY(item.status());
    if (item->kind == ScanItem::Kind::damage) {
      ++report.damaged_ranges;
      report.damaged_bytes += item->bytes;
      if (observer != nullptr) observer->damaged(item->offset, item->bytes, item->problem);
      continue;
    }
    ++report.records_found;
    const JournalRecord& r = item->record;
    if (r.type == RecordType::stroke && r.stroke.chain_step > 0 && !chain.continues(r.stroke)) {
      ++report.broken_chain;
      if (observer != nullptr) observer->dropped(*item, SalvageObserver::Drop::broken_chain);
      continue;
    }
    if (filter != nullptr && !filter->keep(r)) {
      ++report.refused;
      if (observer != nullptr) observer->dropped(*item, SalvageObserver::Drop::refused);
      continue;
    }
    TWISTER_TRY(copy_record(in, out, *item));
    chain.kept(r);
    ++report.records_kept;
  }
}

}  // namespace

Result<SalvageReport> salvage_journal(ports::Storage& in, ports::FileSink& out,
                                      SalvageObserver* observer, RecordFilter* filter) {
  JournalScanner scanner(in);
  TWISTER_TRY(scanner.open());
  SalvageReport report;
  TWISTER_TRY(out.begin());
  Status s = out.write(kFileHeader);
  if (s.ok()) s = copy_records(scanner, in, out, observer, filter, report);
  if (s.ok()) s = out.commit();
  if (!s.ok()) {
    out.abort();
    return s;
  }
  return report;
}

}  // namespace twister::journal
