// Liberty family wire facts: tags, item widths, list translation, configuration checks.
#include "twister/tracker/liberty_wire.hpp"

namespace twister::tracker {

std::array<char, 2> frame_tag(LibertyModel model) {
  switch (model) {
    case LibertyModel::liberty:
      return {'L', 'Y'};
    case LibertyModel::patriot:
      return {'P', 'A'};
    case LibertyModel::latus:
      return {'L', 'U'};
  }
  return {'L', 'Y'};
}

const char* liberty_model_name(LibertyModel model) {
  switch (model) {
    case LibertyModel::liberty:
      return "liberty";
    case LibertyModel::patriot:
      return "patriot";
    case LibertyModel::latus:
      return "latus";
  }
  return "unknown";
}

bool is_supported_liberty_item(std::uint8_t code) { return code <= 11; }

std::size_t liberty_item_width(LibertyItem item) {
  switch (item) {
    case LibertyItem::space:
      return 1;
    case LibertyItem::crlf:
      return 2;
    case LibertyItem::position:
    case LibertyItem::position_ext:
    case LibertyItem::euler:
    case LibertyItem::euler_ext:
      return 12;
    case LibertyItem::dcm:
      return 36;
    case LibertyItem::quaternion:
      return 16;
    case LibertyItem::timestamp:
    case LibertyItem::frame_count:
    case LibertyItem::stylus:
    case LibertyItem::distortion:
      return 4;
  }
  return 0;
}

std::size_t liberty_body_length(const LibertyOutputList& list) {
  std::size_t n = 0;
  for (std::size_t i = 0; i < list.count && i < kLibertyMaxItems; ++i) {
    n += liberty_item_width(list.items[i]);
  }
  return n;
}

Status to_liberty_list(const OutputList& fastrak, LibertyOutputList& out) {
  out = {};
  bool dcm_done = false;
  for (std::size_t i = 0; i < fastrak.count; ++i) {
    LibertyItem item{};
    switch (fastrak.items[i]) {
      case Item::space:
        item = LibertyItem::space;
        break;
      case Item::crlf:
        item = LibertyItem::crlf;
        break;
      case Item::position:
      case Item::position_ext:
        item = LibertyItem::position;
        break;
      case Item::euler:
      case Item::euler_ext:
        item = LibertyItem::euler;
        break;
      case Item::dcm_x:
      case Item::dcm_y:
      case Item::dcm_z:
      case Item::dcm_x_ext:
      case Item::dcm_y_ext:
      case Item::dcm_z_ext:
        // The Liberty sends all three rows as one item.
        if (dcm_done) continue;
        dcm_done = true;
        item = LibertyItem::dcm;
        break;
      case Item::quaternion:
      case Item::quaternion_ext:
        item = LibertyItem::quaternion;
        break;
      case Item::stylus:
      case Item::stylus_ext:
        item = LibertyItem::stylus;
        break;
      default:
        return StatusCode::invalid_argument;
    }
    if (out.count >= kLibertyMaxItems) return StatusCode::invalid_argument;
    out.items[out.count++] = item;
  }
  return Status{};
}

std::size_t liberty_size_value(std::size_t body, LibertySizeField field) {
  return field == LibertySizeField::body ? body : body + kLibertyHeaderBytes;
}

Status to_liberty_config(const FastrakConfig& fastrak, LibertyModel model, LibertyConfig& out) {
  out = {};
  out.model = model;
  out.units = fastrak.units;
  for (std::size_t i = 0; i < fastrak.stations.size(); ++i) {
    const ReceiverConfig& st = fastrak.stations[i];
    out.stations[i].enabled = st.enabled;
    if (!st.enabled) continue;
    const Status s = to_liberty_list(st.list, out.stations[i].list);
    if (!s.ok()) return s;
  }
  return Status{};
}

Status validate(const LibertyConfig& config) {
  bool any = false;
  for (const LibertyStationConfig& st : config.stations) {
    if (!st.enabled) continue;
    any = true;
    if (st.list.count == 0 || st.list.count > kLibertyMaxItems) {
      return StatusCode::invalid_argument;
    }
    for (std::size_t i = 0; i < st.list.count; ++i) {
      if (!is_supported_liberty_item(static_cast<std::uint8_t>(st.list.items[i]))) {
        return StatusCode::invalid_argument;
      }
    }
    if (liberty_body_length(st.list) > kLibertyMaxBodyBytes) return StatusCode::invalid_argument;
  }
  if (!any) return StatusCode::invalid_argument;
  return Status{};
}

}  // namespace twister::tracker
