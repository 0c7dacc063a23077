// `twister tracker-dump --file` (issue 22) on recordings of every frame format, made by
// core's encoders: Fastrak ASCII, IEEE binary and 16-bit packed records, and Liberty,
// Patriot and Latus binary frames, two stations each, with line noise between records.
// Every pose comes back as today's line "station ox oy oz ux uy uz vx vy vz wx wy wz",
// the axes checked against an independent Rz*Ry*Rx; the noise is one error line each.
// The old name `fastrak-dump` prints the same. The recordings stay in the build tree.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "twister/tracker/fastrak_encoder.hpp"
#include "twister/tracker/liberty_encoder.hpp"

namespace twister::tracker {
namespace {

struct Truth {
  int station;
  std::array<double, 3> pos;
  std::array<double, 3> euler;  // az, el, roll (degrees)
};

const std::vector<Truth> kTruth = {
    {1, {12.5, -3.25, 4.0}, {30.0, -20.0, 10.0}},
    {2, {10.0, 5.5, -2.75}, {-120.0, 45.0, 170.0}},
    {1, {20.0, 0.5, 1.25}, {0.0, 0.0, 0.0}},
    {2, {-8.0, 7.0, 3.0}, {90.0, -60.0, -45.0}},
};

// R = Rz(az) Ry(el) Rx(roll) (docs/fastrak-protocol.md §4), row-major.
std::array<double, 9> rotation(const std::array<double, 3>& e) {
  const double d = M_PI / 180.0;
  const double cp = std::cos(e[0] * d), sp = std::sin(e[0] * d);
  const double ct = std::cos(e[1] * d), st = std::sin(e[1] * d);
  const double cf = std::cos(e[2] * d), sf = std::sin(e[2] * d);
  return {cp * ct,
          cp * st * sf - sp * cf,
          cp * st * cf + sp * sf,
          sp * ct,
          sp * st * sf + cp * cf,
          sp * st * cf - cp * sf,
          -st,
          ct * sf,
          ct * cf};
}

FastrakPose pose_of(const Truth& t) {
  FastrakPose p;
  p.station = static_cast<std::uint8_t>(t.station);
  for (std::size_t k = 0; k < 3; ++k) {
    p.position[k] = static_cast<float>(t.pos[k]);
    p.euler_deg[k] = static_cast<float>(t.euler[k]);
  }
  const auto r = rotation(t.euler);
  for (std::size_t k = 0; k < 9; ++k) p.dcm[k] = static_cast<float>(r[k]);
  // Quaternion (w, x, y, z) of R.
  const double w = std::sqrt(std::max(0.0, 1.0 + r[0] + r[4] + r[8])) / 2.0;
  double x = std::sqrt(std::max(0.0, 1.0 + r[0] - r[4] - r[8])) / 2.0;
  double y = std::sqrt(std::max(0.0, 1.0 - r[0] + r[4] - r[8])) / 2.0;
  double z = std::sqrt(std::max(0.0, 1.0 - r[0] - r[4] + r[8])) / 2.0;
  x = std::copysign(x, r[7] - r[5]);
  y = std::copysign(y, r[2] - r[6]);
  z = std::copysign(z, r[3] - r[1]);
  p.quaternion = {static_cast<float>(w), static_cast<float>(x), static_cast<float>(y),
                  static_cast<float>(z)};
  p.status = ' ';
  return p;
}

const std::vector<std::byte> kNoise = {std::byte{0x55}, std::byte{0x13}, std::byte{0xEE}};

std::string run(const std::string& command) {
  std::string out;
  FILE* p = ::popen(command.c_str(), "r");
  if (p == nullptr) return out;
  std::array<char, 4096> buf{};
  std::size_t n = 0;
  while ((n = std::fread(buf.data(), 1, buf.size(), p)) > 0) out.append(buf.data(), n);
  EXPECT_EQ(::pclose(p), 0) << command;
  return out;
}

std::string write_recording(const std::string& name, const std::vector<std::byte>& bytes) {
  const std::string path = std::string(TWISTER_RECORDINGS_DIR) + "/" + name + ".bin";
  std::ofstream f(path, std::ios::binary);
  f.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  return path;
}

// Every record (noise after the first and the third), with `encode(pose, out)`.
template <typename Encode>
std::vector<std::byte> record_all(Encode encode) {
  std::vector<std::byte> bytes;
  for (std::size_t i = 0; i < kTruth.size(); ++i) {
    std::array<std::byte, 512> buf{};
    const std::size_t n = encode(pose_of(kTruth[i]), std::span<std::byte>(buf));
    EXPECT_GT(n, 0u);
    bytes.insert(bytes.end(), buf.begin(), buf.begin() + static_cast<std::ptrdiff_t>(n));
    if (i % 2 == 0) bytes.insert(bytes.end(), kNoise.begin(), kNoise.end());
  }
  return bytes;
}

// The dump's lines against the truth: `pos_tol` in inches, `axis_tol` per component.
void expect_poses(const std::string& out, double pos_tol, double axis_tol) {
  std::istringstream in(out);
  std::string line;
  std::size_t k = 0;
  int errors = 0;
  while (std::getline(in, line)) {
    if (line.rfind("error", 0) == 0) {
      ++errors;
      continue;
    }
    ASSERT_LT(k, kTruth.size()) << out;
    std::istringstream fields(line);
    int station = 0;
    std::array<double, 12> v{};
    fields >> station;
    for (double& x : v) fields >> x;
    ASSERT_FALSE(fields.fail()) << line;
    const Truth& t = kTruth[k++];
    EXPECT_EQ(station, t.station) << line;
    for (std::size_t i = 0; i < 3; ++i) EXPECT_NEAR(v[i], t.pos[i], pos_tol) << line;
    const auto r = rotation(t.euler);
    // The line's axes u, v, w are R's columns.
    for (std::size_t col = 0; col < 3; ++col) {
      for (std::size_t row = 0; row < 3; ++row) {
        EXPECT_NEAR(v[3 + col * 3 + row], r[row * 3 + col], axis_tol) << line;
      }
    }
  }
  EXPECT_EQ(k, kTruth.size()) << out;
  EXPECT_EQ(errors, 2) << out;  // one resync line per noise burst
}

std::string dump(const std::string& path, const std::string& args,
                 const std::string& name = "tracker-dump") {
  return run(std::string(TWISTER_CLI) + " " + name + " --file " + path + " " + args +
             " 2>/dev/null");
}

FastrakConfig fastrak(Format format, OutputList list) {
  FastrakConfig c;
  c.format = format;
  c.stations[0] = {true, list};
  c.stations[1] = {true, list};
  return c;
}

const OutputList kQuat = OutputList::of({Item::position, Item::quaternion, Item::crlf});

TEST(TrackerDumpGolden, FastrakAscii) {
  const FastrakConfig c =
      fastrak(Format::ascii, OutputList::of({Item::position, Item::euler, Item::crlf}));
  const auto path =
      write_recording("fastrak_ascii", record_all([&](const FastrakPose& p, auto out) {
                        auto n = encode_record(p, c, out);
                        return n.ok() ? *n : 0;
                      }));
  expect_poses(dump(path, "-O 1,2,4,1 -O 2,2,4,1 -F"), 0.006, 5e-4);
}

TEST(TrackerDumpGolden, FastrakBinary) {
  const FastrakConfig c = fastrak(Format::binary, kQuat);
  const auto path =
      write_recording("fastrak_binary", record_all([&](const FastrakPose& p, auto out) {
                        auto n = encode_record(p, c, out);
                        return n.ok() ? *n : 0;
                      }));
  const std::string out = dump(path, "-O 1,2,11,1 -O 2,2,11,1 -f");
  expect_poses(out, 1e-5, 1e-5);
  // The old name prints the same.
  EXPECT_EQ(dump(path, "-O 1,2,11,1 -O 2,2,11,1 -f", "fastrak-dump"), out);
}

TEST(TrackerDumpGolden, FastrakBinary16) {
  const FastrakConfig c = fastrak(Format::binary16, kQuat);
  const auto path =
      write_recording("fastrak_binary16", record_all([&](const FastrakPose& p, auto out) {
                        auto n = encode_record(p, c, out);
                        return n.ok() ? *n : 0;
                      }));
  // One count: 65.48 in / 32768 in position, 1/32767 per quaternion component.
  expect_poses(dump(path, "-O 1,2,11,1 -O 2,2,11,1 --binary16"), 0.003, 3e-4);
}

void liberty_case(LibertyModel model, const std::string& name) {
  LibertyConfig c;
  ASSERT_TRUE(to_liberty_config(fastrak(Format::binary, kQuat), model, c).ok());
  const auto path = write_recording(name, record_all([&](const FastrakPose& p, auto out) {
                                      auto n = encode_liberty_frame(p, c, out);
                                      return n.ok() ? *n : 0;
                                    }));
  expect_poses(dump(path, "-O 1,2,11,1 -O 2,2,11,1 -f --model " + name), 1e-5, 1e-5);
  // A Fastrak reading finds no record in them.
  const std::string as_fastrak = dump(path, "-O 1,2,11,1 -O 2,2,11,1 -f");
  EXPECT_EQ(as_fastrak.find("1 "), std::string::npos) << as_fastrak;
}

TEST(TrackerDumpGolden, LibertyFrames) { liberty_case(LibertyModel::liberty, "liberty"); }
TEST(TrackerDumpGolden, PatriotFrames) { liberty_case(LibertyModel::patriot, "patriot"); }
TEST(TrackerDumpGolden, LatusFrames) { liberty_case(LibertyModel::latus, "latus"); }

TEST(TrackerDumpGolden, RefusesWhatAModelCannotSay) {
  // binary16 is no Liberty-family format; a Latus has no device mode here.
  const std::string cli = TWISTER_CLI;
  EXPECT_NE(std::system((cli + " tracker-dump --file /dev/null --binary16 --model liberty "
                               "2>/dev/null")
                            .c_str()),
            0);
  EXPECT_NE(std::system((cli + " tracker-dump /dev/null -f --model latus 2>/dev/null").c_str()), 0);
}

}  // namespace
}  // namespace twister::tracker
