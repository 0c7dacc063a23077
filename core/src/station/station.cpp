#include "twister/station/station.hpp"

#include <glm/vec3.hpp>

#include "twister/journal/journal_reader.hpp"

namespace twister::station {
namespace {

// Bounds per poll() so one chatty source cannot starve the others or the loop.
constexpr int kMaxPosesPerPoll = 64;
constexpr int kMaxEdgesPerPoll = 32;

journal::JournalPose to_journal(const tracker::TrackedFrame& f) {
  return journal::JournalPose{f.origin, f.u, f.v};
}

}  // namespace

Station::Station(ports::ByteStream& tracker, ports::ButtonSource& buttons, ports::Clock& clock,
                 ports::Storage& storage, const StationConfig& config)
    : buttons_(buttons),
      clock_(clock),
      storage_(storage),
      config_(config),
      session_(tracker, clock, config.session),
      debouncer_(config.debounce),
      machine_(config.interaction),
      writer_(storage) {}

Status Station::start() {
  const auto s0 = config_.hand_station[0];
  const auto s1 = config_.hand_station[1];
  if (s0 < 1 || s0 > tracker::kMaxStations || s1 < 1 || s1 > tracker::kMaxStations || s0 == s1) {
    return StatusCode::invalid_argument;
  }
  // Recover: every good record counts towards the sequence; a torn tail (power cut
  // mid-append) is cut off so new records follow the last good one.
  journal::JournalReader reader(storage_);
  TWISTER_TRY(reader.open());
  std::uint32_t records = 0;
  std::uint64_t cut = 0;
  for (;;) {
    auto rec = reader.next();
    if (rec.ok()) {
      records = rec->sequence + 1;
      continue;
    }
    if (rec.status().code() == StatusCode::unavailable) break;
    if (rec.status().code() != StatusCode::data_loss) return rec.status();
    cut = reader.tail_bytes();
    TWISTER_TRY(reader.truncate_tail());
    break;
  }
  TWISTER_TRY(writer_.open());
  next_sequence_ = records;
  started_ = true;
  push_event({StationEventKind::journal_recovered, 0, records, cut, OkStatus(), clock_.now_us()});
  return OkStatus();
}

bool Station::hand_valid(std::uint8_t hand, ports::TimestampUs now_us) const {
  const Hand& h = hands_[hand];
  return h.has_pose && session_.streaming() && now_us - h.pose_time_us <= config_.pose_stale_us;
}

void Station::drain_tracker(ports::TimestampUs now_us) {
  for (int i = 0; i < kMaxPosesPerPoll; ++i) {
    auto pose = session_.poll();
    if (!pose.ok()) break;  // unavailable: nothing now; invalid_argument: bad config
    if (pose->has_button && pose->station >= 1 && pose->station <= tracker::kMaxStations) {
      const auto idx = static_cast<std::size_t>(pose->station - 1);
      const std::int8_t line = config_.stylus_line[idx];
      if (line >= 0 && pose->button != stylus_down_[idx]) {
        stylus_down_[idx] = pose->button;
        ++counters_.button_edges;
        const ports::ButtonEdge edge{static_cast<std::uint8_t>(line), pose->button, now_us};
        if (!debouncer_.feed(edge).ok()) ++counters_.button_errors;
      }
    }
    int hand = -1;
    for (std::uint8_t h = 0; h < input::kHandCount; ++h) {
      if (config_.hand_station[h] == pose->station) hand = h;
    }
    if (hand < 0) {
      ++counters_.foreign_poses;
      continue;
    }
    auto frame = tracker::to_station_frame(*pose, config_.conversion);
    if (!frame.ok()) {
      ++counters_.pose_errors;  // skip: never let an implausible pose move a hand
      continue;
    }
    Hand& h = hands_[static_cast<std::size_t>(hand)];
    h.pose = *frame;
    h.pose_time_us = now_us;
    h.has_pose = true;
    ++counters_.poses;
  }
  const bool streaming = session_.streaming();
  if (streaming != was_streaming_) {
    was_streaming_ = streaming;
    if (!streaming) {
      // Poses from before the loss must not count as valid after re-initialisation.
      // A stylus held at the loss stays "held": no release is invented, so the
      // interaction machine holds the stroke and cancels it after lost_timeout
      // instead of committing it; the first record after re-plug brings the truth.
      for (auto& h : hands_) h.has_pose = false;
    }
    push_event({streaming ? StationEventKind::tracker_streaming : StationEventKind::tracker_lost,
                0, 0, session_.counters().streams_started, OkStatus(), now_us});
  }
}

void Station::drain_buttons(ports::TimestampUs now_us) {
  for (int i = 0; i < kMaxEdgesPerPoll; ++i) {
    auto edge = buttons_.poll();
    if (edge.ok()) {
      buttons_failed_ = false;
      ++counters_.button_edges;
      if (!debouncer_.feed(*edge).ok()) ++counters_.button_errors;
      continue;
    }
    if (edge.status().code() == StatusCode::unavailable) break;
    ++counters_.button_errors;
    if (!buttons_failed_) {
      push_event({StationEventKind::button_source_error, 0, 0, 0, edge.status(), now_us});
    }
    buttons_failed_ = true;
    break;
  }
  for (;;) {
    auto ev = debouncer_.poll(now_us);
    if (!ev.ok()) break;
    config_.buttons.apply(*ev, levels_);
  }
}

Status Station::poll() {
  if (!started_) return StatusCode::failed_precondition;
  const ports::TimestampUs now_us = clock_.now_us();
  drain_tracker(now_us);
  drain_buttons(now_us);
  input::InteractionInputs inputs{};
  for (std::uint8_t h = 0; h < input::kHandCount; ++h) {
    inputs.hands[h].pose_valid = hand_valid(h, now_us);
    inputs.hands[h].position_m = glm::vec3(hands_[h].pose.origin);
    inputs.hands[h].buttons = levels_[h];
  }
  const input::ActionList actions = machine_.step(inputs, now_us);
  for (const input::Action& a : actions.items()) apply(a, now_us);
  return OkStatus();
}

void Station::apply(const input::Action& action, ports::TimestampUs now_us) {
  const std::uint8_t h = action.hand;
  switch (action.kind) {
    case input::ActionKind::grab_begin:
      hands_[h].stroke_start = hands_[h].pose;
      hands_[h].chain_step = 0;
      push_event({StationEventKind::stroke_begin, h, 0, 0, OkStatus(), now_us});
      break;
    case input::ActionKind::freeze:
      commit_stroke(h, now_us);
      hands_[h].stroke_start = hands_[h].pose;
      ++hands_[h].chain_step;
      break;
    case input::ActionKind::commit:
      commit_stroke(h, now_us);
      break;
    case input::ActionKind::cancel:
      ++counters_.strokes_cancelled;
      push_event({StationEventKind::stroke_cancelled, h, 0,
                  static_cast<std::uint64_t>(action.reason), OkStatus(), now_us});
      break;
    case input::ActionKind::refused:
      ++counters_.refused;
      push_event({StationEventKind::refused, h, 0, static_cast<std::uint64_t>(action.reason),
                  OkStatus(), now_us});
      break;
    default:
      break;  // tracking_lost/resumed, moves and the radius gesture need no journal entry
  }
}

void Station::commit_stroke(std::uint8_t hand, ports::TimestampUs now_us) {
  journal::JournalRecord record{};
  record.type = journal::RecordType::stroke;
  record.sequence = next_sequence_;
  record.stroke.method = config_.warp_method;
  record.stroke.hand_mask = static_cast<std::uint8_t>(1u << hand);
  record.stroke.chain_step = hands_[hand].chain_step;
  record.stroke.radius_m = static_cast<double>(machine_.radius_m());
  // The end pose is the hand's last valid pose (the machine commits at it when lost).
  record.stroke.start[hand] = to_journal(hands_[hand].stroke_start);
  record.stroke.end[hand] = to_journal(hands_[hand].pose);
  const Status s = writer_.append(record);
  if (!s.ok()) {
    ++counters_.journal_errors;
    push_event({StationEventKind::journal_error, hand, record.sequence, 0, s, now_us});
    return;
  }
  ++next_sequence_;
  ++counters_.strokes_committed;
  push_event({StationEventKind::stroke_committed, hand, record.sequence, 0, OkStatus(), now_us});
}

void Station::push_event(const StationEvent& event) {
  if (event_count_ == kEventCapacity) {
    ++counters_.events_dropped;
    return;
  }
  events_[(event_head_ + event_count_) % kEventCapacity] = event;
  ++event_count_;
}

Result<StationEvent> Station::next_event() {
  if (event_count_ == 0) return StatusCode::unavailable;
  const StationEvent e = events_[event_head_];
  event_head_ = (event_head_ + 1) % kEventCapacity;
  --event_count_;
  return e;
}

Status Station::flush() { return storage_.sync(); }

}  // namespace twister::station
