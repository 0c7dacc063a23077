// Refinement at the station (issue 13): the [sculpt] keys refine and
// refine_threshold_m, the log lines of a refined commit and of one stopped at the
// mesh's capacity, the spare triangles that come with station.spare_vertices, and
// twister-station as a process: a two-hand stroke refines the sphere, the capacity
// stop is reported, and the journal gives the same mesh to `twister replay` and to
// the station's own start-up replay.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "config/station_config.hpp"
#include "station_assembly.hpp"
#include "station_log.hpp"
#include "station_setup.hpp"
#include "twister/hal/logger.hpp"
#include "twister/hal/posix_file_storage.hpp"
#include "twister/journal/journal_reader.hpp"
#include "twister/mesh/mesh_refiner.hpp"

namespace twister::station_app {
namespace {

using ::testing::HasSubstr;

constexpr const char* kBase =
    "[station]\njournal = \"/tmp/j.bin\"\nmesh = \"m.obj\"\n"
    "[tracker]\nbackend = \"serial\"\n[tracker.serial]\ndevice = \"/dev/twister-fastrak\"\n"
    "[buttons]\nbackend = \"gpiod\"\n[buttons.gpiod]\nlines = [17, 27, 22, 23, 24, 25]\n";

ConfigParseResult parse(const std::string& sculpt) {
  return parse_station_config(kBase + sculpt, "t.toml");
}

TEST(RefineStation, SculptKeys) {
  // The defaults: on at session::kDefaultRefineThresholdM into
  // session::kDefaultSpareVertices (what `twister replay` assumes too).
  const auto none = parse("");
  ASSERT_TRUE(none.ok());
  EXPECT_TRUE(none.config.sculpt.refine);
  EXPECT_EQ(none.config.sculpt.refine_threshold_m, session::kDefaultRefineThresholdM);
  EXPECT_EQ(none.config.station.spare_vertices, session::kDefaultSpareVertices);
  EXPECT_TRUE(make_station_setup(none.config)->sculpt.refine.enabled);
  const auto off = parse("[sculpt]\nrefine = false\n");
  ASSERT_TRUE(off.ok());
  EXPECT_FALSE(make_station_setup(off.config)->sculpt.refine.enabled);
  const auto on = parse("[sculpt]\nrefine = true\nrefine_threshold_m = 0.0025\n");
  ASSERT_TRUE(on.ok());
  const auto setup = make_station_setup(on.config);
  ASSERT_TRUE(setup);
  EXPECT_TRUE(setup->sculpt.refine.enabled);
  EXPECT_EQ(setup->sculpt.refine.threshold_m, 0.0025);
  const auto bad = parse("[sculpt]\nrefine = 1\nrefine_threshold_m = 0.5\n");
  ASSERT_EQ(bad.errors.size(), 2u);
  EXPECT_THAT(bad.errors[0].to_string(), HasSubstr("sculpt.refine: expected true or false"));
  EXPECT_THAT(bad.errors[1].to_string(),
              HasSubstr("sculpt.refine_threshold_m: expected a number from 1e-05 to 0.1, got 0.5"));
}

struct Line {
  ports::LogLevel level;
  std::string component;
  std::string text;
};

class RecordingLog final : public ports::LogSink {
 public:
  std::vector<Line> lines;

