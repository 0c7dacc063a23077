// The kiosk's fixed camera from a TOML file (toml++, as the station's config):
//
//   [camera]
//   azimuth_deg = 200.0      # around the up axis
//   elevation_deg = 25.0     # above the horizontal, -89 .. 89
//   zoom = 1.0               # 1 frames the model; > 1 closer (0.05 .. 50)
//   fov_deg = 35.0           # vertical field of view, 5 .. 120
//   up = [0.0, 0.0, -1.0]    # world up (tracker frame: +Z points down)
//   target = [0.55, 0.0, 0.1]  # optional: look here (metres) instead of the model's centre
//   fixed = true             # mouse and camera keys leave it alone (default true)
//
//   [attract]                # optional: attract mode's turntable of recent sculptures
//   archive = "/var/lib/twister/archive"  # the station's [exhibit] archive_dir
//   models = 6               # the newest archives shown, 1 .. 32
//   seconds = 8.0            # each shown this long, 1 .. 600
//
// Every key is optional; an unknown key, a wrong type or a value out of range is an
// error naming the file, the key and the expected form.
#pragma once

#include <string>

#include "camera.hpp"
#include "twister/hal/expected.hpp"

namespace twister::bridge {

// Attract mode's showcase (twister-bridge --attract-archive and the kiosk file's
// [attract]; AttractShowcase).
struct AttractConfig {
  std::string archive;  // "": none (the station's model turns)
  int models = 6;
  double seconds = 8.0;
};

struct CameraConfig {
  ViewConfig view{};
  bool fixed = true;
  AttractConfig attract{};
};

// Error invalid_argument (syntax, key, type, range) or io_error (cannot read).
hal::Expected<CameraConfig> parse_camera_config(const std::string& text,
                                                const std::string& file_name);
hal::Expected<CameraConfig> load_camera_config(const std::string& path);

}  // namespace twister::bridge
