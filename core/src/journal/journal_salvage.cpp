#include "twister/journal/journal_salvage.hpp"

#include <array>
#include <span>

namespace twister::journal {
namespace {

using Drop = SalvageObserver::Drop;

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

class Copier {
 public:
  Copier(ports::Storage& in, ports::FileSink& out, SalvageObserver* observer, RecordFilter* filter,
         bool ordered, SalvageReport& report)
      : in_(in),
        out_(out),
        observer_(observer),
        filter_(filter),
        ordered_(ordered),
        report_(report) {}

  Status take(const ScanItem& item) {
    const bool candidate =
        item.kind == ScanItem::Kind::record || (ordered_ && is_order_problem(item.problem));
    if (!candidate) {
      ++report_.damaged_ranges;
      report_.damaged_bytes += item.bytes;
      if (observer_ != nullptr) observer_->damaged(item.offset, item.bytes, item.problem);
      return ok_status();
    }
    ++report_.records_found;
    const JournalRecord& r = item.record;
    if (ordered_ && r.sequence != next_) {
      drop(item, r.sequence < next_ ? Drop::out_of_order : Drop::after_gap);
      return ok_status();
    }
    if (r.type == RecordType::stroke && r.stroke.chain_step > 0 && !chain_.continues(r.stroke)) {
      drop(item, Drop::broken_chain);
      return ok_status();
    }
    if (filter_ != nullptr && !filter_->keep(r)) {
      drop(item, Drop::refused);
      return ok_status();
    }
    TWISTER_TRY(copy_record(in_, out_, item));
    chain_.kept(r);
    next_ = r.sequence + 1;
    ++report_.records_kept;
    return ok_status();
  }

 private:
  void drop(const ScanItem& item, Drop why) {
    switch (why) {
      case Drop::broken_chain:
        ++report_.broken_chain;
        break;
      case Drop::refused:
        ++report_.refused;
        break;
      case Drop::out_of_order:
        ++report_.out_of_order;
        break;
      case Drop::after_gap:
        ++report_.after_gap;
        break;
    }
    if (observer_ != nullptr) observer_->dropped(item, why);
  }

  ports::Storage& in_;
  ports::FileSink& out_;
  SalvageObserver* observer_;
  RecordFilter* filter_;
  bool ordered_;
  SalvageReport& report_;
  ChainState chain_{};
  std::uint32_t next_ = 0;  // version 2: the sequence the copy needs next
};

Status copy_records(JournalScanner& scanner, Copier& copier) {
  for (;;) {
    auto item = scanner.next();
    if (item.status().code() == StatusCode::unavailable) return ok_status();
    TWISTER_TRY(item.status());
    TWISTER_TRY(copier.take(*item));
  }
}

}  // namespace

Result<SalvageReport> salvage_journal(ports::Storage& in, ports::FileSink& out,
                                      SalvageObserver* observer, RecordFilter* filter) {
  JournalScanner scanner(in);
  TWISTER_TRY(scanner.open());
  // An empty file or a torn file header: the copy is an empty journal of the newest format.
  const JournalFormat format = scanner.header() == HeaderCheck::ok && scanner.file_size() > 0
                                   ? scanner.format()
                                   : version2_format(0);
  SalvageReport report;
  Copier copier(in, out, observer, filter, format.proves_order(), report);
  TWISTER_TRY(out.begin());
  const auto header = file_header(format);
  Status s = out.write(std::span<const std::byte>(header).first(format.header_bytes()));
  if (s.ok()) s = copy_records(scanner, copier);
  if (s.ok()) s = out.commit();
  if (!s.ok()) {
    out.abort();
    return s;
  }
  return report;
}

}  // namespace twister::journal
