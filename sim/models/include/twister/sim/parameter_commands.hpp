// ParameterCommands: the simulated Fastrak's interpreter of parameter commands
// (tracker::Parameters from the shared command codec: `O l H e Q x v o N B b G` change
// the unit's settings or read them back, `A R I X` are accepted without effect).
// Replies and error records (`2 E*ERROR*... EC n`: -1 missing field, -2 not a number,
// -3 out of range, -5 list too long) go to a ReplySink. Not thread-safe.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "twister/ports/clock.hpp"
#include "twister/sim/unit_settings.hpp"
#include "twister/tracker/fastrak_command.hpp"

namespace twister::sim {

class ReplySink {
 public:
  // A reply line (read-backs), sent when the command is done (`at`).
  virtual void reply(std::string_view text, ports::TimestampUs at) = 0;
  // The error record for the command `echo` (as received) with code `code`.
  virtual void error(std::string_view echo, int code, ports::TimestampUs at) = 0;

 protected:
  ~ReplySink() = default;
};

class ParameterCommands {
 public:
  // liberty_codes: `O` takes and reads back the Liberty family's item codes
  // (docs/liberty-protocol.md §3), kept as the equivalent Fastrak list.
  ParameterCommands(UnitSettings& settings, ReplySink& replies, bool liberty_codes = false)
      : settings_(settings), replies_(replies), liberty_codes_(liberty_codes) {}

  // Runs `command`, done at `at`; `echo` is the command as received (for errors).
  void execute(const tracker::Parameters& command, std::string_view echo, ports::TimestampUs at);

 private:
  using Fields = std::vector<std::string>;
  void output_list(int station, const Fields& f, std::string_view echo, ports::TimestampUs at);
  void station_state(int station, const Fields& f, std::string_view echo, ports::TimestampUs at);
  void hemisphere(int station, const Fields& f, std::string_view echo, ports::TimestampUs at);
  void stylus_mode(const Fields& f, std::string_view echo, ports::TimestampUs at);
  void envelope(int station, const Fields& f, std::string_view echo, ports::TimestampUs at);
  // `x` / `v` (no station): set, macro or read back the filter.
  void filter(tracker::ParameterCommand which, const Fields& f, std::string_view echo,
              ports::TimestampUs at);
  // `N` (tip offset, current units) and `G` (boresight reference angles): s,a,b,c.
  void station_vector(tracker::ParameterCommand which, int station, const Fields& f,
                      std::string_view echo, ports::TimestampUs at);
  void serial_port(const Fields& f, std::string_view echo, ports::TimestampUs at);

  // The list of `O`'s item codes; false: an error was replied.
  bool read_list(const Fields& f, std::string_view echo, ports::TimestampUs at,
                 tracker::OutputList& list);

  UnitSettings& settings_;
  ReplySink& replies_;
  bool liberty_codes_ = false;
};

}  // namespace twister::sim
