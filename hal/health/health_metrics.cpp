#include "twister/hal/health_metrics.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <sys/statvfs.h>
#include <unistd.h>

#include <cerrno>
#include <cstdarg>
#include <cstdio>
#include <cstring>
#include <filesystem>

namespace twister::hal {
namespace {

// Appends printf output to a fixed buffer; remembers overflow.
class Text {
 public:
  explicit Text(std::span<char> out) : out_(out) {}
  __attribute__((format(printf, 2, 3))) void put(const char* format, ...) {
    if (overflow_ || out_.empty()) {
      overflow_ = true;
      return;
    }
    va_list args;
    va_start(args, format);
    const int n = std::vsnprintf(out_.data() + used_, out_.size() - used_, format, args);
    va_end(args);
    if (n < 0 || static_cast<std::size_t>(n) >= out_.size() - used_) {
      overflow_ = true;
      return;
    }
    used_ += static_cast<std::size_t>(n);
  }
  std::size_t length() const { return overflow_ ? 0 : used_; }

 private:
  std::span<char> out_;
  std::size_t used_ = 0;
  bool overflow_ = false;
};

void gauge(Text& t, const char* name, const char* help, double value) {
  t.put("# HELP %s %s\n# TYPE %s gauge\n%s %.17g\n", name, help, name, name, value);
}

void counter(Text& t, const char* name, const char* help, std::uint64_t value) {
  t.put("# HELP %s %s\n# TYPE %s counter\n%s %llu\n", name, help, name, name,
        static_cast<unsigned long long>(value));
}

}  // namespace

const char* tracker_health_name(TrackerHealth state) {
  switch (state) {
    case TrackerHealth::starting:
      return "starting";
    case TrackerHealth::streaming:
      return "streaming";
    case TrackerHealth::lost:
      return "lost";
  }
  return "unknown";
}

std::size_t format_prometheus(const HealthMetrics& m, std::span<char> out) {
  Text t(out);
  t.put("%s", kMetricsMarker);
  t.put(
      "# HELP twister_tracker_state The tracker's state: 1 for the state it is in.\n"
      "# TYPE twister_tracker_state gauge\n");
  for (const TrackerHealth s :
       {TrackerHealth::starting, TrackerHealth::streaming, TrackerHealth::lost}) {
    t.put("twister_tracker_state{state=\"%s\"} %d\n", tracker_health_name(s),
          s == m.tracker ? 1 : 0);
  }
  gauge(t, "twister_tracker_rate_hertz", "Tracker poses used per second, both hands.",
        m.tracker_rate_hz);
  gauge(t, "twister_visitors_today",
        "Visitors whose sculpture ended and was archived today (UTC day).",
        static_cast<double>(m.visitors_today));
  counter(t, "twister_strokes_committed_total", "Strokes committed since the station started.",
          m.strokes_committed);
  counter(t, "twister_strokes_not_saved_total",
          "Commits whose journal record could not be made durable since the station started.",
          m.strokes_not_saved);
  gauge(t, "twister_link_open", "1 when the display link is configured and listening.",
        m.link_open ? 1.0 : 0.0);
  gauge(t, "twister_display_connected", "1 when the main display is connected and admitted.",
        m.display_connected ? 1.0 : 0.0);
  gauge(t, "twister_spectators", "Read-only displays connected.",
        static_cast<double>(m.spectators));
  gauge(t, "twister_archive_free_bytes",
        "Free bytes on the file system of the archive (-1: unknown).",
        static_cast<double>(m.archive_free_bytes));
  gauge(t, "twister_uptime_seconds", "Seconds since the station started.", m.uptime_s);
  gauge(t, "twister_buttons_present", "1 when the button device is there.",
        m.buttons_present ? 1.0 : 0.0);
  return t.length();
}

std::size_t format_systemd_status(const HealthMetrics& m, std::span<char> out) {
  Text t(out);
  t.put(
      "STATUS=tracker %s %.0f/s, strokes %llu (%llu not saved), visitors %llu, display %s, "
      "spectators %u, buttons %s",
      tracker_health_name(m.tracker), m.tracker_rate_hz,
      static_cast<unsigned long long>(m.strokes_committed),
      static_cast<unsigned long long>(m.strokes_not_saved),
      static_cast<unsigned long long>(m.visitors_today),
      m.display_connected ? "connected" : (m.link_open ? "waiting" : "none"), m.spectators,
      m.buttons_present ? "ok" : "missing");
  return t.length();
}

std::int64_t free_bytes_at(const char* path) {
  struct statvfs st {};
  if (::statvfs(path, &st) != 0) return -1;
  return static_cast<std::int64_t>(st.f_bavail) * static_cast<std::int64_t>(st.f_frsize);
}

Expected<std::unique_ptr<MetricsFile>> MetricsFile::open(const std::string& path) {
  if (path.empty()) return make_error(StatusCode::invalid_argument, "metrics file: empty path");
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::path folder = fs::path(path).parent_path();
  if (folder.empty()) folder = ".";
  if (!fs::is_directory(folder, ec)) {
    return make_error(StatusCode::io_error, "metrics file " + path + ": the folder " +
                                                folder.string() + " does not exist");
  }
  struct stat st {};
  if (::lstat(path.c_str(), &st) == 0) {
    if (!S_ISREG(st.st_mode)) {
      return make_error(
          S_ISDIR(st.st_mode) ? StatusCode::invalid_argument : StatusCode::failed_precondition,
          "metrics file " + path + " is " + file_type_name(st.st_mode) + "; it is not replaced");
    }
    const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_NOFOLLOW | O_CLOEXEC);
    char head[sizeof kMetricsMarker] = {};
    const ssize_t n = fd >= 0 ? ::read(fd, head, sizeof kMetricsMarker - 1) : -1;
    if (fd >= 0) ::close(fd);
    if (n != 0 && (n != static_cast<ssize_t>(sizeof kMetricsMarker - 1) ||
                   std::memcmp(head, kMetricsMarker, sizeof kMetricsMarker - 1) != 0)) {
      return make_error(StatusCode::failed_precondition,
                        "metrics file " + path +
                            " exists and is not one twister-station wrote (its first line is "
                            "not \"# twister-station health metrics ...\"); it is not replaced: "
                            "choose another [health] metrics_file or remove it");
    }
  }
  PosixFileSinkConfig config;
  config.path = path;
  config.replace = PosixFileSinkConfig::Replace::own_magic;
  const auto* marker = reinterpret_cast<const std::byte*>(kMetricsMarker);
  config.magic.assign(marker, marker + sizeof kMetricsMarker - 1);
  return std::make_unique<MetricsFile>(std::move(config));
}

Status MetricsFile::write(const HealthMetrics& m) {
  const std::size_t n = format_prometheus(m, text_);
  if (n == 0) return StatusCode::resource_exhausted;
  Status s = sink_.begin();
  if (s.ok()) s = sink_.write(std::as_bytes(std::span(text_.data(), n)));
  if (s.ok()) s = sink_.commit();
  if (!s.ok()) {
    sink_.abort();
    return s;
  }
  ++writes_;
  return ok_status();
}

}  // namespace twister::hal
