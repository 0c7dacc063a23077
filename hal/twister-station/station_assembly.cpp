#include "station_assembly.hpp"

#include "station_setup.hpp"
#include "twister/meshio/obj_file.hpp"

namespace twister::station_app {
namespace {

hal::Expected<void> open_journal(hal::PosixFileStorage& journal, const std::string& path) {
  if (const Status s = journal.open({.path = path}); !s.ok()) {
    return hal::Error{s, "cannot open journal " + path + " (" + s.name() + ", errno " +
                             std::to_string(journal.last_errno()) + ")"};
  }
  return {};
}

hal::Expected<void> start_core(station::Station& core, const std::string& journal_path) {
  const Status s = core.start();
  if (s.ok()) return {};
  const char* why = s.name();
  if (s.code() == StatusCode::data_loss) {
    why = "is not a Twister journal, or does not fit this mesh (left untouched)";
  }
  return hal::Error{s, "journal " + journal_path + ": " + why};
}

}  // namespace

WorkMemory::WorkMemory(std::size_t vertex_capacity, std::size_t triangle_capacity)
    : live_x_(vertex_capacity),
      live_y_(vertex_capacity),
      live_z_(vertex_capacity),
      weights1_(vertex_capacity),
      weights2_(vertex_capacity),
      plan_indices_(vertex_capacity),
      undo_changes_(input::kDefaultUndoChanges),
      undo_entries_(input::kDefaultUndoEntries),
      refiner_(vertex_capacity, triangle_capacity),
      undo_triangles_(input::kDefaultUndoTriangleChanges),
      normal_x_(vertex_capacity),
      normal_y_(vertex_capacity),
      normal_z_(vertex_capacity) {}

input::SculptStorage WorkMemory::storage() {
  return input::SculptStorage{live_x_,
                              live_y_,
                              live_z_,
                              math::WarpPlanStorage{plan_indices_, weights1_, weights2_},
                              undo_changes_,
                              undo_entries_,
                              refiner_.storage(),
                              undo_triangles_,
                              mesh::NormalColumns{normal_x_, normal_y_, normal_z_}};
}

hal::Expected<std::unique_ptr<meshio::MeshBuffer>> load_station_mesh(
    const std::filesystem::path& path, std::size_t spare_vertices) {
  meshio::ObjLoad loaded = meshio::load_obj(path, spare_vertices, 2 * spare_vertices);
  if (!loaded.status.ok()) {
    return hal::Error{loaded.status, "mesh " + path.string() + ": " + loaded.message};
  }
  return std::move(loaded.buffer);
}

hal::Expected<std::unique_ptr<StationParts>> assemble_station(const StationConfig& config,
                                                              const AssemblyOptions& options) {
  auto setup = make_station_setup(config);
  if (!setup) return setup.error();
  auto backends = make_backends(config);
  if (!backends) return backends.error();
  auto parts = std::make_unique<StationParts>();
  parts->backends = std::move(*backends);
  if (auto opened = open_journal(parts->journal, config.station.journal); !opened) {
    return opened.error();
  }
  parts->mesh_path = config.station.mesh;
  if (parts->mesh_path.is_relative()) parts->mesh_path = options.config_dir / parts->mesh_path;
  auto model = load_station_mesh(parts->mesh_path, config.station.spare_vertices);
  if (!model) return model.error();
  parts->model = std::move(*model);
  mesh::Mesh& mesh = parts->model->mesh();
  parts->work = std::make_unique<WorkMemory>(mesh.vertex_capacity(), mesh.triangle_capacity());
  Backends& b = parts->backends;
  parts->core = std::make_unique<station::Station>(*b.tracker, *b.buttons, *b.clock, parts->journal,
                                                   mesh, parts->work->storage(), *setup);
  if (auto started = start_core(*parts->core, config.station.journal); !started) {
    return started.error();
  }
  if (!options.link_address.empty()) {
    if (auto opened = parts->display.open(options.link_address, parts->core->sculpt()); !opened) {
      return opened.error();
    }
  }
  return parts;
}

}  // namespace twister::station_app
