// Conversions between a math::Frame and the pose a journal record stores (origin, U,
// V; W is rebuilt as U x V). The journal library knows no math types, so the input
// parts that write and read records convert here, in one place.
#pragma once

#include "twister/journal/journal_record.hpp"
#include "twister/math/frame.hpp"

namespace twister::session {

inline journal::JournalPose to_journal(const math::Frame& f) { return {f.origin, f.u, f.v}; }

inline math::Frame from_journal(const journal::JournalPose& p) {
  return math::frame_from_uv(p.origin_m, p.u, p.v);
}

}  // namespace twister::session
