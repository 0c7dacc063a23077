// Checkpoints written from the station's real loop (issue 11, item 10): with a
// checkpoint every record, the loop writes them a chunk per pass while strokes commit
// (freeze chains), allocates nothing doing so, and a restart from the last checkpoint
// gives the model a full replay of the journal gives. With [sculpt] refine on
// (checkpoint format 2), refined commits are checkpointed too, and a restart from the
// last checkpoint or from one in the middle of the run (records replayed after it)
// gives the full replay's model.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <string>

#include "allocation_counter.hpp"
#include "station_assembly.hpp"
#include "station_loop.hpp"
#include "station_test_support.hpp"
#include "twister/hal/logger.hpp"

namespace twister::station_app {
namespace {

namespace fs = std::filesystem;

StationFileConfig loop_config(const std::string& journal, const std::string& scenario,
                              const std::string& station_keys = "", const std::string& tail = "") {
  std::string text = station_test::sim_config(journal, scenario) + tail;
  text.insert(text.find("[tracker]"), "checkpoint_interval = 1\n" + station_keys);  // [station]
  const ConfigParseResult parsed = parse_station_config(text, "ckpt.toml");
  EXPECT_TRUE(parsed.ok()) << (parsed.errors.empty() ? "" : parsed.errors[0].to_string());
  return parsed.config;
}

TEST(StationCheckpointLoop, TheLoopWritesCheckpointsWithoutAllocatingAndRestartMatches) {
  const fs::path dir = fs::temp_directory_path() / ("ckpt_loop_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string journal = (dir / "j.twj").string();
  const std::string scenario = (dir / "chains.scn").string();
  station_test::write_file(scenario, station_test::chain_scenario(4, 3));
  const StationFileConfig config = loop_config(journal, scenario);
  std::uint64_t final_checksum = 0;
  {
    auto assembled = assemble_station(config, {TWISTER_DEPLOY_DIR, ""});
    ASSERT_TRUE(assembled) << assembled.error().message;
    StationParts& parts = **assembled;
    hal::Logger log({"twister-station", hal::LogLevel::warning, false, 2});
    StationLoop loop(*parts.core, parts.backends, parts.display, log,
                     make_loop_config(config, 0.0, parts.backends));
    ASSERT_TRUE(loop.start());
    ports::Clock& clock = *parts.backends.clock;
    const ports::TimestampUs t0 = clock.now_us();
    while (clock.now_us() - t0 < 2'500'000) ASSERT_TRUE(loop.step());  // tracker start-up
    std::size_t allocations = 0;
    {
      test::AllocationCounter counter;
      while (loop.step()) {
      }
      allocations = counter.count();
    }
    const station::StationCounters& c = parts.core->counters();
    EXPECT_EQ(allocations, 0u);
    EXPECT_EQ(c.events.strokes_committed, 16u);  // 4 strokes x (3 freezes + release)
    EXPECT_GE(c.events.checkpoints_written, 4u);
    EXPECT_EQ(c.events.checkpoints_failed, 0u);
    std::printf("in-loop checkpoints: %llu written, %llu restarted by a commit\n",
                static_cast<unsigned long long>(c.events.checkpoints_written),
                static_cast<unsigned long long>(c.checkpoints_restarted));
    ASSERT_TRUE(loop.finish().ok());
    final_checksum = parts.core->mesh().checksum();
  }
  // A restart restores the final checkpoint (nothing left to replay) and holds the
  // very model; a full replay (the checkpoint removed) agrees.
  auto again = assemble_station(config, {TWISTER_DEPLOY_DIR, ""});
  ASSERT_TRUE(again) << again.error().message;
  EXPECT_EQ((*again)->core->recovery().checkpoint, station::JournalRecovery::Checkpoint::used);
  EXPECT_EQ((*again)->core->recovery().replayed, 0u);
  EXPECT_EQ((*again)->core->mesh().checksum(), final_checksum);
  again = hal::make_error(StatusCode::unavailable, "released");
  fs::remove(journal + ".ckpt");
  auto full = assemble_station(config, {TWISTER_DEPLOY_DIR, ""});
  ASSERT_TRUE(full) << full.error().message;
  EXPECT_EQ((*full)->core->recovery().replayed, 16u);
  EXPECT_EQ((*full)->core->mesh().checksum(), final_checksum);
  fs::remove_all(dir);
}

// A restart of `config` with `checkpoint` as its checkpoint file (none: removed).
struct Restart {
  station::JournalRecovery::Checkpoint use = station::JournalRecovery::Checkpoint::none;
  std::uint64_t replayed = 0;
  std::uint64_t checksum = 0;
};

Restart restart(const StationFileConfig& config, const std::string& checkpoint) {
  const std::string ckpt = config.station.journal + ".ckpt";
  fs::remove(ckpt);
  if (!checkpoint.empty()) fs::copy_file(checkpoint, ckpt);
  auto parts = assemble_station(config, {TWISTER_DEPLOY_DIR, ""});
  EXPECT_TRUE(parts) << parts.error().message;
  if (!parts) return {};
  const station::JournalRecovery& r = (*parts)->core->recovery();
  return {r.checkpoint, r.replayed, (*parts)->core->mesh().checksum()};
}

TEST(StationCheckpointLoop, WithRefinementOnRefinedCommitsAreCheckpointedAndRestartsMatch) {
  const fs::path dir = fs::temp_directory_path() / ("ckpt_refine_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string journal = (dir / "j.twj").string();
  const std::string scenario = (dir / "strokes.scn").string();
  station_test::write_file(scenario, station_test::chain_scenario(4, 0));  // plain strokes
  const StationFileConfig config =
      loop_config(journal, scenario, "spare_vertices = 20000\n",
                  "[sculpt]\nrefine = true\nrefine_threshold_m = 0.0005\n");
  const std::string middle = (dir / "middle.ckpt").string();
  std::uint64_t final_checksum = 0;
  {
    auto assembled = assemble_station(config, {TWISTER_DEPLOY_DIR, ""});
    ASSERT_TRUE(assembled) << assembled.error().message;
    StationParts& parts = **assembled;
    hal::Logger log({"twister-station", hal::LogLevel::warning, false, 2});
    StationLoop loop(*parts.core, parts.backends, parts.display, log,
                     make_loop_config(config, 0.0, parts.backends));
    ASSERT_TRUE(loop.start());
    ports::Clock& clock = *parts.backends.clock;
    const ports::TimestampUs t0 = clock.now_us();
    while (clock.now_us() - t0 < 2'500'000) ASSERT_TRUE(loop.step());  // tracker start-up
    const station::StationCounters& c = parts.core->counters();
    const std::size_t start_vertices = parts.core->mesh().vertex_count();
    std::size_t allocations = 0;
    for (bool more = true; more;) {
      {
        test::AllocationCounter counter;
        more = loop.step();
        allocations += counter.count();
      }
      // The second checkpoint, kept for a restart with records after it.
      if (c.events.checkpoints_written == 2 && !fs::exists(middle))
        fs::copy_file(journal + ".ckpt", middle);
    }
    EXPECT_EQ(allocations, 0u);
    EXPECT_EQ(c.events.strokes_committed, 4u);
    EXPECT_EQ(c.events.refined_commits, 4u);
    EXPECT_GE(c.events.checkpoints_written, 4u);
    EXPECT_EQ(c.events.checkpoints_failed, 0u);
    EXPECT_EQ(c.events.journal_errors, 0u);
    ASSERT_TRUE(loop.finish().ok());
    EXPECT_GT(parts.core->mesh().vertex_count(), start_vertices);
    final_checksum = parts.core->mesh().checksum();
    std::printf("refined: %llu commits, %llu checkpoints written, %zu -> %zu vertices\n",
                static_cast<unsigned long long>(c.events.refined_commits),
                static_cast<unsigned long long>(c.events.checkpoints_written), start_vertices,
                parts.core->mesh().vertex_count());
  }
  const std::string last = (dir / "last.ckpt").string();
  fs::copy_file(journal + ".ckpt", last);
  const Restart from_last = restart(config, last);
  EXPECT_EQ(from_last.use, station::JournalRecovery::Checkpoint::used);
  EXPECT_EQ(from_last.replayed, 0u);
  EXPECT_EQ(from_last.checksum, final_checksum);
  ASSERT_TRUE(fs::exists(middle));
  const Restart from_middle = restart(config, middle);
  EXPECT_EQ(from_middle.use, station::JournalRecovery::Checkpoint::used);
  EXPECT_GT(from_middle.replayed, 0u);
  EXPECT_EQ(from_middle.checksum, final_checksum);
  const Restart full = restart(config, "");
  EXPECT_EQ(full.use, station::JournalRecovery::Checkpoint::none);
  EXPECT_EQ(full.replayed, 4u);
  EXPECT_EQ(full.checksum, final_checksum);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace twister::station_app
