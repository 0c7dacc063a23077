// StationLink: the coordinator of admission, mesh mirror, live stream and queues,
// and the route of the display's commands into the session.
#include "twister/station/station_link.hpp"

#include "twister/station/station.hpp"

namespace twister::station {

StationLink::StationLink(ports::LinkPort& port, StationLinkStorage storage,
                         const StationLinkConfig& config, const StationLinkOptions& options)
    : queues_(port, storage.out),
      admission_(port, queues_, *this, options, config.handshake_timeout_us),
      mirror_(queues_, MeshMirrorStorage{storage.x, storage.y, storage.z, storage.triangle_indices},
              options.spectator_staging),
      live_(queues_, LiveStreamConfig{config.live_interval_us, config.status_interval_us,
                                      config.stroke_repeat_us, config.workspace}),
      spectators_(options.spectators,
                  SpectatorConfig{options.max_spectators, options.spectator_stall_us},
                  LiveStreamConfig{config.live_interval_us, config.status_interval_us,
                                   config.stroke_repeat_us, config.workspace},
                  options.spectator_queues) {}

Status StationLink::start(const session::SculptSession& session) {
  if (queues_.bulk_capacity() < 4 * link::kMaxFrameBytes) return StatusCode::resource_exhausted;
  TWISTER_TRY(mirror_.start(session.mesh()));
  TWISTER_TRY(spectators_.start());
  last_sequence_ = session.next_sequence();
  started_ = true;
  return ok_status();
}

void StationLink::step(const session::SculptSession& session, const StationStatus& status,
                       ports::TimestampUs now_us) {
  now_us_ = now_us;
  admission_.poll(now_us);
  if (session.next_sequence() != last_sequence_) {
    last_sequence_ = session.next_sequence();
    mirror_.track(session.mesh(), admitted(), spectators_.any_current());
    spectators_.on_commit(mirror_.staged());  // before the main queue's flush moves it
  }
  if (admitted()) {
    mirror_.send();
    const link::DecoderCounters d = admission_.decoder_counters();
    live_.poll(session, status,
               LinkFacts{mirror_.version(), d.bad_crc + d.bad_cobs + d.bad_payload,
                         static_cast<std::uint32_t>(spectators_.count())},
               now_us);
  }
  queues_.flush();  // the main display first: spectators never delay it
  spectators_.poll(session, status, mirror_, now_us);
}

template <class Submit>
void StationLink::route_commands(Submit submit) {
  for (const link::Command& command : commands_) {
    if (submit(session_command(command)).ok()) {
      ++commands_routed_;
    } else {
      ++commands_refused_;  // the session's queue is full
    }
  }
  commands_.clear();
}

void StationLink::poll(Station& station, ports::TimestampUs now_us) {
  if (!started_) return;
  step(station.sculpt(), station.status(), now_us);
  if (admitted()) visitor_.send(station, queues_, now_us);
  spectators_.send_visitor(station, now_us);
  route_commands([&station](const session::SessionCommand& c) { return station.submit(c); });
  refresh_counters();
}

void StationLink::poll(session::SculptSession& session, const StationStatus& status,
                       ports::TimestampUs now_us) {
  if (!started_) return;
  step(session, status, now_us);
  route_commands([&session](const session::SessionCommand& c) { return session.submit(c); });
  refresh_counters();
}

void StationLink::on_admitted(const MeshIdentity& holds) {
  mirror_.resync(holds);
  live_.restart();
  visitor_.restart();
}

bool StationLink::on_spectator(const MeshIdentity& holds) {
  return spectators_.admit(mirror_, holds, now_us_);
}

void StationLink::on_display_lost() {
  queues_.clear();
  mirror_.cancel();
}

void StationLink::on_resend_request() { mirror_.want_full(); }

void StationLink::on_command(const link::Command& command) {
  if (!commands_.push_back(command).ok()) ++commands_refused_;
}

void StationLink::say_goodbye() {
  spectators_.say_goodbye();
  if (!connected()) return;
  (void)queues_.urgent(link::Bye{link::ByeReason::shutdown});
  queues_.flush();
}

void StationLink::refresh_counters() {
  const AdmissionCounters& a = admission_.counters();
  const MirrorCounters& m = mirror_.counters();
  const LiveCounters& l = live_.counters();
  counters_ = StationLinkCounters{a.connects,
                                  a.disconnects,
                                  m.full_sends,
                                  m.commits_sent,
                                  l.live_sent,
                                  l.live_dropped,
                                  a.resend_requests,
                                  a.newcomers,
                                  a.displaced,
                                  a.refused,
                                  commands_routed_,
                                  a.commands_refused + commands_refused_,
                                  static_cast<std::uint32_t>(spectators_.count()),
                                  spectators_.totals()};
}

session::SessionCommand session_command(const link::Command& c) {
  session::SessionCommand out;
  out.hand = 0;  // a display's command belongs to no hand
  switch (c.kind) {
    case link::CommandKind::undo:
      out.kind = session::SessionCommandKind::undo;
      break;
    case link::CommandKind::redo:
      out.kind = session::SessionCommandKind::redo;
      break;
    case link::CommandKind::next_method:
      out.kind = session::SessionCommandKind::next_method;
      break;
    case link::CommandKind::set_method:
      out.kind = session::SessionCommandKind::set_method;
      out.method = static_cast<math::WarpMethod>(c.method);
      break;
    case link::CommandKind::cycle_symmetry:
      out.kind = session::SessionCommandKind::cycle_symmetry;
      break;
    case link::CommandKind::new_sculpture:
      out.kind = session::SessionCommandKind::new_sculpture;
      break;
    case link::CommandKind::undo_new_sculpture:
      out.kind = session::SessionCommandKind::undo_new_sculpture;
      break;
  }
  return out;
}

}  // namespace twister::station
