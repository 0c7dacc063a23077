#include "twister/hal/logger.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace twister::hal {
namespace {

using ports::LogArg;

bool is_conversion(char c) { return std::strchr("diuxXoeEfFgGaAcsp%", c) != nullptr; }

// Appends `text` (length n) to out[pos..]; keeps one byte for the terminator.
std::size_t append(std::span<char> out, std::size_t pos, const char* text, std::size_t n) {
  if (pos + 1 >= out.size()) return pos;
  const std::size_t room = out.size() - 1 - pos;
  const std::size_t take = n < room ? n : room;
  std::memcpy(out.data() + pos, text, take);
  return pos + take;
}

// Formats one conversion `spec` (from '%' to the conversion character, length
// modifiers dropped) with `arg`, converting the argument to what the spec expects.
std::size_t format_one(std::span<char> out, std::size_t pos, std::string_view spec,
                       const LogArg& arg) {
  std::array<char, 32> fmt{};
  const char conversion = spec.back();
  std::size_t n = 0;
  for (char c : spec.substr(0, spec.size() - 1)) {
    if (std::strchr("hljztL", c) == nullptr && n + 4 < fmt.size()) fmt[n++] = c;
  }
  std::array<char, 128> piece{};
  int written = 0;
  if (std::strchr("di", conversion) != nullptr) {
    fmt[n++] = 'l';
    fmt[n++] = 'l';
    fmt[n++] = conversion;
    const long long v = arg.kind == LogArg::Kind::signed_integer     ? arg.i
                        : arg.kind == LogArg::Kind::unsigned_integer ? static_cast<long long>(arg.u)
                        : arg.kind == LogArg::Kind::real             ? static_cast<long long>(arg.d)
                                                                     : 0;
    written = std::snprintf(piece.data(), piece.size(), fmt.data(), v);
  } else if (std::strchr("uxXo", conversion) != nullptr) {
    fmt[n++] = 'l';
    fmt[n++] = 'l';
    fmt[n++] = conversion;
    const unsigned long long v =
        arg.kind == LogArg::Kind::unsigned_integer ? arg.u
        : arg.kind == LogArg::Kind::signed_integer ? static_cast<unsigned long long>(arg.i)
        : arg.kind == LogArg::Kind::real           ? static_cast<unsigned long long>(arg.d)
                                                   : 0;
    written = std::snprintf(piece.data(), piece.size(), fmt.data(), v);
  } else if (std::strchr("eEfFgGaA", conversion) != nullptr) {
    fmt[n++] = conversion;
    const double v = arg.kind == LogArg::Kind::real               ? arg.d
                     : arg.kind == LogArg::Kind::signed_integer   ? static_cast<double>(arg.i)
                     : arg.kind == LogArg::Kind::unsigned_integer ? static_cast<double>(arg.u)
                                                                  : 0.0;
    written = std::snprintf(piece.data(), piece.size(), fmt.data(), v);
  } else {  // s, c, p: text (other kinds print as "?")
    const char* text = arg.kind == LogArg::Kind::text && arg.s != nullptr ? arg.s : "?";
    return append(out, pos, text, std::strlen(text));
  }
  if (written < 0) return pos;
  const auto length = static_cast<std::size_t>(written);
  return append(out, pos, piece.data(), length < piece.size() ? length : piece.size() - 1);
}

const char* level_word(LogLevel level) {
  switch (level) {
    case LogLevel::error:
      return "error: ";
    case LogLevel::warning:
      return "warning: ";
    default:
      return "";
  }
}

}  // namespace

