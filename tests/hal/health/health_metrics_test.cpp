// The metrics file: Prometheus text that promtool accepts, the values we put in,
// atomic replace of our own file only, no allocation per write; the STATUS= line.
#include "twister/hal/health_metrics.hpp"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <regex>
#include <string>

#include "allocation_counter.hpp"
#include "prometheus_text.hpp"

namespace twister::hal {
namespace {

namespace fs = std::filesystem;

struct ToolRun {
  int exit_code = -1;
  std::string out;
};

ToolRun run(const std::string& command) {
  ToolRun r;
  FILE* p = popen((command + " 2>&1").c_str(), "r");
  if (p == nullptr) return r;
  std::array<char, 512> buf{};
  while (fgets(buf.data(), buf.size(), p) != nullptr) r.out += buf.data();
  const int status = pclose(p);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

class HealthMetricsFile : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("twister_health_test_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

HealthMetrics known_run() {
  HealthMetrics m;
  m.tracker = TrackerHealth::streaming;
  m.tracker_rate_hz = 119.5;
  m.visitors_today = 7;
  m.strokes_committed = 42;
  m.strokes_not_saved = 1;
  m.link_open = true;
  m.display_connected = true;
  m.spectators = 2;
  m.archive_free_bytes = 123456789012;
  m.uptime_s = 3600.25;
  m.buttons_present = false;
  return m;
}

TEST_F(HealthMetricsFile, PromtoolAcceptsItAndTheNumbersAreOurs) {
  const fs::path path = dir_ / "twister.prom";
  auto file = MetricsFile::open(path.string());
  ASSERT_TRUE(file) << file.error().message;
  ASSERT_TRUE((*file)->write(known_run()).ok()) << (*file)->last_error();
  const std::string text = slurp(path);
  EXPECT_EQ(text.rfind(kMetricsMarker, 0), 0U);
  const ToolRun check = run(std::string(TWISTER_PROMTOOL) + " check metrics < " + path.string());
  EXPECT_EQ(check.exit_code, 0) << check.out << text;
  EXPECT_EQ(check.out, "") << "promtool's lint findings";
  EXPECT_EQ(test::prometheus_sample(text, "twister_tracker_state{state=\"streaming\"}"), 1.0);
  EXPECT_EQ(test::prometheus_sample(text, "twister_tracker_state{state=\"lost\"}"), 0.0);
  EXPECT_EQ(test::prometheus_sample(text, "twister_tracker_rate_hertz"), 119.5);
  EXPECT_EQ(test::prometheus_sample(text, "twister_visitors_today"), 7.0);
  EXPECT_EQ(test::prometheus_sample(text, "twister_strokes_committed_total"), 42.0);
  EXPECT_EQ(test::prometheus_sample(text, "twister_strokes_not_saved_total"), 1.0);
  EXPECT_EQ(test::prometheus_sample(text, "twister_link_open"), 1.0);
  EXPECT_EQ(test::prometheus_sample(text, "twister_display_connected"), 1.0);
  EXPECT_EQ(test::prometheus_sample(text, "twister_spectators"), 2.0);
  EXPECT_EQ(test::prometheus_sample(text, "twister_archive_free_bytes"), 123456789012.0);
  EXPECT_EQ(test::prometheus_sample(text, "twister_uptime_seconds"), 3600.25);
  EXPECT_EQ(test::prometheus_sample(text, "twister_buttons_present"), 0.0);
  // Every metric has its HELP and TYPE.
  const std::regex sample_line(R"(\n(twister_[a-z_]+)[{ ])");
  for (auto it = std::sregex_iterator(text.begin(), text.end(), sample_line);
       it != std::sregex_iterator(); ++it) {
    const std::string name = (*it)[1];
    EXPECT_NE(text.find("# HELP " + name + " "), std::string::npos) << name;
    EXPECT_NE(text.find("# TYPE " + name + " "), std::string::npos) << name;
  }
}

TEST_F(HealthMetricsFile, ReplacesItsOwnFileAtomicallyWithoutAllocating) {
  const fs::path path = dir_ / "twister.prom";
  auto file = MetricsFile::open(path.string());
  ASSERT_TRUE(file);
  HealthMetrics m = known_run();
  ASSERT_TRUE((*file)->write(m).ok());
  struct stat before {};
  ASSERT_EQ(::stat(path.c_str(), &before), 0);
  m.strokes_committed = 43;
  EXPECT_NO_ALLOCATIONS({ ASSERT_TRUE((*file)->write(m).ok()) << (*file)->last_error(); });
  struct stat after {};
  ASSERT_EQ(::stat(path.c_str(), &after), 0);
  EXPECT_NE(before.st_ino, after.st_ino);  // a new file renamed into place
  EXPECT_EQ(test::prometheus_sample(slurp(path), "twister_strokes_committed_total"), 43.0);
  EXPECT_EQ((*file)->writes(), 2U);
  // No temporaries left in the collector's folder.
  std::size_t files = 0;
  for (const auto& entry : fs::directory_iterator(dir_)) {
    (void)entry;
    ++files;
  }
  EXPECT_EQ(files, 1U);
  // A later run takes its own file over.
  auto again = MetricsFile::open(path.string());
  ASSERT_TRUE(again) << again.error().message;
  EXPECT_TRUE((*again)->write(m).ok());
}

TEST_F(HealthMetricsFile, RefusesAFileThatIsNotOurs) {
  const fs::path path = dir_ / "other.prom";
  std::ofstream(path) << "# HELP node_thing x\n# TYPE node_thing gauge\nnode_thing 1\n";
  auto refused = MetricsFile::open(path.string());
  ASSERT_FALSE(refused);
  EXPECT_EQ(refused.error().status.code(), StatusCode::failed_precondition);
  EXPECT_NE(refused.error().message.find("not one twister-station wrote"), std::string::npos)
      << refused.error().message;
  EXPECT_NE(refused.error().message.find(path.string()), std::string::npos);
  EXPECT_EQ(slurp(path).rfind("# HELP node_thing", 0), 0U);  // untouched
  auto folder = MetricsFile::open((dir_ / "missing" / "x.prom").string());
  ASSERT_FALSE(folder);
  EXPECT_NE(folder.error().message.find("does not exist"), std::string::npos);
  auto directory = MetricsFile::open(dir_.string());
  ASSERT_FALSE(directory);
  EXPECT_NE(directory.error().message.find("a directory"), std::string::npos);
  // An empty file holds nothing to lose: taken.
  const fs::path empty = dir_ / "empty.prom";
  std::ofstream{empty};
  EXPECT_TRUE(MetricsFile::open(empty.string()));
  // A foreign file put there after open is refused at the write, not replaced.
  const fs::path later = dir_ / "later.prom";
  auto file = MetricsFile::open(later.string());
  ASSERT_TRUE(file);
  std::ofstream(later) << "someone else's\n";
  EXPECT_FALSE((*file)->write(known_run()).ok());
  EXPECT_EQ(slurp(later), "someone else's\n");
}

TEST(HealthStatusLine, SaysWhatMatters) {
  std::array<char, 256> out{};
  const std::size_t n = format_systemd_status(known_run(), out);
  ASSERT_GT(n, 0U);
  EXPECT_STREQ(out.data(),
               "STATUS=tracker streaming 120/s, strokes 42 (1 not saved), visitors 7, display "
               "connected, spectators 2, buttons missing");
  std::array<char, 16> small{};
  EXPECT_EQ(format_systemd_status(known_run(), small), 0U);
  std::array<char, 64> tiny{};
  EXPECT_EQ(format_prometheus(known_run(), tiny), 0U);
}

}  // namespace
}  // namespace twister::hal
