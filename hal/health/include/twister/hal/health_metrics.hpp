// The station's health for whoever looks after a fleet of kiosks (issue 25): a plain
// struct of values, written in Prometheus' text exposition format (format 0.0.4:
// "# HELP" and "# TYPE" lines, metric names twister_*) to a file that node_exporter's
// textfile collector reads, and as one systemd STATUS= line.
//
// The file is replaced atomically (hal::PosixFileSink: a temporary in the same folder,
// fsync, rename), so the collector never reads half a file. Its first line is
// kMetricsMarker; MetricsFile::open() refuses a path that holds a file without it (a
// file that is not ours, e.g. another exporter's .prom) before anything is written.
// Formatting and writing never allocate (fixed buffers), so the station writes from
// its loop.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>

#include "twister/hal/expected.hpp"
#include "twister/hal/posix_file_sink.hpp"

namespace twister::hal {

// The first line of every metrics file we write.
inline constexpr char kMetricsMarker[] =
    "# twister-station health metrics (node_exporter textfile collector; replaced atomically)\n";

enum class TrackerHealth : std::uint8_t { starting = 0, streaming = 1, lost = 2 };
const char* tracker_health_name(TrackerHealth state);

struct HealthMetrics {
  TrackerHealth tracker = TrackerHealth::starting;
  double tracker_rate_hz = 0.0;          // poses used per second, both hands
  std::uint64_t visitors_today = 0;      // sculptures ended and archived today (exhibit)
  std::uint64_t strokes_committed = 0;   // since the station started
  std::uint64_t strokes_not_saved = 0;   // commits whose journal record was not made durable
  bool link_open = false;                // a display link is configured and listening
  bool display_connected = false;        // the main display is admitted
  std::uint32_t spectators = 0;          // read-only displays connected
  std::int64_t archive_free_bytes = -1;  // free space where the archive lives (-1: unknown)
  double uptime_s = 0.0;
  bool buttons_present = false;  // the button device is there
};

// Longest text format_prometheus() writes (with room to spare).
inline constexpr std::size_t kMetricsTextBytes = 4096;

// The exposition text (kMetricsMarker first) into `out`; returns its length, or 0
// when `out` is too small. No allocation.
std::size_t format_prometheus(const HealthMetrics& m, std::span<char> out);

// "STATUS=tracker streaming 120/s, strokes 12 (0 not saved), visitors 3, display
// connected, spectators 0, buttons ok" into `out` (NUL-terminated, for sd_notify);
// returns its length, or 0 when `out` is too small. No allocation.
std::size_t format_systemd_status(const HealthMetrics& m, std::span<char> out);

// Free bytes on the file system holding `path` (statvfs, f_bavail: what an
// unprivileged writer may use); -1 when it cannot be asked. No allocation.
std::int64_t free_bytes_at(const char* path);

class MetricsFile {
 public:
  // Checks `path` once, at start: its folder exists and is a folder, and the path
  // holds nothing, or a regular file that starts with kMetricsMarker (ours, from an
  // earlier run). Errors: invalid_argument (empty path, a directory), io_error (no
  // such folder), failed_precondition (a file that is not ours: names it and says why).
  static Expected<std::unique_ptr<MetricsFile>> open(const std::string& path);

  // Formats `m` and replaces the file atomically. No allocation. io_error /
  // failed_precondition (someone put another file there since): last_error() says why.
  Status write(const HealthMetrics& m);
  const char* last_error() const { return sink_.last_error(); }
  const std::string& path() const { return sink_.path(); }
  std::uint64_t writes() const { return writes_; }

  explicit MetricsFile(PosixFileSinkConfig config) : sink_(std::move(config)) {}

 private:
  PosixFileSink sink_;
  std::array<char, kMetricsTextBytes> text_{};
  std::uint64_t writes_ = 0;
};

}  // namespace twister::hal
