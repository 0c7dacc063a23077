// The parser's '2'-led replies (docs/fastrak-protocol.md §3.6): the 55-byte status record and every
// other reply line (read-backs, command errors with their EC code).
#include <algorithm>

#include "fastrak_fields.hpp"
#include "twister/tracker/fastrak_parser.hpp"

namespace twister::tracker {

using internal::ch;
using internal::is_digit;
using internal::is_letter;

FastrakParser::Candidate FastrakParser::examine_reply(const std::byte* p, std::size_t avail,
                                                      FastrakEvent& out) const {
  if (avail < 2) return {Verdict::need_more, 2};
  const char station = ch(p[1]);
  if (station != ' ' && !is_digit(station) && !is_letter(station)) return {Verdict::drop, 1};
  if (avail < 3) return {Verdict::need_more, 3};
  const char command = ch(p[2]);
  if (!is_letter(command)) return {Verdict::drop, 1};
  // A reply is printable text up to CR LF; anything else is not a reply.
  std::size_t i = 3;
  for (; i < avail; ++i) {
    const char c = ch(p[i]);
    if (c == kCr) break;
    if (c < 0x20 || c > 0x7E) return {Verdict::drop, 1};
    if (i + 2 >= kMaxReplyBytes) return {Verdict::drop, 1};
  }
  if (i + 1 >= avail) return {Verdict::need_more, std::min(i + 2, kMaxReplyBytes)};
  if (ch(p[i + 1]) != kLf) return {Verdict::drop, 1};
  const std::size_t len = i + 2;

  auto hex = [](char c) -> int {
    if (is_digit(c)) return c - '0';
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    return -1;
  };
  if (command == 'S' && len == kStatusReplyBytes) {
    const int h0 = hex(ch(p[3])), h1 = hex(ch(p[4])), h2 = hex(ch(p[5]));
    if (h0 >= 0 && h1 >= 0 && h2 >= 0) {
      out.kind = EventKind::status;
      FastrakStatus& s = out.status;
      s = {};
      s.station = is_digit(station) ? static_cast<std::uint8_t>(station - '0') : 0;
      s.flags = static_cast<std::uint16_t>((h0 << 8) | (h1 << 4) | h2);
      // The mode bits sit in the third hex digit (FreeVR, §3.6).
      s.binary = (h2 & 1) != 0;
      s.centimetres = (h2 & 2) != 0;
      s.continuous = (h2 & 8) != 0;
      return {Verdict::accept, len};
    }
  }
  out.kind = EventKind::reply;
  FastrakReply& r = out.reply;
  r = {};
  r.station = station;
  r.command = command;
  r.length = static_cast<std::uint8_t>(len);
  if (command == 'E') {
    r.is_error = true;
    // "*ERROR* EC <code>": find "EC" after the echoed input.
    for (std::size_t k = 3; k + 2 < len; ++k) {
      if (ch(p[k]) == 'E' && ch(p[k + 1]) == 'C') {
        std::size_t j = k + 2;
        while (j < len && ch(p[j]) == ' ') ++j;
        bool neg = false;
        if (j < len && ch(p[j]) == '-') {
          neg = true;
          ++j;
        }
        int code = 0;
        while (j < len && is_digit(ch(p[j])) && code < 1000) code = code * 10 + (ch(p[j++]) - '0');
        r.error_code = neg ? -code : code;
      }
    }
  }
  return {Verdict::accept, len};
}

}  // namespace twister::tracker
