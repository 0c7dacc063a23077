// FastrakSession's models: their names, and the Liberty family's start-up
// (docs/liberty-protocol.md §9): the configuration commands and the WhoAmI check. The
// state machine is fastrak_session.cpp.
#include <array>
#include <string_view>
#include <utility>

#include "twister/tracker/fastrak_session.hpp"
#include "twister/tracker/liberty_startup.hpp"

namespace twister::tracker {

const char* session_state_name(SessionState s) {
  switch (s) {
    case SessionState::backoff:
      return "backoff";
    case SessionState::ladder:
      return "ladder";
    case SessionState::settle:
      return "settle";
    case SessionState::await_status:
      return "await_status";
    case SessionState::configuring:
      return "configuring";
    case SessionState::verify_status:
      return "verify_status";
    case SessionState::streaming:
      return "streaming";
  }
  return "unknown";
}

const char* tracker_model_name(TrackerModel model) {
  switch (model) {
    case TrackerModel::fastrak:
      return "FASTRAK";
    case TrackerModel::liberty:
      return "Liberty";
    case TrackerModel::patriot:
      return "Patriot";
    case TrackerModel::latus:
      return "Latus";
  }
  return "unknown";
}

bool FastrakSession::build_liberty_commands() {
  // docs/liberty-protocol.md §9: no station enables (the unit reports the sensors
  // plugged in) and no stylus mode (the drivers leave it); each line ends with CR.
  bool ok = true;
  for (int s = 1; s <= kMaxStations; ++s) {
    if (!config_.protocol.stations[static_cast<std::size_t>(s - 1)].enabled) continue;
    // The family's own item codes (§3), as the parser frames them.
    ok = ok && add_liberty_list(s) &&
         add_command(hemisphere_command(s, config_.hemisphere[static_cast<std::size_t>(s - 1)]));
  }
  std::array<char, kMaxCommandBytes> text{};
  for (const auto& [letter, setting] :
       {std::pair{kLibertyPositionFilter, config_.position_filter},
        std::pair{kLibertyAttitudeFilter, config_.attitude_filter}}) {
    const Result<std::size_t> n = encode_liberty_filter(letter, setting, text);
    ok = ok && n.ok() && (*n == 0 || add_text(std::string_view(text.data(), *n)));
  }
  if (config_.model == TrackerModel::latus) ok = ok && add_text(kLatusUsbBufferingOff);
  const bool inches = config_.protocol.units == Units::inches;
  ok = ok && add_text(inches ? kLibertyInches : kLibertyCentimetres);
  return ok && add_text(kLibertyBinary);
}

bool FastrakSession::add_text(std::string_view text) {
  if (text.size() + 1 > commands_.data.size() - commands_.len) return false;
  for (const char c : text) commands_.data[commands_.len++] = c;
  commands_.data[commands_.len++] = '\0';
  return true;
}

bool FastrakSession::add_liberty_list(int station) {
  const auto room = std::span<char>(commands_.data).subspan(commands_.len);
  const auto& list = parsers_.liberty.config().stations[static_cast<std::size_t>(station - 1)].list;
  const Result<std::size_t> n = encode_liberty_output_list(station, list, room);
  if (!n.ok() || *n >= room.size()) return false;
  commands_.len += *n;
  commands_.data[commands_.len++] = '\0';
  return true;
}

void FastrakSession::judge_whoami(ports::TimestampUs now) {
  if (flags_.whoami_first != kLibertyWhoAmIFirst) {  // not a WhoAmI reply: as a bad status
    ++counters_.status_mismatch;
    if (recovery_.rung < config_.reset_rung_limit) ++recovery_.rung;
    fault(now);
    return;
  }
  stream_.discard_input();
  parsers_.reset();
  rx_.len = rx_.pos = 0;
  flags_.whoami_first = 0;
  commands_.pos = 0;
  timers_.deadline = now;
  enter(SessionState::configuring);
}

}  // namespace twister::tracker
