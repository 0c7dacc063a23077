// BridgeApp: twister-bridge's loop body. Reads link bytes (a fresh decoder per
// connection), runs the display's side of the handshake (hello with its mesh
// version: resync by version; the pre-shared-key challenge-response when given an
// authenticator; hello again when the station stays silent, e.g. a station
// restarted behind a serial line), keeps the scene replica and answers resend
// requests, and keeps the display current: the rest mesh on each verified version,
// the stroke's weights once per segment, the screws on each hands update.
// Yielding: told `bye: displaced` (another display took the link), it leaves the
// link alone and tries again after 2 s, doubling to 60 s, with a yielding hello the
// station refuses (`bye: busy`) while another display holds the link: it comes
// back when the link is free, and two displays never take it from each other.
// Backing off for good: unauthorised, or a station speaking another protocol
// version, stops all link I/O (stopped() says why).
// Snapshots (offscreen): the rest mesh when the first mesh arrives, the live warp
// as each stroke segment ends (live-<next version>.png), and the committed mesh.
// Time (hello retry, silence, the hands rate) comes from the ports::Clock the
// program hands in (hal::MonotonicClock; tests drive a fake).
// Messages go to the LogSink it is given (components "link", "replica",
// "snapshot"): link loss and rejected change sets are warnings, being displaced a
// warning, refusals errors, connects, meshes and commits notices, pictures info.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "framing.hpp"
#include "hud_model.hpp"
#include "mesh_renderer.hpp"
#include "scene_replica.hpp"
#include "twister/link/link_authenticator.hpp"
#include "twister/link/link_codec.hpp"
#include "twister/ports/clock.hpp"
#include "twister/ports/link_port.hpp"
#include "twister/ports/log_sink.hpp"
#include "weight_preview.hpp"

namespace twister::bridge {

// What the camera frames (kiosk and offscreen; a window's free camera frames the model).
enum class Framing : std::uint8_t {
  model,      // the model's bounding sphere (when the first mesh arrives)
  workspace,  // the station's working volume and the model, growing to keep the cursors
  automatic,  // workspace when the station has a work frame or a configured volume
};

struct BridgeOptions {
  std::string snapshot_dir;  // empty: no PNGs
  Framing framing = Framing::model;
  // With snapshot_dir: also a frame-<n>.png after every `movie_every`-th hands update
  // (0: none), a moving picture in the station's time (one update per 8 ms at most).
  std::uint32_t movie_every = 0;
  link::LinkAuthenticator* authenticator = nullptr;  // the pre-shared key (null: none)
  // A read-only display (twister-bridge --spectator): hello with kHelloSpectator,
  // and no commands sent.
  bool spectator = false;
  ReplicaLimits limits{};
  std::int64_t hello_retry_ms = 1000;  // hello again until the station answers
  std::int64_t silence_ms = 3000;      // no frame this long: hello again (new session)
  std::int64_t yield_first_ms = 2000;  // displaced: the first try again after this,
  std::int64_t yield_max_ms = 60000;   // doubling on each `bye: busy` up to this
};

struct BridgeCounters {
  std::uint64_t connects = 0;
  std::uint64_t disconnects = 0;
  std::uint64_t snapshots = 0;
  std::uint64_t hellos_sent = 0;
  std::uint64_t ignored = 0;               // station messages before the handshake completed
  std::uint64_t hands_busiest_second = 0;  // most hands updates in one wall-clock second
  std::uint64_t commands_sent = 0;         // keyboard commands sent to the station
  std::uint64_t displaced = 0;             // times another display took the link
  std::uint64_t busy = 0;                  // yielding tries refused while it was taken
};

// Why the bridge stopped using the link (none: it did not).
enum class BridgeStop : std::uint8_t { none, unauthorised, version };

class BridgeApp {
 public:
  // `renderer` may be null (headless replica, tests). `port`, `clock`, `log` and the
  // authenticator must outlive the app.
  BridgeApp(ports::LinkPort& port, ports::Clock& clock, MeshRenderer* renderer,
            BridgeOptions options, ports::LogSink& log);
  // One step: link I/O and replica updates (never blocks). Returns frames decoded.
  std::size_t step();
  // Sends a sculptor's command (keys: undo, redo, method) to the station, which
  // acts on it only from the admitted display. False when the link is not ready
  // (nothing is queued for later: a stale undo must not fire on reconnect).
  // A spectator sends none (false).
  bool send_command(const link::Command& command);
  // Draws through `view` (mesh, cues, HUD) from now on; null: the mesh alone.
  void set_view(class SceneView* view) { view_ = view; }
  // Attract mode shows the showcase's recent sculptures instead of the station's model
  // (null: the station's model turns, as before). Must outlive the app.
  void set_showcase(class AttractShowcase* showcase) { showcase_ = showcase; }
  // The archive's sculpture on screen now (its directory name; "": the station's model).
  const std::string& showing_archive() const { return showing_name_; }
  // Draws the current scene (window mode each frame; offscreen for snapshots).
  void draw();
  // The link as the HUD shows it.
  LinkView link_view() const;
  HudInput hud_input() const;
  // Draws and writes <snapshot_dir>/<name>.png; returns the path ("" on failure).
  std::string snapshot(const std::string& name);

