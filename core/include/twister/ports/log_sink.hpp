// LogSink port: where core parts send log messages. Core never formats text: a
// message is a printf-style format (a string literal, static storage) plus its
// arguments as values; the sink (the program's logger) decides whether the level
// is shown and formats it. No heap, no I/O in core. Deferred formatting like this
// is the firmware habit (pw_log, defmt): the cost of a filtered-out message is a
// level comparison.
#pragma once

#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <span>

namespace twister::ports {

// Levels are syslog priorities (sd-daemon(3) prefixes <3> .. <7>).
enum class LogLevel : std::uint8_t { error = 3, warning = 4, notice = 5, info = 6, debug = 7 };

// One argument of a message, matched in order with the format's conversions:
// %d %i (signed), %u %x %X (unsigned, any length modifier), %f %e %g (real),
// %s (text).
struct LogArg {
  enum class Kind : std::uint8_t { signed_integer, unsigned_integer, real, text };
  Kind kind = Kind::signed_integer;
  union {
    std::int64_t i;
    std::uint64_t u;
    double d;
    const char* s;
  };

  LogArg(int v) : kind(Kind::signed_integer), i(v) {}              // NOLINT: implicit by design
  LogArg(long v) : kind(Kind::signed_integer), i(v) {}             // NOLINT
  LogArg(long long v) : kind(Kind::signed_integer), i(v) {}        // NOLINT
  LogArg(unsigned v) : kind(Kind::unsigned_integer), u(v) {}       // NOLINT
  LogArg(unsigned long v) : kind(Kind::unsigned_integer), u(v) {}  // NOLINT
  LogArg(unsigned long long v) : kind(Kind::unsigned_integer), u(v) {}  // NOLINT
  LogArg(double v) : kind(Kind::real), d(v) {}                          // NOLINT
  LogArg(const char* v) : kind(Kind::text), s(v) {}                     // NOLINT
};

class LogSink {
 public:
  virtual ~LogSink() = default;

  // Whether a message at `level` would be shown (skip expensive arguments).
  bool enabled(LogLevel level) const { return do_enabled(level); }

  // `component` names the part ("journal", "tracker"); `format` and the strings
  // among `args` must stay valid for the call only.
  void write(LogLevel level, const char* component, const char* format,
             std::initializer_list<LogArg> args = {}) {
    if (do_enabled(level)) do_write(level, component, format, {args.begin(), args.size()});
  }

 private:
  virtual bool do_enabled(LogLevel level) const = 0;
  virtual void do_write(LogLevel level, const char* component, const char* format,
                        std::span<const LogArg> args) = 0;
};

// A sink that drops everything (the default where no log is wanted).
class NullLogSink final : public LogSink {
 private:
  bool do_enabled(LogLevel) const override { return false; }
  void do_write(LogLevel, const char*, const char*, std::span<const LogArg>) override {}
};

}  // namespace twister::ports
