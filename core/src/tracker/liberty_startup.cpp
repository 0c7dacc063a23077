// The Liberty family's start-up commands (liberty_startup.hpp).
#include "twister/tracker/liberty_startup.hpp"

#include "twister/base/assert.hpp"

namespace twister::tracker {

std::size_t liberty_ladder(LibertyModel family, int rung, std::span<char> out) {
  std::size_t n = 0;
  const auto put = [&](char c) {
    if (n < out.size()) out[n++] = c;
  };
  if (family != LibertyModel::latus) put(kCr);  // VRPN's Liberty driver; its LibertyHS not
  put('F');
  put('0');
  put(kCr);
  if (rung >= 3) {
    put(kCtrlY);
    put(kCr);
  }
  put(kLibertyPoll);
  return n;
}

Result<std::size_t> encode_liberty_filter(char letter, const FilterSetting& setting,
                                          std::span<char> out) {
  if (setting.mode == FilterSetting::Mode::leave) return std::size_t{0};
  // The Fastrak's parameters and their three decimals, under the Liberty's letter.
  const ParameterCommand which = letter == kLibertyAttitudeFilter
                                     ? ParameterCommand::attitude_filter
                                     : ParameterCommand::position_filter;
  Parameters p;
  if (setting.mode == FilterSetting::Mode::off) {
    p.command = which;
    const bool ok = p.append("0,1,0,0");  // FLOW = 1: no filtering (VRPN)
    TWISTER_ASSERT(ok);
  } else {
    const auto set = filter_command(which, setting);
    TWISTER_ASSERT(set.has_value());
    p = *set;
  }
  const Result<std::size_t> n = encode(FastrakCommand{p}, out);
  if (!n.ok()) return n;
  out[0] = letter;
  return n;
}

}  // namespace twister::tracker
