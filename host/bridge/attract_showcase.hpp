// AttractShowcase: attract mode's turntable of recent sculptures (issue 25). Between
// visitors the display shows, instead of the station's model (the base mesh then),
// the newest complete archives of the station's exhibit archive directory
// (twister-bridge --attract-archive DIR; the layout in docs/exhibit.md: one directory
// YYYYMMDDTHHMMSSZ-vNNNN-IIIIIIII per visitor, renamed into place only when complete),
// each for `seconds_each` with a caption ("Sculpture 12 · 4 strokes": the visitor
// number from the name, the strokes from record.json). Models are read from
// model.glb (hal/meshio's read_glb, tinygltf underneath: +Y up, metres, centred).
// The directory is listed again every `rescan_s` (a listing; only new names are read)
// so new visitors' sculptures appear and pruned ones go. Bounded: at most `models`
// kept, each within `limits` (file bytes, vertices, triangles). Never fatal: no
// directory, nothing in it or only bad files leave the station's model on screen
// (said once in the log); a bad file is skipped with its error logged once and
// counted. No GL: BridgeApp places and draws the model of the moment.
#pragma once

#include <cstddef>
#include <cstdint>
#include <glm/vec3.hpp>
#include <set>
#include <string>
#include <vector>

#include "mesh_data.hpp"
#include "twister/meshio/glb_reader.hpp"
#include "twister/ports/log_sink.hpp"

namespace twister::bridge {

struct ShowcaseOptions {
  std::string dir;            // the station's exhibit archive ([exhibit] archive_dir)
  std::size_t models = 6;     // the newest archives shown (and kept in memory)
  double seconds_each = 8.0;  // how long each is shown
  double rescan_s = 20.0;     // how often the directory is listed again
  meshio::GlbReadLimits limits = {std::size_t{32} << 20, 400'000, 400'000};
};

struct ShowcaseModel {
  std::string name;          // the archive's directory name
  std::string caption;       // "Sculpture 12 · 4 strokes"
  MeshData mesh;             // as in model.glb: +Y up, metres
  std::uint64_t serial = 0;  // unique per model read (what the renderer holds)
};

struct ShowcaseCounters {
  std::uint64_t scans = 0;
  std::uint64_t loaded = 0;   // models read
  std::uint64_t skipped = 0;  // archives whose model could not be read (each counted once)
};

class AttractShowcase {
 public:
  AttractShowcase(ShowcaseOptions options, ports::LogSink& log);
  // Attract mode begins at `now_s`: the newest first (and a rescan when due).
  void begin(double now_s);
  // The model to show at `now_s` (null: none, show the station's model). Lists the
  // directory again when due. The pointer is valid until the next call.
  const ShowcaseModel* at(double now_s);
  const std::vector<ShowcaseModel>& models() const { return models_; }
  const ShowcaseCounters& counters() const { return counters_; }
  const ShowcaseOptions& options() const { return options_; }

 private:
  void rescan(double now_s);
  bool load(const std::string& name, ShowcaseModel& out);

  ShowcaseOptions options_;
  ports::LogSink& log_;
  std::vector<ShowcaseModel> models_;  // newest first
  std::set<std::string> bad_;          // archives whose model could not be read
  ShowcaseCounters counters_{};
  double epoch_s_ = 0.0;
  double next_scan_s_ = -1.0;  // < 0: never listed
  bool told_empty_ = false;    // the fall-back was logged (until models appear)
  std::uint64_t serials_ = 0;
};

// Whether `name` is an archive directory's name (YYYYMMDDTHHMMSSZ-vNNNN-IIIIIIII).
bool archive_name(const std::string& name);
// The caption of an archive: its visitor number and record.json's strokes (when
// the record says; `strokes` < 0: unknown).
std::string showcase_caption(const std::string& name, long strokes);
// The model placed where the station's model is: its bounding box's centre at `centre`,
// its half diagonal `radius`, its +Y along `up` (all in the frame the renderer draws).
MeshData place_upright(const MeshData& mesh, glm::vec3 up, glm::vec3 centre, float radius);

}  // namespace twister::bridge
