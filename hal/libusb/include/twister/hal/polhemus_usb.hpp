// The Polhemus trackers this station knows on USB (vendor 0x0f44), by product id:
// which model, whether the id is the one a unit shows before its firmware is loaded,
// and the firmware file Polhemus' udev rules load into it with fxload. Facts and their
// sources: docs/hardware.md ("USB trackers"). Plain data; no libusb here.
#pragma once

#include <cstdint>

namespace twister::hal {

inline constexpr std::uint16_t kPolhemusVendorId = 0x0f44;

// The models the station reads (FASTRAK and FASTRAK 3 send Fastrak records, the others
// Liberty-family frames), then those it recognises but cannot read.
enum class PolhemusUsbModel : std::uint8_t {
  fastrak,
  fastrak3,
  liberty,
  patriot,
  latus,
  unsupported,
};

// Bit of `model` in a mask of wanted models (PolhemusUsbIds::mask).
constexpr std::uint8_t polhemus_model_bit(PolhemusUsbModel model) {
  return static_cast<std::uint8_t>(1u << static_cast<unsigned>(model));
}
inline constexpr std::uint8_t kAnyReadablePolhemus =
    polhemus_model_bit(PolhemusUsbModel::fastrak) | polhemus_model_bit(PolhemusUsbModel::fastrak3) |
    polhemus_model_bit(PolhemusUsbModel::liberty) | polhemus_model_bit(PolhemusUsbModel::patriot) |
    polhemus_model_bit(PolhemusUsbModel::latus);

struct PolhemusUsbId {
  std::uint16_t product_id = 0;
  PolhemusUsbModel model = PolhemusUsbModel::unsupported;
  bool needs_firmware = false;  // the id before fxload; the unit re-enumerates afterwards
  const char* name = "";        // "Liberty", "FASTRAK 3", ...
  const char* firmware = "";    // Polhemus' file fxload loads ("" when none is needed)
  const char* note = "";        // why an unsupported unit cannot be read
};

// The entry for a vendor/product pair; nullptr when it is no Polhemus tracker known here.
const PolhemusUsbId* find_polhemus_usb_id(std::uint16_t vendor_id, std::uint16_t product_id);

// The running (firmware loaded) product id of a readable model's first listed id, for
// the log ("0xff12" for liberty); 0 for unsupported.
std::uint16_t polhemus_running_id(PolhemusUsbModel model);

const char* polhemus_model_name(PolhemusUsbModel model);

}  // namespace twister::hal
