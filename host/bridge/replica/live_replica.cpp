// SceneReplica: the hands, the radius and the live stroke. The stroke's weights come
// from a math::WarpPlan built from the exact start frames, once per segment and
// mesh version; per hands update the end frames come from the compact samples and
// the screws from link::live_screw, which turns the way the station turned.
#include <algorithm>
#include <cmath>

#include "replica_plan.hpp"
#include "scene_replica.hpp"
#include "twister/link/math_conversion.hpp"
#include "twister/math/decay.hpp"
#include "twister/math/warp_kernels.hpp"

namespace twister::bridge {
namespace {

void set_buttons(HandView& v, std::uint8_t bits) {
  v.grab = (bits & link::kButtonGrab) != 0;
  v.radius = (bits & link::kButtonRadius) != 0;
  v.freeze = (bits & link::kButtonFreeze) != 0;
  v.move_object = (bits & link::kButtonMoveObject) != 0;
}

}  // namespace

math::SymmetrySpec stroke_symmetry(const link::StrokeBegin& s) {
  return {static_cast<math::SymmetryKind>(s.symmetry[0]), s.symmetry[1], s.symmetry[2],
          s.symmetry[3]};
}

void SceneReplica::on_stroke(const link::StrokeBegin& s) {
  if (stroke_known_ && s.stroke == stroke_.stroke && s.mesh_version == stroke_.mesh_version) {
    return;  // the once-a-second repeat of the segment we hold
  }
  stroke_ = s;
  stroke_known_ = true;
  plan_.reset();
}

bool SceneReplica::ensure_plan() {
  if (plan_ && plan_->stroke == stroke_.stroke) return plan_->plan != nullptr;
  plan_ = std::make_unique<Plan>();
  plan_->stroke = stroke_.stroke;
  live_.symmetric_gpu.ready = false;
  const std::size_t n = mesh_.vertex_count();
  plan_->indices.resize(n);
  plan_->w1.resize(n);
  plan_->w2.resize(n);
  const math::SymmetrySpec spec = stroke_symmetry(stroke_);
  math::SymmetryGroup group;
  if (!group.set(spec).ok()) {
    ++counters_.plan_errors;  // a group the station would not have built
    return false;
  }
  plan_->symmetry = group.trivial() ? nullptr : std::make_unique<meshio::SymmetryBuffer>(n);
  auto plan = std::make_unique<math::WarpPlan>(
      math::WarpPlanStorage{plan_->indices, plan_->w1, plan_->w2,
                            plan_->symmetry ? plan_->symmetry->plan_symmetry() : nullptr});
  std::array<math::Frame, 2> start{};
  std::size_t hands = 0;
  for (std::size_t h = 0; h < link::kLinkHands; ++h) {
    if ((stroke_.hand_mask & (1u << h)) != 0) start[hands++] = stroke_.start[h];
  }
  live_.weight1.assign(n, 0.0F);
  live_.weight2.assign(n, 0.0F);
  live_.gradient1.assign(3 * n, 0.0F);
  live_.gradient2.assign(3 * n, 0.0F);
  live_.weights_changed = true;
  const math::ConstVertexColumns rest{mesh_.x, mesh_.y, mesh_.z};
  if (!plan->build(rest, std::span<const math::Frame>(start.data(), hands), stroke_.radius_m,
                   static_cast<math::WarpMethod>(stroke_.method), group)
           .ok()) {
    ++counters_.plan_errors;
    return false;
  }
  const auto idx = plan->indices();
  const auto w1 = plan->weights(0);
  const auto w2 = plan->weights(1);
  for (std::size_t k = 0; k < idx.size(); ++k) {
    live_.weight1[idx[k]] = w1[k];
    if (!w2.empty()) live_.weight2[idx[k]] = w2[k];
  }
  plan_->plan = std::move(plan);
  fill_gradients(start, hands);
  build_symmetric_gpu();
  return true;
}

void SceneReplica::fill_gradients(const std::array<math::Frame, 2>& start, std::size_t hands) {
  const std::size_t n = mesh_.vertex_count();
  const double step = 1e-3 * stroke_.radius_m;
  for (std::size_t h = 0; h < hands; ++h) {
    const glm::dvec3 grab = start[h].origin;
    const glm::dvec3 other = start[1 - h].origin;
    const glm::dvec3* other_ptr = hands == 2 ? &other : nullptr;
    const std::vector<float>& w = h == 0 ? live_.weight1 : live_.weight2;
    std::vector<float>& g = h == 0 ? live_.gradient1 : live_.gradient2;
    for (std::size_t i = 0; i < n; ++i) {
      if (w[i] <= 0.0F) continue;
      const glm::dvec3 p(mesh_.x[i], mesh_.y[i], mesh_.z[i]);
      for (int a = 0; a < 3; ++a) {
        glm::dvec3 e(0.0);
        e[a] = step;
        const double up = math::hand_weight(grab, other_ptr, stroke_.radius_m, p + e);
        const double down = math::hand_weight(grab, other_ptr, stroke_.radius_m, p - e);
        g[3 * i + static_cast<std::size_t>(a)] = static_cast<float>((up - down) / (2.0 * step));
      }
    }
  }
}

void SceneReplica::on_hands(const link::Hands& h) {
  ++counters_.live_frames;
  if (hands_sequence_known_ && h.sequence != hands_sequence_) {
    counters_.live_missed += static_cast<std::uint16_t>(h.sequence - hands_sequence_);
  }
  hands_sequence_ = static_cast<std::uint16_t>(h.sequence + 1);
  hands_sequence_known_ = true;
  radius_m_ = h.radius_m;
  const bool stroke_on = (h.flags & link::kStrokeActive) != 0;
  const bool stroke_ok =
      stroke_on && stroke_known_ && static_cast<std::uint16_t>(stroke_.stroke) == h.stroke;
  for (std::size_t k = 0; k < link::kLinkHands; ++k) {
    HandView& v = hands_[k];
    v.tracked = (h.flags & (link::kHandTracked0 << k)) != 0;
    v.present = (h.flags & (link::kHandSample0 << k)) != 0;
    v.in_stroke = stroke_ok && (stroke_.hand_mask & (1u << k)) != 0;
    set_buttons(v, static_cast<std::uint8_t>(h.buttons >> (4 * k)));
    if (!v.present) continue;
    if (stroke_on && !stroke_ok) {
      v.present = false;  // relative to a start frame we do not hold yet
    } else if (v.in_stroke) {
      v.pose = link::live_end_frame(stroke_.start[k], h.hands[k]);
    } else {
      v.pose = link::from_compact(h.hands[k]);
    }
  }
  update_live(h);
}

void SceneReplica::update_live(const link::Hands& h) {
  const bool was_active = live_.active;
  live_.active = false;
  if ((h.flags & link::kStrokeActive) == 0) return;
  if (!stroke_known_ || static_cast<std::uint16_t>(stroke_.stroke) != h.stroke) {
    ++counters_.live_unknown;
    return;
  }
  if (!has_mesh() || stroke_.mesh_version != version_) {
    ++counters_.live_stale;
    return;
  }
  if (!ensure_plan()) return;
  live_.method = static_cast<math::WarpMethod>(stroke_.method);
  live_.symmetry = plan_->plan->symmetry();
  live_.hand_mask = stroke_.hand_mask;
  live_.radius_m = stroke_.radius_m;
  live_.refine_threshold_m = stroke_.refine_threshold_m;
  live_.hands.clear();
  for (std::size_t k = 0; k < link::kLinkHands; ++k) {
    if ((stroke_.hand_mask & (1u << k)) == 0) continue;
    if (!hands_[k].present) return;      // a stroke hand without its sample: not drawn
    live_.hands.push_back({}).ignore();  // one per link hand: fits
    LiveHand& lh = live_.hands.back();
    lh.session_hand = static_cast<std::uint8_t>(k);
    lh.start = stroke_.start[k];
    lh.end = hands_[k].pose;
    lh.screw = link::live_screw(lh.start, lh.end, h.hands[k]);
  }
  if (!was_active || live_.stroke != stroke_.stroke) live_.weights_changed = true;
  live_.stroke = stroke_.stroke;
  live_.active = true;
  update_symmetric_images();
}

bool SceneReplica::follow_hands() const {
  math::PlanFrames end;
  std::uint8_t long_turns = 0;
  for (std::size_t i = 0; i < live_.hands.size(); ++i) {
    end.push_back(live_.hands[i].end).ignore();  // as many as the plan's hands: fits
    if (live_.hands[i].screw.angle > 3.141592653589793) {
      long_turns = static_cast<std::uint8_t>(long_turns | (1u << i));
    }
  }
  math::WarpPlan& live_plan = *plan_->plan;  // the cached plan follows the hands
  return live_plan.update_turns(end, long_turns).ok();
}

MeshData SceneReplica::cpu_warp() const {
  if (!live_.active || !plan_ || !plan_->plan) return {};
  MeshData out = mesh_;
  const math::WarpPlan& plan = *plan_->plan;
  const math::ConstVertexColumns rest{mesh_.x, mesh_.y, mesh_.z};
  if (plan.symmetric()) {
    // Every image of every hand: the station's own update and apply (the float path,
    // on the same storage), with its turn sense per hand, so the preview is what the
    // commit writes.
    if (!follow_hands()) return {};
    (void)plan.apply(rest, math::VertexColumns{out.x, out.y, out.z});
    return out;
  }
  if (live_.method == math::WarpMethod::scodef) {
    // scodef has no screw: the plan's own update from the end frames.
    math::WarpPlan copy = plan;
    math::PlanFrames end;
    for (const LiveHand& lh : live_.hands) end.push_back(lh.end).ignore();  // as many: fits
    if (!copy.update(end).ok()) return {};
    (void)copy.apply(rest, math::VertexColumns{out.x, out.y, out.z});
    return out;
  }
  std::array<math::KernelHand, 2> k{};
  bool long_way = false;
  for (std::size_t i = 0; i < live_.hands.size(); ++i) {
    const LiveHand& lh = live_.hands[i];
    math::fill_kernel_hand(k[i], lh.screw, lh.start, lh.end, live_.method);
    long_way = long_way || lh.screw.angle > 3.141592653589793;
  }
  const auto idx = plan.indices();
  const auto w1 = plan.weights(0);
  std::vector<float> zeros(idx.size(), 0.0F);
  const auto w2 = live_.hands.size() == 2 ? plan.weights(1) : std::span<const float>(zeros);
  std::vector<float> gx(idx.size()), gy(idx.size()), gz(idx.size());
  std::vector<float> rx(idx.size()), ry(idx.size()), rz(idx.size());
  for (std::size_t i = 0; i < idx.size(); ++i) {
    gx[i] = mesh_.x[idx[i]];
    gy[i] = mesh_.y[idx[i]];
    gz[i] = mesh_.z[idx[i]];
  }
  const math::KernelSpan s{gx.data(), gy.data(), gz.data(), w1.data(), w2.data(),
                           rx.data(), ry.data(), rz.data(), idx.size()};
  // The station's simd kernel; the scalar one past a half turn (the simd sin/cos
  // covers half angles up to pi/2 only on this core).
  if (live_.hands.size() == 2) {
    long_way ? math::warp_two_scalar(k[0], k[1], s) : math::warp_two_simd(k[0], k[1], s);
  } else {
    long_way ? math::warp_one_scalar(k[0], s) : math::warp_one_simd(k[0], s);
  }
  for (std::size_t i = 0; i < idx.size(); ++i) {
    out.x[idx[i]] = rx[i];
    out.y[idx[i]] = ry[i];
    out.z[idx[i]] = rz[i];
  }
  return out;
}

LiveMessages make_live_messages(std::uint32_t mesh_version, std::uint32_t stroke,
                                math::WarpMethod method, double radius_m, std::uint8_t hand_mask,
                                const std::array<math::Frame, 2>& start,
                                const std::array<math::Frame, 2>& end,
                                const std::array<math::Screw, 2>* screws) {
  LiveMessages out;
  out.stroke.stroke = stroke;
  out.stroke.mesh_version = mesh_version;
  out.stroke.method = static_cast<std::uint8_t>(method);
  out.stroke.hand_mask = hand_mask;
  out.stroke.radius_m = radius_m;
  out.hands.stroke = static_cast<std::uint16_t>(stroke);
  out.hands.flags = link::kStrokeActive;
  out.hands.radius_m = static_cast<float>(radius_m);
  std::size_t k = 0;
  for (std::size_t h = 0; h < link::kLinkHands; ++h) {
    if ((hand_mask & (1u << h)) == 0) continue;
    const math::Screw s = screws != nullptr ? (*screws)[k] : math::compute_screw(start[k], end[k]);
    out.stroke.start[h] = start[k];
    out.hands.hands[h] = link::to_live_compact(start[k], end[k], s);
    out.hands.flags = static_cast<std::uint8_t>(out.hands.flags | (link::kHandSample0 << h) |
                                                (link::kHandTracked0 << h));
    ++k;
  }
  return out;
}

}  // namespace twister::bridge