 private:
  bool do_enabled(ports::LogLevel) const override { return true; }
  void do_write(ports::LogLevel level, const char* component, const char* format,
                std::span<const ports::LogArg> args) override {
    std::array<char, 512> text{};
    hal::format_log_message(text, format, args);
    lines.push_back({level, component, text.data()});
  }
};

TEST(RefineStation, LogLines) {
  session::SessionEvent e = session::make_event(session::SessionEventKind::refined, 0,
                                                session::payload::Refinement{3, 1234});
  RecordingLog log;
  log_station_event(e, log);
  ASSERT_EQ(log.lines.size(), 1u);
  EXPECT_EQ(log.lines[0].level, ports::LogLevel::info);
  EXPECT_EQ(log.lines[0].component, "refine");
  EXPECT_EQ(log.lines[0].text, "journal record 3 refined: 1234 vertices added");
  e = session::make_event(session::SessionEventKind::refine_stopped, 0,
                          session::payload::RefinementStop{3, mesh::RefineStop::vertex_capacity},
                          StatusCode::resource_exhausted);
  log_station_event(e, log);
  ASSERT_EQ(log.lines.size(), 2u);
  EXPECT_EQ(log.lines[1].level, ports::LogLevel::warning);
  EXPECT_EQ(log.lines[1].text,
            "journal record 3: refinement stopped, the mesh's vertex capacity is used up "
            "(station.spare_vertices); the stroke is committed and the mesh conforming, some "
            "edges stay coarser than sculpt.refine_threshold_m");
  EXPECT_EQ(session::session_event_kind_name(e.kind), std::string("refine_stopped"));
}

TEST(RefineStation, SpareVerticesComeWithTwiceAsManyTriangles) {
  auto model = load_station_mesh(TWISTER_DEPLOY_DIR "/sim_sphere.obj", 1000);
  ASSERT_TRUE(model);
  const mesh::Mesh& m = (*model)->mesh();
  EXPECT_EQ(m.vertex_capacity(), m.vertex_count() + 1000);
  EXPECT_EQ(m.triangle_capacity(), m.triangle_count() + 2000);
}

// twister-station and twister as processes --------------------------------------

struct ProcessRun {
  int exit_code = -1;
  std::string output;
};

ProcessRun run(const std::string& cmd) {
  ProcessRun r;
  FILE* p = ::popen((cmd + " 2>&1").c_str(), "r");
  if (p == nullptr) return r;
  std::array<char, 512> buf{};
  while (std::fgets(buf.data(), buf.size(), p) != nullptr) r.output += buf.data();
  const int status = ::pclose(p);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

std::string temp_path(const std::string& name) {
  return "/tmp/twister_refine_station_" + std::to_string(::getpid()) + "_" + name;
}

// The deploy sphere, the two-hand scenario (or the idle one), refinement on.
std::string station_config(const std::string& journal, int spare, const char* scenario) {
  const std::string path = temp_path(std::string("station_") + scenario + ".toml");
  std::ofstream(path) << "[station]\njournal = \"" << journal << "\"\nmesh = \"" TWISTER_DEPLOY_DIR
                      << "/sim_sphere.obj\"\nspare_vertices = " << spare
                      << "\n[tracker]\nbackend = \"sim\"\n[tracker.sim]\n"
                      << (std::string(scenario) == "idle"
                              ? std::string("scenario = \"idle\"\n")
                              : std::string("scenario_file = \"" TWISTER_SCENARIO_DIR
                                            "/sim_two_hands.scn\"\n"))
                      << "time = \"virtual\"\n[buttons]\nbackend = \"sim\"\n"
                      << "[sculpt]\nrefine = true\nrefine_threshold_m = 0.0003\n";
  return path;
}

std::string final_checksum(const std::string& output) {
  const std::string key = "twister-station: mesh checksum ";
  const auto at = output.rfind(key);
  return at == std::string::npos ? "" : output.substr(at + key.size(), 16);
}

std::vector<journal::JournalRecord> read_journal(const std::string& path) {
  hal::PosixFileStorage storage;
  EXPECT_TRUE(storage.open({.path = path, .create_if_missing = false}).ok());
  journal::JournalReader reader(storage);
  EXPECT_TRUE(reader.open().ok());
  std::vector<journal::JournalRecord> out;
  for (auto r = reader.next(); r.ok(); r = reader.next()) out.push_back(*r);
  return out;
}

TEST(RefineStation, AtCapacityTheStationSaysWhyAndCarriesOn) {
  const std::string journal = temp_path("small.bin");
  ::unlink(journal.c_str());
  ::unlink((journal + ".ckpt").c_str());  // its checkpoint
  const ProcessRun r = run(std::string(TWISTER_STATION_BIN) + " --config " +
                           station_config(journal, 25, "two_hands"));
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("refine: on: edges split above 0.0003 m, room for 25 more"));
  EXPECT_THAT(r.output, HasSubstr("twister-station: warning: refine: journal record 0: "
                                  "refinement stopped, the mesh's vertex capacity is used up"));
  EXPECT_THAT(r.output, HasSubstr("strokes committed 1"));
  ASSERT_EQ(read_journal(journal).size(), 1u);
  ::unlink(journal.c_str());
  ::unlink((journal + ".ckpt").c_str());  // its checkpoint
}

TEST(RefineStation, StartUpReplayAndTwisterReplayAgreeOnTheRefinedMesh) {
  const std::string journal = temp_path("big.bin");
  ::unlink(journal.c_str());
  ::unlink((journal + ".ckpt").c_str());  // its checkpoint
  const ProcessRun live = run(std::string(TWISTER_STATION_BIN) + " --log-level info --config " +
                              station_config(journal, 20000, "two_hands"));
  ASSERT_EQ(live.exit_code, 0) << live.output;
  EXPECT_THAT(live.output, HasSubstr("refine: journal record 0 refined: "));
  const std::string checksum = final_checksum(live.output);
  ASSERT_EQ(checksum.size(), 16u) << live.output;
  const auto records = read_journal(journal);
  ASSERT_EQ(records.size(), 1u);
  EXPECT_EQ(records[0].stroke.refine_threshold_m, 0.0003);
  // The station's own start-up replay (no new strokes: the idle scenario).
  const ProcessRun again =
      run(std::string(TWISTER_STATION_BIN) + " --config " + station_config(journal, 20000, "idle"));
  ASSERT_EQ(again.exit_code, 0) << again.output;
  EXPECT_THAT(again.output, HasSubstr("triangles, checksum " + checksum)) << again.output;
  EXPECT_EQ(final_checksum(again.output), checksum);
  // `twister replay` with the station's spare capacity.
  const ProcessRun replay =
      run(std::string(TWISTER_CLI_BIN) + " replay " + journal + " --mesh " + TWISTER_DEPLOY_DIR +
          "/sim_sphere.obj --spare-vertices 20000 --out " + journal + ".obj");
  ASSERT_EQ(replay.exit_code, 0) << replay.output;
  EXPECT_THAT(replay.output, HasSubstr("checksum " + checksum));
  ::unlink((journal + ".obj").c_str());
  ::unlink(journal.c_str());
  ::unlink((journal + ".ckpt").c_str());  // its checkpoint
}

// A clutch chain (sim/scenarios/freeze_360.scn: hand 0 holds, hand 1 turns a full turn
// in four clutched quarter turns) refined at its end: the chain's last record carries
// the threshold, and the station's start-up replay and `twister replay` agree with it.
TEST(RefineStation, AClutchChainIsRefinedAtItsEndAndReplaysTheSame) {
  const std::string journal = temp_path("chain.bin");
  const std::string box = temp_path("chain_box.obj");
  ::unlink(journal.c_str());
  ::unlink((journal + ".ckpt").c_str());  // its checkpoint
  const ProcessRun made = run(std::string(TWISTER_CLI_BIN) +
                              " mesh box -n 12 --size 0.20 --center 0.55 0 0.10 --out " + box);
  ASSERT_EQ(made.exit_code, 0) << made.output;
  const auto config = [&](const char* scenario) {
    const std::string path = temp_path(std::string("chain_") + scenario + ".toml");
    std::ofstream(path)
        << "[station]\njournal = \"" << journal << "\"\nmesh = \"" << box
        << "\"\nspare_vertices = 20000\n[tracker]\nbackend = \"sim\"\n"
        << "left_station = 1\nright_station = 2\n[tracker.sim]\n"
        << (std::string(scenario) == "idle"
                ? std::string("scenario = \"idle\"\n")
                : std::string("scenario_file = \"" TWISTER_SIM_SCENARIO_DIR "/freeze_360.scn\"\n"))
        << "time = \"virtual\"\n[buttons]\nbackend = \"sim\"\n"
        << "[sculpt]\nradius_m = 0.45\nrefine = true\nrefine_threshold_m = 0.0005\n";
    return path;
  };
  const ProcessRun live =
      run(std::string(TWISTER_STATION_BIN) + " --log-level info --config " + config("chain"));
  ASSERT_EQ(live.exit_code, 0) << live.output;
  const std::string checksum = final_checksum(live.output);
  ASSERT_EQ(checksum.size(), 16u) << live.output;
  const auto records = read_journal(journal);
  ASSERT_GE(records.size(), 4u);
  for (std::size_t i = 0; i < records.size(); ++i) {
    EXPECT_EQ(records[i].stroke.chain_step, i);
    EXPECT_EQ(records[i].stroke.refine_threshold_m, i + 1 == records.size() ? 0.0005 : 0.0);
  }
  EXPECT_THAT(live.output, HasSubstr("refine: journal record " +
                                     std::to_string(records.size() - 1) + " refined: "));
  const ProcessRun again = run(std::string(TWISTER_STATION_BIN) + " --config " + config("idle"));
  ASSERT_EQ(again.exit_code, 0) << again.output;
  EXPECT_EQ(final_checksum(again.output), checksum);
  const ProcessRun replay = run(std::string(TWISTER_CLI_BIN) + " replay " + journal + " --mesh " +
                                box + " --spare-vertices 20000 --out " + journal + ".obj");
  ASSERT_EQ(replay.exit_code, 0) << replay.output;
  EXPECT_THAT(replay.output, HasSubstr("checksum " + checksum));
  for (const std::string& f : {journal + ".obj", journal, journal + ".ckpt", box,
                               temp_path("chain_chain.toml"), temp_path("chain_idle.toml")}) {
    ::unlink(f.c_str());
  }
}

// The configs station_config() writes, removed once every test has run.
class RemoveStationConfigs : public ::testing::Environment {
 public:
  void TearDown() override {
    for (const char* scenario : {"two_hands", "idle"}) {
      ::unlink(temp_path(std::string("station_") + scenario + ".toml").c_str());
    }
  }
};
[[maybe_unused]] ::testing::Environment* const kRemoveStationConfigs =
    ::testing::AddGlobalTestEnvironment(new RemoveStationConfigs);

}  // namespace
}  // namespace twister::station_app