  bool connected() const { return connected_; }
  bool spectator() const { return options_.spectator; }
  // The handshake is complete: the station's data is trusted and shown.
  bool ready() const { return connected_ && ready_; }
  BridgeStop stopped() const { return stop_; }
  // Displaced: waiting to try again (yielding) until the station admits it.
  bool yielding() const { return yield_.active; }
  // When the next try is due (monotonic ms; meaningful while yielding()).
  std::int64_t next_try_ms() const { return yield_.retry_at_ms; }
  const SceneReplica& replica() const { return replica_; }
  SceneReplica& replica() { return replica_; }
  const BridgeCounters& counters() const { return counters_; }
  link::DecoderCounters decoder_counters() const { return decoder_.counters(); }
  const std::vector<std::string>& pictures() const { return pictures_; }

 private:
  // Handshake (bridge_session.cpp).
  void on_connect();
  void send_hello();
  void on_station_hello(const link::Hello& hello);
  void on_station_auth(const link::Auth& auth);
  void on_bye(const link::Bye& bye);
  void stop(BridgeStop why);
  // Leaves the link alone until the next try (first 2 s, then doubling).
  void yield_link();
  void admitted();
  void keep_alive();
  // Display (bridge_app.cpp).
  void handle(const link::LinkMessage& m);
  void handle_scene(const link::LinkMessage& m);
  // Queues one message (each type encoded directly, no LinkMessage built).
  template <link::LinkBody M>
  void send(const M& m) {
    std::array<std::byte, link::kMaxFrameBytes> frame{};
    const auto n = link::encode_frame(m, frame);
    if (n.ok())
      out_.insert(out_.end(), frame.begin(), frame.begin() + static_cast<std::ptrdiff_t>(*n));
  }
  void flush();
  // Beside a live or movie picture: where its screw axes, cursors and HUD panel are.
  void write_cues(const std::string& path) const;
  // The workspace framing (Framing): holds the volume and the model, follows the
  // cursors once per hands update (so pictures repeat from run to run).
  bool workspace_framing() const;
  void hold_framing();
  void follow_cursors();
  void refresh_display();
  void refresh_weights(bool mesh_uploaded);
  // Attract mode with a showcase: its model of the moment on the renderer (true), or
  // the station's model back at once (false; the caller uploads it).
  bool show_archive();
  std::int64_t now_ms() const { return clock_.now_us() / 1000; }

  ports::LinkPort& port_;
  ports::Clock& clock_;
  MeshRenderer* renderer_;
  class SceneView* view_ = nullptr;
  class AttractShowcase* showcase_ = nullptr;
  ports::LogSink& log_;
  BridgeOptions options_;
  SceneReplica replica_;
  link::LinkDecoder decoder_;
  std::vector<std::byte> in_;  // receive buffer, sized once
  std::vector<std::byte> out_;
  bool connected_ = false;
  bool station_stopped_ = false;  // its last connection ended with bye: shutdown
  // Handshake of the current connection.
  bool station_hello_ = false;
  bool ready_ = false;
  link::Nonce bridge_nonce_{};
  link::Nonce station_nonce_{};
  std::int64_t hello_sent_ms_ = 0;
  std::int64_t last_frame_ms_ = 0;
  std::int64_t hands_second_ = 0;
  std::uint64_t hands_in_second_ = 0;
  std::uint64_t hands_last_second_ = 0;
  BridgeStop stop_ = BridgeStop::none;
  struct Yield {
    bool active = false;
    std::int64_t backoff_ms = 0;
    std::int64_t retry_at_ms = 0;
  } yield_;
  // Display.
  bool display_mesh_live_ = false;  // the renderer holds CPU-warped positions (scodef)
  std::uint32_t shown_version_ = 0;
  std::uint32_t shown_stroke_ = 0;
  std::uint64_t shown_live_frames_ = 0;  // replica live frames when the CPU warp was shown
  bool showing_live_weights_ = false;    // the renderer holds the stroke's weights
  std::uint32_t live_pictured_ = 0;      // the stroke segment last pictured (live-<v>.png)
  std::uint64_t movie_hands_ = 0;        // hands updates counted for movie frames
  std::uint64_t movie_frames_ = 0;       // frame-<n>.png written
  WeightPreview preview_;                // weights before a grab
  WorkspaceFraming framing_;             // Framing::workspace: what the camera holds
  std::uint64_t over_capacity_logged_ = 0;
  // Attract's showcase: in attract mode since the last step, the archive model the
  // renderer holds (its serial; 0: the station's) and its name and caption.
  bool in_attract_ = false;
  std::uint64_t showing_serial_ = 0;
  std::string showing_name_;
  std::string showing_caption_;
  bool live_mesh_stale_ = false;  // the renderer held an archive model: upload again
  BridgeCounters counters_{};
  std::vector<std::string> pictures_;
};

}  // namespace twister::bridge
