#include "twister/sim/unit_settings.hpp"

namespace twister::sim {

void UnitSettings::power_up(const PowerUpSettings& start) {
  protocol = {};
  protocol.format = start.format;
  for (int s = 0; s < 4; ++s) {
    protocol.stations[static_cast<std::size_t>(s)].enabled = s < start.receivers;
  }
  continuous = start.continuous;
  output_on = true;
  stylus_mode = 1;
  for (auto& h : hemisphere) h = {1.0, 0.0, 0.0};
  for (auto& e : envelope) e = {180.0, 90.0, 180.0, -180.0, -90.0, -180.0};
  filter = {start.position_filter, start.attitude_filter};
  tip_offset_in = {};
  boresight_on = {};
  boresight_requests = {};
  boresight_reference_deg = {};
  baud = start.baud;  // `o` is not saved: power-up uses the switches' rate
}

}  // namespace twister::sim
