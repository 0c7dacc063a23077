// The device model's command side: the host's bytes through the input buffer into
// commands (CommandInput), the mode commands, the status record and the replies. The
// cycle, the records and the line are in fastrak_device.cpp.
#include "twister/sim/fastrak_device.hpp"

// GCC 12 reports a false -Wrestrict inside std::string concatenation at -O3
// (GCC bug 105329); nothing here overlaps.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wrestrict"
#endif

#include <array>
#include <string>

#include "twister/tracker/fastrak_encoder.hpp"
#include "twister/tracker/liberty_startup.hpp"

namespace twister::sim {

using tracker::Format;
using tracker::ModeCommand;
using tracker::Units;

void FastrakDevice::receive(const std::byte* data, std::size_t size, ports::TimestampUs now) {
  apply_faults(now);
  // A resetting, stalled or hung-up unit understands nothing.
  if (now < busy_until_ || faults_.in_window(now, FaultKind::stall) ||
      faults_.in_window(now, FaultKind::hangup)) {
    return;
  }
  const bool misclock = misclocked(now);
  for (std::size_t i = 0; i < size; ++i) {
    std::byte b = data[i];
    if (misclock && !misclock_byte(b)) continue;
    read_buffered(now);             // what waited is read before this byte
    if (now < busy_until_) return;  // a ^Y earlier in this chunk
    heard(input_.take(static_cast<char>(b), now), now);
  }
}

void FastrakDevice::read_buffered(ports::TimestampUs now) {
  // Bytes that waited in the input buffer while a command was processed are read when
  // it is done, one command after another (a ^Y among them empties the buffer).
  while (input_.buffered_ready(now) && input_.ready_at() >= busy_until_) {
    const ports::TimestampUs at = input_.ready_at();
    heard(input_.take_buffered(), at);
  }
}

void FastrakDevice::heard(CommandInput::Heard what, ports::TimestampUs at) {
  switch (what) {
    case CommandInput::Heard::nothing:
      break;
    case CommandInput::Heard::lost:
      ++counters_.input_lost;
      break;
    case CommandInput::Heard::error:
      error(input_.echo(), input_.error_code(), at);
      break;
    case CommandInput::Heard::command:
      execute(input_.command(), input_.echo(), input_.done());
      input_.hold_until(input_.done());
      break;
    case CommandInput::Heard::who_am_i:  // the text is assumed; VRPN checks the '0'
      ++counters_.commands;
      reply(std::string(1, tracker::kLibertyWhoAmIFirst) + " Polhemus " +
                (config_.model == DeviceModel::patriot ? "PATRIOT" : "LIBERTY") +
                " (twister-sim device model)\r\n",
            input_.done());
      break;
  }
}

void FastrakDevice::execute(const tracker::FastrakCommand& command, std::string_view echo,
                            ports::TimestampUs now) {
  ++counters_.commands;
  if (const auto* mode = std::get_if<tracker::Mode>(&command)) {
    execute_mode(mode->command, now);
  } else {
    parameters_.execute(std::get<tracker::Parameters>(command), echo, now);
  }
}

void FastrakDevice::execute_mode(ModeCommand command, ports::TimestampUs now) {
  switch (command) {
    case ModeCommand::poll:
      for (const int station : active_stations()) queue_record(station, now);
      return;
    case ModeCommand::continuous:
      settings_.continuous = true;
      settings_.output_on = true;
      if (scenario_origin_ == kNotYet) {  // ScenarioClock::first_continuous: t = 0 now
        scenario_origin_ = now;
        faults_.start_at(now);
      }
      return;
    case ModeCommand::polled:
      settings_.continuous = false;
      // The stream stopped: what was left of a line hit's budget has nothing to eat.
      counters_.drop_expired += faults_.expire_drop();
      return;
    case ModeCommand::ascii:
    case ModeCommand::binary: {
      const Format binary = config_.packed16 ? Format::binary16 : Format::binary;
      settings_.protocol.format = command == ModeCommand::ascii ? Format::ascii : binary;
      return;
    }
    case ModeCommand::inches:
    case ModeCommand::centimetres:
      settings_.protocol.units =
          command == ModeCommand::inches ? Units::inches : Units::centimetres;
      return;
    case ModeCommand::status:
      send_status(now);
      return;
    case ModeCommand::factory_defaults: {
      const bool cont = settings_.continuous;
      const ports::TimestampUs busy = busy_until_;
      power_up(now);
      --counters_.resets;
      settings_.continuous = cont;
      busy_until_ = busy;
      return;
    }
    case ModeCommand::reinitialise:
      power_up(now);
      return;
    case ModeCommand::built_in_test:  // accepted, no effect on the model
    case ModeCommand::metal_compensation_on:
    case ModeCommand::metal_compensation_off:
    case ModeCommand::save:
    case ModeCommand::suspend:
    case ModeCommand::resume:
      return;
  }
}

void FastrakDevice::send_status(ports::TimestampUs now) {
  tracker::FastrakStatus st;
  const ActiveStations act = active_stations();
  st.station = static_cast<std::uint8_t>(act.empty() ? 1 : act[cycle_.next_station % act.size()]);
  st.flags = 0x3F0;
  st.binary = settings_.protocol.format != Format::ascii;
  st.centimetres = settings_.protocol.units == Units::centimetres;
  st.continuous = settings_.continuous;
  std::array<std::byte, 64> buf{};
  auto n = tracker::encode_status(st, buf);
  if (n.ok()) queue(std::span<const std::byte>(buf.data(), *n), now);
}

FastrakDevice::ActiveStations FastrakDevice::active_stations() const {
  ActiveStations out;
  for (int s = 1; s <= 4; ++s) {
    if (settings_.protocol.stations[static_cast<std::size_t>(s - 1)].enabled &&
        s <= scenario_.receivers) {
      out.ids[out.count++] = s;
    }
  }
  return out;
}

void FastrakDevice::queue(std::span<const std::byte> bytes, ports::TimestampUs now) {
  counters_.line_overflow += line_.queue(bytes, now, settings_.baud);
}

void FastrakDevice::reply(std::string_view text, ports::TimestampUs at) {
  queue(std::as_bytes(std::span<const char>(text.data(), text.size())), at);
}

void FastrakDevice::error(std::string_view echo, int code, ports::TimestampUs at) {
  ++counters_.command_errors;
  reply("2 E*ERROR* " + std::string(echo) + " *ERROR* EC " + std::to_string(code) +
            " *PS 0 *FL 1 *ST 0\r\n",
        at);
}

}  // namespace twister::sim
