// The table of Polhemus USB ids (docs/hardware.md, "USB trackers", gives each source).
#include "twister/hal/polhemus_usb.hpp"

#include <array>

namespace twister::hal {
namespace {

using M = PolhemusUsbModel;

// Ids and firmware files: Polhemus' udev rules (90-Polhemus_trkr.rules as shipped by
// polhemus_ros_driver); the Latus id 0xff20 also in VRPN's vrpn_Tracker_LibertyHS.
constexpr std::array<PolhemusUsbId, 13> kIds{{
    {0x0002, M::fastrak, false, "FASTRAK", "", ""},
    {0x0001, M::fastrak, true, "FASTRAK", "FastrakUSB.hex (fxload -t fx)", ""},
    {0x0003, M::fastrak3, false, "FASTRAK 3", "", ""},
    {0xff12, M::liberty, false, "Liberty", "", ""},
    {0xff11, M::liberty, true, "Liberty", "LbtyUsb.hex (fxload -t fx)", ""},
    {0xef12, M::patriot, false, "Patriot", "", ""},
    {0xef11, M::patriot, true, "Patriot", "PatriotUSB.hex (fxload -t fx)", ""},
    {0xff20, M::latus, false, "Liberty HS / Latus", "", ""},
    {0xff21, M::latus, true, "Liberty HS / Latus", "LbtyUsbHS.hex (fxload -t fx2)", ""},
    {0xef20, M::unsupported, false, "Patriot HS", "",
     "its frames are not documented in the sources this station was written from"},
    {0xef21, M::unsupported, true, "Patriot HS", "PatriotUSB2.hex (fxload -t fx2)",
     "its frames are not documented in the sources this station was written from"},
    {0xbf01, M::unsupported, false, "Viper", "", "it speaks a different, binary protocol"},
    {0xcf01, M::unsupported, false, "G4", "", "it is reached only through Polhemus' SDK"},
}};

}  // namespace

const PolhemusUsbId* find_polhemus_usb_id(std::uint16_t vendor_id, std::uint16_t product_id) {
  if (vendor_id != kPolhemusVendorId) return nullptr;
  for (const PolhemusUsbId& id : kIds) {
    if (id.product_id == product_id) return &id;
  }
  return nullptr;
}

std::uint16_t polhemus_running_id(PolhemusUsbModel model) {
  for (const PolhemusUsbId& id : kIds) {
    if (id.model == model && !id.needs_firmware) return id.product_id;
  }
  return 0;
}

const char* polhemus_model_name(PolhemusUsbModel model) {
  switch (model) {
    case M::fastrak:
      return "FASTRAK";
    case M::fastrak3:
      return "FASTRAK 3";
    case M::liberty:
      return "Liberty";
    case M::patriot:
      return "Patriot";
    case M::latus:
      return "Liberty HS / Latus";
    case M::unsupported:
      break;
  }
  return "unsupported Polhemus unit";
}

}  // namespace twister::hal
