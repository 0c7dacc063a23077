#include "station_setup.hpp"

#include <algorithm>

namespace twister::station_app {

hal::Expected<station::StationConfig> make_station_setup(const StationConfig& config) {
  using tracker::Item;
  station::StationConfig c;
  const TrackerConfig& t = config.tracker;
  auto& proto = c.session.protocol;
  proto.format =
      t.format == RecordFormat::binary ? tracker::Format::binary : tracker::Format::ascii;
  proto.units = tracker::Units::inches;
  c.hand_station = {t.left_station, t.right_station};
  const bool stylus = config.buttons.backend == ButtonBackend::stylus;
  for (const std::uint8_t s : c.hand_station) {
    auto& st = proto.stations[static_cast<std::size_t>(s - 1)];
    st.enabled = true;
    // Quaternion: shortest orientation item; the stylus item only where it exists.
    st.list =
        stylus && s == 1
            ? tracker::OutputList::of({Item::position, Item::quaternion, Item::stylus, Item::crlf})
            : tracker::OutputList::of({Item::position, Item::quaternion, Item::crlf});
  }
  c.session.silence_timeout_us = static_cast<std::int64_t>(t.silence_timeout_ms) * 1000;
  c.session.backoff_initial_us = static_cast<std::int64_t>(t.reconnect_interval_ms) * 1000;
  c.session.backoff_max_us = std::max<std::int64_t>(c.session.backoff_initial_us, 8'000'000);
  c.conversion.units = proto.units;
  c.conversion.format = proto.format;
  c.pose_stale_us = std::max<std::int64_t>(200'000, c.session.silence_timeout_us / 2);
  c.checkpoint_interval = config.station.checkpoint_interval;
  c.sculpt.debounce.interval_us.fill(static_cast<ports::TimestampUs>(config.buttons.debounce_ms) *
                                     1000);
  if (stylus) {
    // Paper button map: line 0 = hand 0 grab, line 3 = hand 1 grab.
    if (t.left_station == 1) {
      c.stylus_line[0] = 0;
    } else if (t.right_station == 1) {
      c.stylus_line[0] = 3;
    } else {
      return hal::make_error(
          StatusCode::invalid_argument,
          "buttons.backend = \"stylus\" needs receiver 1 (the stylus) in a hand: set "
          "tracker.left_station or tracker.right_station to 1");
    }
  }
  return c;
}

}  // namespace twister::station_app
