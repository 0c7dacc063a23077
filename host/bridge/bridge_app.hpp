// BridgeApp: twister-bridge's loop body. Reads link bytes, decodes frames, keeps
// the scene replica, answers with hello (after every (re)connect: resync by
// version) and resend requests, and keeps the display current: the rest mesh on
// each verified version, the stroke's weights once per stroke, the screws on each
// live frame. Snapshots (offscreen): the rest mesh when the first mesh arrives,
// the live warp just before each commit is applied, and the committed mesh.
// Messages go to the LogSink it is given (components "link", "replica",
// "snapshot"): link loss and rejected change sets are warnings, connects, meshes
// and commits notices, each picture written info.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "mesh_renderer.hpp"
#include "scene_replica.hpp"
#include "twister/link/link_codec.hpp"
#include "twister/ports/link_port.hpp"
#include "twister/ports/log_sink.hpp"

namespace twister::bridge {

struct BridgeOptions {
  std::string snapshot_dir;  // empty: no PNGs
};

struct BridgeCounters {
  std::uint64_t connects = 0;
  std::uint64_t disconnects = 0;
  std::uint64_t snapshots = 0;
};

class BridgeApp {
 public:
  // `renderer` may be null (headless replica, tests). `port` and `log` must outlive
  // the app.
  BridgeApp(ports::LinkPort& port, MeshRenderer* renderer, BridgeOptions options,
            ports::LogSink& log);
  // One step: link I/O and replica updates (never blocks). Returns frames decoded.
  std::size_t step();
  // Draws the current scene (window mode each frame; offscreen for snapshots).
  void draw();
  // Draws and writes <snapshot_dir>/<name>.png; returns the path ("" on failure).
  std::string snapshot(const std::string& name);

  bool connected() const { return connected_; }
  const SceneReplica& replica() const { return replica_; }
  SceneReplica& replica() { return replica_; }
  const BridgeCounters& counters() const { return counters_; }
  link::DecoderCounters decoder_counters() const { return decoder_.counters(); }
  const std::vector<std::string>& pictures() const { return pictures_; }

 private:
  void handle(const link::LinkMessage& m);
  void send(const link::LinkMessage& m);
  void flush();
  void refresh_display();

  ports::LinkPort& port_;
  MeshRenderer* renderer_;
  ports::LogSink& log_;
  BridgeOptions options_;
  SceneReplica replica_;
  link::LinkDecoder decoder_;
  std::vector<std::byte> in_;  // receive buffer, sized once
  std::vector<std::byte> out_;
  bool connected_ = false;
  bool display_mesh_live_ = false;  // the renderer holds CPU-warped positions (scodef)
  std::uint32_t shown_version_ = 0;
  std::uint32_t shown_stroke_ = 0;
  std::uint64_t shown_live_frames_ = 0;  // replica live frames when the CPU warp was shown
  BridgeCounters counters_{};
  std::vector<std::string> pictures_;
};

}  // namespace twister::bridge
