// The link fuzzers' seeds speak this protocol: every seed in
// tests/fuzz/corpus/link_decoder_fuzz delivers at least one message through a fresh
// LinkDecoder, and together they cover every message type; likewise the
// scene_replica_fuzz seeds (a mode byte, then frames or length-prefixed payloads, see
// tests/fuzz/scene_replica_fuzz.cpp). A protocol bump makes the old seeds fail here (a
// fuzzer whose seeds are all refused at the version byte only exercises the framing).
// To write them again after a deliberate change:
//   TWISTER_WRITE_LINK_SEEDS=tests/fuzz/corpus build/tests/link_fuzz_seeds_test
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "twister/link/link_codec.hpp"

namespace twister::link {
namespace {

namespace fs = std::filesystem;

// One plausible message of each type, named for its seed file.
std::vector<std::pair<std::string, LinkMessage>> one_of_each() {
  std::vector<std::pair<std::string, LinkMessage>> m;
  Hello hello;
  hello.role = Role::bridge;
  hello.mesh_version = 3;
  m.emplace_back("hello", hello);
  m.emplace_back("auth", Auth{});
  m.emplace_back("bye", Bye{});
  MeshBegin begin;
  begin.version = 1;
  begin.vertex_count = 3;
  begin.triangle_count = 1;
  m.emplace_back("mesh_begin", begin);
  Vertices vertices;
  vertices.count = 3;
  for (std::uint16_t i = 0; i < 3; ++i) vertices.items[i] = {i, 0.1F * i, 0.2F, -0.3F * i};
  m.emplace_back("vertices", vertices);
  Triangles triangles;
  triangles.count = 1;
  triangles.indices[1] = 1;
  triangles.indices[2] = 2;
  m.emplace_back("triangles", triangles);
  m.emplace_back("mesh_end", MeshEnd{1, 0x0123456789abcdefULL});
  m.emplace_back("resend_request", ResendRequest{});
  StrokeBegin stroke;
  stroke.stroke = 7;
  stroke.mesh_version = 1;
  stroke.hand_mask = 3;
  stroke.refine_threshold_m = 0.0005F;
  stroke.radius_m = 0.1;
  stroke.start[1].origin = {0.2, 0.0, 0.0};
  stroke.symmetry = {1, 1, 0, 0};  // the mirror x = 0
  m.emplace_back("stroke_mirrored", stroke);
  Hands hands;
  hands.sequence = 9;
  hands.flags = kHandSample0 | kHandSample1 | kHandTracked0 | kHandTracked1 | kStrokeActive;
  hands.buttons = kButtonGrab;
  hands.radius_m = 0.1F;
  m.emplace_back("hands", hands);
  m.emplace_back("object", ObjectPose{});
  StatusReport status;
  status.tracker_state = static_cast<std::uint8_t>(TrackerState::streaming);
  status.buttons_state = static_cast<std::uint8_t>(ButtonsState::missing);
  status.symmetry = {2, 0, 2, 6};
  status.spectators = 1;
  m.emplace_back("status", status);
  m.emplace_back("command", Command{});
  Workspace workspace;
  workspace.flags = kWorkspaceCalibrated;
  workspace.up = {0.0F, 0.0F, 1.0F};
  workspace.min = {-0.3F, -0.3F, 0.0F};
  workspace.max = {0.3F, 0.3F, 0.4F};
  m.emplace_back("workspace", workspace);
  m.emplace_back("visitor", VisitorState{VisitorPhase::sculpting, kVisitorResetUndoable, 3, 17, 5,
                                         42.0F, 0.0F});
  m.emplace_back("notice", Notice{NoticeCode::undo_refused, 0});
  return m;
}

std::vector<std::byte> frame_of(const LinkMessage& message) {
  std::vector<std::byte> out(kMaxFrameBytes);
  const Result<std::size_t> n = encode_frame(message, out);
  EXPECT_TRUE(n.ok()) << "message type " << message.index() + 1 << " does not encode";
  out.resize(n.ok() ? *n : 0);
  return out;
}

void write_file(const fs::path& path, const std::vector<std::byte>& bytes) {
  std::ofstream(path, std::ios::binary)
      .write(reinterpret_cast<const char*>(bytes.data()),
             static_cast<std::streamsize>(bytes.size()));
}

// A message's payload (version, type, body) as scene_replica_fuzz's modes 1 and 2 read
// it: one length byte, then the payload.
void append_payload(std::vector<std::byte>& out, const LinkMessage& message) {
  const std::vector<std::byte> frame = frame_of(message);
  FrameDecoderBuffer<kMaxFrameBytes> decoder;
  for (const std::byte b : frame) {
    const auto payload = decoder.process(b);
    if (!payload.ok()) continue;
    ASSERT_LE(payload->size(), 255u) << "message type " << message.index() + 1;
    out.push_back(static_cast<std::byte>(payload->size()));
    out.insert(out.end(), payload->begin(), payload->end());
  }
}

// scene_replica_fuzz: every type as frames (mode 0), as payloads (mode 1) and after
// the harness's 4 x 4 grid (mode 2: the stroke and hands act on a mesh), a commit
// that appends to the grid, and a full mesh announcing counts past every limit.
void write_replica_seeds(const fs::path& dir) {
  fs::create_directories(dir);
  std::vector<std::byte> frames{std::byte{0}};
  std::vector<std::byte> raw{std::byte{1}};
  std::vector<std::byte> on_grid{std::byte{2}};
  for (const auto& [name, message] : one_of_each()) {
    const std::vector<std::byte> f = frame_of(message);
    frames.insert(frames.end(), f.begin(), f.end());
    append_payload(raw, message);
    append_payload(on_grid, message);
  }
  write_file(dir / "each_type_frames", frames);
  write_file(dir / "each_type_payloads", raw);
  write_file(dir / "each_type_on_grid", on_grid);
  std::vector<std::byte> commit{std::byte{2}};
  append_payload(commit, MeshBegin{false, 1, 2, 17, 19});
  Vertices added;
  added.count = 1;
  added.items[0] = {16, 0.15F, 0.15F, 0.05F};
  append_payload(commit, added);
  Triangles fan;
  fan.first = 18;
  fan.count = 1;
  fan.indices[0] = 5;
  fan.indices[1] = 6;
  fan.indices[2] = 16;
  append_payload(commit, fan);
  append_payload(commit, MeshEnd{2, 0x0123456789abcdefULL});
  write_file(dir / "commit_appends", commit);
  // A live stroke under rot6 about z on the grid (the replica's symmetric plan and the
  // display shader's entries, issue 26).
  std::vector<std::byte> symmetric{std::byte{2}};
  StrokeBegin stroke;
  stroke.stroke = 5;
  stroke.mesh_version = 1;
  stroke.hand_mask = 1;
  stroke.radius_m = 0.15;
  stroke.start[0].origin = {0.2, 0.1, 0.0};
  stroke.symmetry = {2, 0, 2, 6};
  append_payload(symmetric, stroke);
  Hands hands;
  hands.stroke = 5;
  hands.flags = kHandSample0 | kHandTracked0 | kStrokeActive;
  hands.radius_m = 0.15F;
  append_payload(symmetric, hands);
  write_file(dir / "symmetric_stroke_on_grid", symmetric);
  std::vector<std::byte> huge{std::byte{1}};
  append_payload(huge, MeshBegin{true, 0, 1, 0xffffffffU, 0xffffffffU});
  write_file(dir / "huge_counts", huge);
}

// Writes the seeds: a frame of each type, and the hands frame after line garbage.
void write_seeds(const fs::path& dir) {
  fs::create_directories(dir);
  for (const auto& [name, message] : one_of_each()) {
    const std::vector<std::byte> f = frame_of(message);
    std::ofstream(dir / name, std::ios::binary)
        .write(reinterpret_cast<const char*>(f.data()), static_cast<std::streamsize>(f.size()));
  }
  std::vector<std::byte> garbage{std::byte{0x55}, std::byte{0x00}, std::byte{0xff}, std::byte{0x02},
                                 std::byte{0x00}};
  for (const auto& [name, message] : one_of_each()) {
    if (name != "hands") continue;
    const std::vector<std::byte> f = frame_of(message);
    garbage.insert(garbage.end(), f.begin(), f.end());
  }
  std::ofstream(dir / "garbage_then_hands", std::ios::binary)
      .write(reinterpret_cast<const char*>(garbage.data()),
             static_cast<std::streamsize>(garbage.size()));
}

std::vector<unsigned char> read_bytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(LinkFuzzSeeds, EachSpeaksThisProtocolAndTogetherTheyCoverEveryMessageType) {
  const fs::path dir = fs::path(TWISTER_SOURCE_DIR) / "tests/fuzz/corpus/link_decoder_fuzz";
  if (const char* out = std::getenv("TWISTER_WRITE_LINK_SEEDS"); out != nullptr) {
    write_seeds(fs::path(out) / "link_decoder_fuzz");
    write_replica_seeds(fs::path(out) / "scene_replica_fuzz");
  }
  std::set<std::size_t> types;
  std::size_t seeds = 0;
  for (const fs::directory_entry& e : fs::directory_iterator(dir)) {
    ++seeds;
    LinkDecoder decoder;
    std::size_t delivered = 0;
    for (const unsigned char c : read_bytes(e.path())) {
      if (const auto m = decoder.process(static_cast<std::byte>(c)); m.ok()) {
        ++delivered;
        types.insert((*m)->index());
      }
    }
    EXPECT_GT(delivered, 0u) << e.path().filename() << ": no message of protocol "
                             << int{kProtocolVersion};
  }
  EXPECT_GT(seeds, 0u);
  EXPECT_EQ(types.size(), std::variant_size_v<LinkMessage>) << "a message type has no seed";
}

TEST(LinkFuzzSeeds, OneOfEachEncodesAndDecodesToItself) {
  for (const auto& [name, message] : one_of_each()) {
    const std::vector<std::byte> f = frame_of(message);
    LinkDecoder decoder;
    const LinkMessage* got = nullptr;
    for (const std::byte b : f) {
      if (const auto m = decoder.process(b); m.ok()) got = *m;
    }
    ASSERT_NE(got, nullptr) << name;
    EXPECT_EQ(got->index(), message.index()) << name;
    EXPECT_EQ(frame_of(*got), f) << name;
  }
}

// Every scene_replica_fuzz seed delivers a message of this protocol in its mode, and
// together they cover every type.
TEST(LinkFuzzSeeds, SceneReplicaSeedsSpeakThisProtocol) {
  const fs::path dir = fs::path(TWISTER_SOURCE_DIR) / "tests/fuzz/corpus/scene_replica_fuzz";
  std::set<std::size_t> types;
  std::size_t seeds = 0;
  for (const fs::directory_entry& e : fs::directory_iterator(dir)) {
    ++seeds;
    const std::vector<unsigned char> bytes = read_bytes(e.path());
    ASSERT_FALSE(bytes.empty()) << e.path().filename();
    std::size_t delivered = 0;
    LinkDecoder decoder;
    LinkMessage message;
    for (std::size_t i = 1; i < bytes.size();) {
      if (bytes[0] % 3 == 0) {
        if (const auto m = decoder.process(static_cast<std::byte>(bytes[i++])); m.ok()) {
          ++delivered;
          types.insert((*m)->index());
        }
        continue;
      }
      const std::size_t len = std::min<std::size_t>(bytes[i], bytes.size() - i - 1);
      const auto* p = reinterpret_cast<const std::byte*>(bytes.data() + i + 1);
      if (decode_payload(std::span<const std::byte>(p, len), message).ok()) {
        ++delivered;
        types.insert(message.index());
      }
      i += 1 + len;
    }
    EXPECT_GT(delivered, 0u) << e.path().filename() << ": no message of protocol "
                             << int{kProtocolVersion};
  }
  EXPECT_GT(seeds, 0u);
  EXPECT_EQ(types.size(), std::variant_size_v<LinkMessage>) << "a message type has no seed";
}

}  // namespace
}  // namespace twister::link