std::size_t format_log_message(std::span<char> out, const char* format,
                               std::span<const ports::LogArg> args) {
  if (out.empty()) return 0;
  std::size_t pos = 0;
  std::size_t next_arg = 0;
  for (const char* p = format; *p != '\0';) {
    if (*p != '%') {
      const char* literal_end = std::strchr(p, '%');
      const std::size_t n =
          literal_end ? static_cast<std::size_t>(literal_end - p) : std::strlen(p);
      pos = append(out, pos, p, n);
      p += n;
      continue;
    }
    const char* start = p++;
    while (*p != '\0' && !is_conversion(*p)) ++p;
    if (*p == '\0') {
      pos = append(out, pos, start, static_cast<std::size_t>(p - start));
      break;
    }
    if (*p == '%') {
      pos = append(out, pos, "%", 1);
    } else if (next_arg < args.size()) {
      pos = format_one(out, pos, std::string_view(start, static_cast<std::size_t>(p - start + 1)),
                       args[next_arg++]);
    } else {
      pos = append(out, pos, "?", 1);
    }
    ++p;
  }
  out[pos] = '\0';
  return pos;
}

Logger::Logger(LoggerConfig config) : config_(std::move(config)) {}

bool Logger::do_enabled(LogLevel level) const {
  return static_cast<int>(level) <= static_cast<int>(config_.threshold);
}

void Logger::do_write(LogLevel level, const char* component, const char* format,
                      std::span<const ports::LogArg> args) {
  std::array<char, kMaxLine + 1> line{};
  const std::span<char> out(line.data(), kMaxLine);  // keeps room for the newline
  std::size_t pos = 0;
  if (config_.syslog_prefixes) {
    std::array<char, 8> prefix{};
    const int n = std::snprintf(prefix.data(), prefix.size(), "<%d>", static_cast<int>(level));
    pos = append(out, pos, prefix.data(), static_cast<std::size_t>(n));
  } else {
    pos = append(out, pos, config_.program.data(), config_.program.size());
    pos = append(out, pos, ": ", 2);
    const char* word = level_word(level);
    pos = append(out, pos, word, std::strlen(word));
  }
  if (component != nullptr && *component != '\0') {
    pos = append(out, pos, component, std::strlen(component));
    pos = append(out, pos, ": ", 2);
  }
  pos += format_log_message(out.subspan(pos), format, args);
  if (pos + 1 >= out.size()) std::memcpy(line.data() + kMaxLine - 3, "...", 3);
  line[pos] = '\n';
  std::size_t done = 0;
  while (done <= pos) {
    const ssize_t n = ::write(config_.fd, line.data() + done, pos + 1 - done);
    if (n <= 0) return;  // a log line is never worth blocking or failing for
    done += static_cast<std::size_t>(n);
  }
}

bool parse_log_level(std::string_view text, LogLevel& out) {
  for (const LogLevel l :
       {LogLevel::error, LogLevel::warning, LogLevel::notice, LogLevel::info, LogLevel::debug}) {
    if (text == log_level_name(l)) {
      out = l;
      return true;
    }
  }
  return false;
}

const char* log_level_name(LogLevel level) {
  switch (level) {
    case LogLevel::error:
      return "error";
    case LogLevel::warning:
      return "warning";
    case LogLevel::notice:
      return "notice";
    case LogLevel::info:
      return "info";
    case LogLevel::debug:
      return "debug";
  }
  return "unknown";
}

bool stderr_is_journal() {
  // sd-daemon(3): JOURNAL_STREAM is "DEVICE:INODE" of the stream systemd connected.
  const char* env = std::getenv("JOURNAL_STREAM");
  struct stat st {};
  if (env == nullptr || ::fstat(2, &st) != 0) return false;
  unsigned long long dev = 0;
  unsigned long long ino = 0;
  if (std::sscanf(env, "%llu:%llu", &dev, &ino) != 2) return false;
  return dev == static_cast<unsigned long long>(st.st_dev) &&
         ino == static_cast<unsigned long long>(st.st_ino);
}

Logger& process_log() {
  static Logger logger(LoggerConfig{"twister", LogLevel::notice, stderr_is_journal(), 2});
  return logger;
}

}  // namespace twister::hal
