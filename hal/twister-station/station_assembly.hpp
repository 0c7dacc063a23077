// StationParts: everything twister-station builds before its loop, in the order it
// is built (and torn down in reverse): the backends, the journal file, the initial
// model, the core's working memory sized once from the model's capacity, the core
// Station (journal replayed onto the model) and the optional display link.
// assemble_station() is the program's start-up: it allocates, the loop never does.
// Every failure comes back as one hal::Error whose message names what failed.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "backend_factory.hpp"
#include "config/station_config.hpp"
#include "display_link.hpp"
#include "exhibit_archive.hpp"
#include "station_memory.hpp"
#include "twister/hal/expected.hpp"
#include "twister/hal/output_file.hpp"
#include "twister/hal/posix_file_sink.hpp"
#include "twister/hal/posix_file_storage.hpp"
#include "twister/meshio/mesh_buffer.hpp"
#include "twister/meshio/symmetry_buffer.hpp"
#include "twister/session/sculpt_session.hpp"
#include "twister/station/station.hpp"

namespace twister::station_app {

struct AssemblyOptions {
  std::filesystem::path config_dir;  // a relative station.mesh is relative to it
  std::string link_address;          // --link (overrides [link] address); empty: config's
};

struct StationParts {
  Backends backends;
  hal::PosixFileStorage journal;  // locked while the station runs
  // Where the bytes of a torn journal tail go before it is cut: JOURNAL.torn-tail
  // (or .1, .2, ...: never an existing file).
  std::unique_ptr<hal::PosixFileSink> tail_archive;
  // JOURNAL.ckpt: read at start when present, replaced by each new checkpoint (only
  // when it is a checkpoint this program wrote).
  std::unique_ptr<hal::PosixFileStorage> checkpoint_in;
  std::unique_ptr<hal::PosixFileSink> checkpoint_out;
  // What start-up recovery did, for the log: a notice (checkpoint restored) or a
  // warning (torn tail cut, checkpoint ignored) each.
  struct Note {
    bool warning = false;
    std::string text;
  };
  std::vector<Note> recovery_notes;
  std::filesystem::path mesh_path;  // as opened (resolved against config_dir)
  // A shared lock on station.mesh while the station runs: the tools (twister replay,
  // mesh, export) refuse to write over a locked file (hal/output_file.hpp).
  hal::FileReadLock base_lock;
  int stale_temporaries = 0;  // JOURNAL.ckpt.tmp-* / .torn-tail.tmp-* removed at start
  std::unique_ptr<meshio::MeshBuffer> model;
  std::unique_ptr<WorkMemory> work;
  std::unique_ptr<RefineMemory> refine;  // [sculpt] refine on
  // Symmetric strokes' plan storage: always there, so a journal with symmetric
  // strokes replays whatever [sculpt] symmetry says now.
  std::unique_ptr<meshio::SymmetryBuffer> symmetry;
  // [exhibit] enabled: the archive and the base model the mesh is reset to after
  // each sculpture (the model file loaded again, without spare capacity).
  std::unique_ptr<ExhibitArchive> archive;
  std::unique_ptr<meshio::MeshBuffer> base_model;
  std::unique_ptr<station::Station> core;  // started: the journal is replayed
  DisplayLink display;                     // open when a link address is set
};

// Builds and starts everything. Errors (message for the log): the backends'
// (make_backends), the journal's ("cannot open journal PATH (io_error, errno N)";
// "journal PATH is in use by another twister-station (PID N)"; "journal PATH: is not
// a Twister journal, or does not fit this mesh (left untouched)"; "journal PATH: damaged
// record at offset X ...; N valid records follow it ..."), the mesh's ("mesh PATH:
// ..."), the link's ("link ADDRESS: ...").
hal::Expected<std::unique_ptr<StationParts>> assemble_station(const StationFileConfig& config,
                                                              const AssemblyOptions& options);

// station.toml's model as a mesh with the configured spare capacity (spare_vertices
// more vertices, twice as many more triangles: what refinement of a closed mesh
// needs). Errors: io_error / invalid_argument "mesh PATH: line N: what is wrong"
// (meshio::load_obj).
hal::Expected<std::unique_ptr<meshio::MeshBuffer>> load_station_mesh(
    const std::filesystem::path& path, std::size_t spare_vertices);

}  // namespace twister::station_app
