// Logger: the programs' logging facade and the LogSink of the core they drive.
// Every line has a level and a component: "twister-station: tracker: lost" or, at
// warning and error, "twister-station: error: journal: ...". Under systemd (stderr
// connected to the journal, JOURNAL_STREAM) lines carry sd-daemon(3) priority
// prefixes instead ("<4>tracker: lost") so journald stores their levels.
// Messages below the threshold cost a comparison. Formatting happens in a fixed
// buffer and each line is one write(2): no heap, so the station may log from its
// steady-state loop. Thread-compatible (one line = one write).
#pragma once

#include <string>
#include <string_view>
#include <utility>

#include "twister/ports/log_sink.hpp"

namespace twister::hal {

using ports::LogLevel;

struct LoggerConfig {
  std::string program;                    // prefix of plain lines ("twister-station")
  LogLevel threshold = LogLevel::notice;  // lines above it (less severe) are dropped
  bool syslog_prefixes = false;           // "<N>" instead of the program name
  int fd = 2;                             // where lines go (stderr)
};

class Logger final : public ports::LogSink {
 public:
  // Longest line written; longer messages are cut (marked with "...").
  static constexpr std::size_t kMaxLine = 1024;

  explicit Logger(LoggerConfig config);

  void configure(LoggerConfig config) { config_ = std::move(config); }
  void set_threshold(LogLevel level) { config_.threshold = level; }
  LogLevel threshold() const { return config_.threshold; }

  template <typename... Args>
  void error(const char* component, const char* format, Args... args) {
    write(LogLevel::error, component, format, {ports::LogArg(args)...});
  }
  template <typename... Args>
  void warning(const char* component, const char* format, Args... args) {
    write(LogLevel::warning, component, format, {ports::LogArg(args)...});
  }
  template <typename... Args>
  void notice(const char* component, const char* format, Args... args) {
    write(LogLevel::notice, component, format, {ports::LogArg(args)...});
  }
  template <typename... Args>
  void info(const char* component, const char* format, Args... args) {
    write(LogLevel::info, component, format, {ports::LogArg(args)...});
  }
  template <typename... Args>
  void debug(const char* component, const char* format, Args... args) {
    write(LogLevel::debug, component, format, {ports::LogArg(args)...});
  }

 private:
  bool do_enabled(LogLevel level) const override;
  void do_write(LogLevel level, const char* component, const char* format,
                std::span<const ports::LogArg> args) override;

  LoggerConfig config_;
};

// Formats `format` with `args` into `out` (always NUL-terminated); returns the
// length. A conversion without an argument prints "?"; extra arguments are ignored.
std::size_t format_log_message(std::span<char> out, const char* format,
                               std::span<const ports::LogArg> args);

// "error", "warning", "notice", "info", "debug" <-> LogLevel; false when unknown.
bool parse_log_level(std::string_view text, LogLevel& out);
const char* log_level_name(LogLevel level);

// True when stderr is the systemd journal's stream (JOURNAL_STREAM matches it).
bool stderr_is_journal();

// The process's logger (a program sets it up once in main; default: notice, plain).
Logger& process_log();

}  // namespace twister::hal
