// The real twister-station executable with [exhibit] on (issue 25, label exhibit): the
// simulator backend in virtual time plays one visitor (a two-hand stroke on the deploy
// sphere, then hands still); idle_seconds 5 and grace 0 end the sculpture and the
// program archives it. Checked: one archive directory holding exactly journal.twj,
// model.stl, model.glb, thumbnail.png and record.json; the STL passes Debian's admesh
// (a checker we did not write: no open or disconnected facets, one part, centred on the
// origin); the .glb reloads with tinygltf with a material; record.json names the
// visitor and its one stroke; the journal left is a new one, shorter than the archived
// one; the metrics file says one visitor today.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <tiny_gltf.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>

#include "prometheus_text.hpp"
#include "twister/meshio/glb_reader.hpp"

namespace {

namespace fs = std::filesystem;

struct CommandRun {
  int exit_code = -1;
  std::string out;
};

CommandRun run(const std::string& command) {
  CommandRun r;
  FILE* p = ::popen((command + " 2>&1").c_str(), "r");
  if (p == nullptr) return r;
  std::array<char, 4096> buf{};
  for (std::size_t n; (n = std::fread(buf.data(), 1, buf.size(), p)) > 0;)
    r.out.append(buf.data(), n);
  const int status = ::pclose(p);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

std::string read_file(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>()};
}

double after(const std::string& out, const std::string& label) {
  const std::size_t at = out.find(label);
  if (at == std::string::npos) return std::nan("");
  return std::strtod(out.c_str() + at + label.size(), nullptr);
}

TEST(ExhibitProgram, AnIdleVisitorIsArchivedWithAnStlAdmeshPassesAndAGlbThatReloads) {
  const fs::path dir =
      fs::temp_directory_path() / ("exhibit_program_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path config = dir / "station.toml";
  std::ofstream(config)
      << "[station]\njournal = \"" << (dir / "journal.twj").string()
      << "\"\nmesh = \"" TWISTER_DEPLOY_DIR "/sim_sphere.obj\"\n"
      << "[tracker]\nbackend = \"sim\"\n[tracker.sim]\nscenario_file = \"" TWISTER_SCENARIO_DIR
         "/exhibit_visitor.scn\"\ntime = \"virtual\"\n"
      << "[buttons]\nbackend = \"sim\"\n"
      << "[exhibit]\nenabled = true\narchive_dir = \"" << (dir / "archive").string()
      << "\"\nidle_seconds = 5\ngrace_seconds = 0\n"
      << "[health]\nmetrics_file = \"" << (dir / "metrics.prom").string() << "\"\n";
  const CommandRun r =
      run(std::string(TWISTER_STATION_BIN) + " --config " + config.string() + " --log-level info");
  ASSERT_EQ(r.exit_code, 0) << r.out;

  std::vector<fs::path> archives;
  for (const auto& e : fs::directory_iterator(dir / "archive")) archives.push_back(e.path());
  ASSERT_EQ(archives.size(), 1u) << r.out;
  const fs::path a = archives[0];
  std::vector<std::string> files;
  for (const auto& e : fs::directory_iterator(a)) files.push_back(e.path().filename().string());
  std::sort(files.begin(), files.end());
  EXPECT_EQ(files, (std::vector<std::string>{"journal.twj", "model.glb", "model.stl", "record.json",
                                             "thumbnail.png"}))
      << a;

  const std::string record = read_file(a / "record.json");
  EXPECT_NE(record.find("\"visitor\": 1,"), std::string::npos) << record;
  EXPECT_NE(record.find("\"end\": \"idle\""), std::string::npos) << record;
  EXPECT_NE(record.find("\"strokes\": 1,"), std::string::npos) << record;

  // Debian's admesh: closed, one part, centred on the origin (mm, +Z up).
  const CommandRun ad = run("admesh " + (a / "model.stl").string());
  ASSERT_EQ(ad.exit_code, 0) << ad.out;
  EXPECT_NE(ad.out.find("Binary STL file"), std::string::npos) << ad.out;
  EXPECT_TRUE(std::regex_search(ad.out, std::regex(R"(Total disconnected facets\s*:\s*0\s+0)")))
      << ad.out;
  EXPECT_TRUE(std::regex_search(ad.out, std::regex(R"(Facets with 1 disconnected edge\s*:\s*0\s)")))
      << ad.out;
  EXPECT_TRUE(std::regex_search(ad.out, std::regex(R"(Number of parts\s*:\s*1\b)"))) << ad.out;
  EXPECT_NE(ad.out.find("No holes need to be filled."), std::string::npos) << ad.out;
  for (const char* axis : {"X", "Y", "Z"}) {
    const double lo = after(ad.out, std::string("Min ") + axis + " = ");
    const double hi = after(ad.out, std::string("Max ") + axis + " = ");
    EXPECT_NEAR(lo + hi, 0.0, 0.01) << axis << "\n" << ad.out;
    EXPECT_GT(hi - lo, 150.0) << axis;  // a 0.2 m sphere, pulled, in mm
  }
  std::smatch m;
  ASSERT_TRUE(std::regex_search(ad.out, m, std::regex(R"(Number of facets\s*:\s*(\d+))")))
      << ad.out;
  const int facets = std::stoi(m[1].str());

  tinygltf::TinyGLTF loader;
  tinygltf::Model model;
  std::string err, warn;
  ASSERT_TRUE(loader.LoadBinaryFromFile(&model, &err, &warn, (a / "model.glb").string())) << err;
  ASSERT_EQ(model.materials.size(), 1u);
  EXPECT_EQ(model.meshes.at(0).primitives.at(0).material, 0);
  const int indices = model.meshes.at(0).primitives.at(0).indices;
  ASSERT_GE(indices, 0);
  EXPECT_EQ(static_cast<int>(model.accessors.at(static_cast<std::size_t>(indices)).count),
            3 * facets);

  // The display's attract showcase reads the same model back (meshio::read_glb).
  const auto shown = twister::meshio::read_glb((a / "model.glb").string());
  ASSERT_TRUE(shown) << shown.error().message;
  EXPECT_EQ(static_cast<int>((*shown)->mesh().triangle_count()), facets);

  EXPECT_LT(fs::file_size(dir / "journal.twj"), fs::file_size(a / "journal.twj"));
  // The metrics: one visitor's sculpture ended today.
  const std::string prom = read_file(dir / "metrics.prom");
  EXPECT_EQ(twister::test::prometheus_sample(prom, "twister_visitors_today"), 1.0) << prom;
  std::printf(
      "archive %s: admesh %d facets, 0 disconnected, 1 part; glb %zu material(s); "
      "%zu bytes of journal archived, %ju left\n",
      a.filename().c_str(), facets, model.materials.size(),
      static_cast<std::size_t>(fs::file_size(a / "journal.twj")),
      static_cast<std::uintmax_t>(fs::file_size(dir / "journal.twj")));
  if (::testing::Test::HasFailure()) {
    std::printf("kept for inspection: %s\n%s\n", dir.c_str(), r.out.c_str());
  } else {
    fs::remove_all(dir);
  }
}

}  // namespace
