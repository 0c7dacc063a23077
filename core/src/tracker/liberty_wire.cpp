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

Status to_fastrak_list(const LibertyOutputList& liberty, OutputList& out) {
  out = {};
  const auto add = [&out](Item item) {
    if (out.count >= kMaxItems) return false;
    out.items[out.count++] = item;
    return true;
  };
  for (std::size_t i = 0; i < liberty.count && i < kLibertyMaxItems; ++i) {
    bool ok = true;
    switch (liberty.items[i]) {
      case LibertyItem::space:
        ok = add(Item::space);
        break;
      case LibertyItem::crlf:
        ok = add(Item::crlf);
        break;
      case LibertyItem::position:
      case LibertyItem::position_ext:
        ok = add(Item::position);
        break;
      case LibertyItem::euler:
      case LibertyItem::euler_ext:
        ok = add(Item::euler);
        break;
      case LibertyItem::dcm:
        ok = add(Item::dcm_x) && add(Item::dcm_y) && add(Item::dcm_z);
        break;
      case LibertyItem::quaternion:
        ok = add(Item::quaternion);
        break;
      case LibertyItem::stylus:
        ok = add(Item::stylus);
        break;
      default:
        return StatusCode::invalid_argument;
    }
    if (!ok) return StatusCode::invalid_argument;
  }
  return Status{};
}

Result<std::size_t> encode_liberty_output_list(int station, const LibertyOutputList& list,
                                               std::span<char> out) {
  if (station < 1 || station > kLibertyMaxStations || list.count == 0 ||
      list.count > kLibertyMaxItems) {
    return StatusCode::invalid_argument;
  }
  std::size_t n = 0;
  const auto put = [&](char c) {
    if (n >= out.size()) return false;
    out[n++] = c;
    return true;
  };
  const auto put_number = [&](unsigned v) {
    if (v >= 10 && !put(static_cast<char>('0' + v / 10))) return false;
    return put(static_cast<char>('0' + v % 10));
  };
  bool ok = put('O') && put_number(static_cast<unsigned>(station));
  for (std::size_t i = 0; i < list.count; ++i) {
    ok = ok && put(',') && put_number(static_cast<unsigned>(list.items[i]));
  }
  ok = ok && put(kCr);
  if (!ok) return StatusCode::out_of_range;
  return n;
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
