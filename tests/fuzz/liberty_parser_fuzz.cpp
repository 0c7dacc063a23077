// libFuzzer harness for LibertyParser configured as a Liberty (properties:
// liberty_fuzz_common.hpp).
#include "liberty_fuzz_common.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return twister::tracker::fuzz::fuzz_one(twister::tracker::LibertyModel::liberty, data, size);
}
