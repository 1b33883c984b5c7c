// The per-decision reward of the driving scenarios (docs/scenarios.md), SUMO-free so it can be tested and
// documented on its own (docs/scenarios.md).
//
//   r = r_v − offset − w_gap·h(leader) − [ego changed lane] w_gap·h(new follower) − w_fail·[failed LC]
//   r = −collision_penalty on a collision (the episode then terminates)
//
// r_v = max(0, 1 − |v − v_des| / v_des) ∈ [0, 1] (FLOW's desired-velocity term) and
// h = clamp(1 − gap / s*, 0, 1), with the IDM desired gap s* = s0 + max(0, v·T + v·Δv / (2√(a·b)))
// of the vehicle behind (Δv its closing speed). In the `short` variant (offset 0) a good step earns up to 1; a step spent at
// standstill earns −offset; tailgating, cutting somebody off or commanding impossible lane changes push
// it below 0; a collision costs as much as ten perfect steps and forfeits the rest of the episode.
#pragma once

#include <algorithm>
#include <cmath>
#include <string>

namespace rapid::driving {

struct RewardWeights {
  double offset = 0.0;              // subtracted from r_v: where a slow step turns negative
  double gap = 1.0;                 // w_gap: unsafe headway, per unit of (1 − gap/s*)
  double failed_lane_change = 0.3;  // w_fail
  double collision = 10.0;          // collision_penalty
};

// The reward variants a scenario's `reward` setting names.
//   short: r_v − penalties, as above: a step is negative only when penalised.
//   flow:  AD4RL/FLOW-style at 0.1 s decisions: r = r_v − 0.3 − 2·h(leader) − [changed lane]·2·h(new
//          follower) − 1·[failed LC], −10 on a collision. A free step at v_des earns 0.7; a step
//          below 0.3·v_des, or with a gap under ~65% of s*, or a failed lane change is negative, so
//          the paper's ε = −0.15 separates good steps (above) from unsafe, penalised or crawling
//          ones (below), and a queue at 40% of v_des still pays (+0.1), so crashing out of a jam
//          never beats waiting in it.
inline RewardWeights reward_weights(const std::string& variant) {
  if (variant == "flow") return {.offset = 0.3, .gap = 2.0, .failed_lane_change = 1.0, .collision = 10.0};
  return {};
}

// IDM constants of the humans' vType (envs/networks/vtypes.add.xml), except s0 = 2 m < minGap so
// that humans in their own steady state are never penalised.
struct IdmGap {
  double s0 = 2.0, T = 1.0, a = 2.6, b = 4.5;
  // s* for a follower at speed v closing in at dv = v − v_leader.
  double desired_gap(double v, double dv) const {
    return s0 + std::max(0.0, v * T + v * dv / (2.0 * std::sqrt(a * b)));
  }
  // h ∈ [0, 1]: 0 at or beyond s*, 1 at contact.
  double shortfall(double gap, double v, double dv) const {
    return std::clamp(1.0 - gap / desired_gap(v, dv), 0.0, 1.0);
  }
};

inline double velocity_term(double v, double v_des) {
  return std::max(0.0, 1.0 - std::abs(v - v_des) / v_des);
}

// What one decision's reward is computed from (the ego after the decision, its current lane).
struct RewardInputs {
  double speed = 0.0;           // v, m/s
  double desired_speed = 25.0;  // v_des, m/s
  bool leader = false;          // a leader within the sensing range
  double leader_gap = 0.0, leader_speed = 0.0;
  bool follower = false;        // a follower within the sensing range
  double follower_gap = 0.0, follower_speed = 0.0;
  bool collision = false, changed_lane = false, failed_lane_change = false;
};

// The reward and its terms, each as the amount it adds (velocity) or subtracts (the others):
//   total = velocity − gap − follower − failed_lane_change, or −collision on a collision (the
//   other terms are then 0). total is computed in exactly that order, so it is the reward.
struct RewardTerms {
  double velocity = 0.0;            // r_v − offset
  double gap = 0.0;                 // w_gap·h(ego, leader)
  double follower = 0.0;            // w_gap·h(new follower, ego) after a lane change
  double failed_lane_change = 0.0;  // w_fail
  double collision = 0.0;           // collision_penalty
  double total = 0.0;               // the reward
};

inline RewardTerms reward_terms(const RewardWeights& w, const IdmGap& idm, const RewardInputs& in) {
  RewardTerms t;
  if (in.collision) {
    t.collision = w.collision;
    t.total = -w.collision;
    return t;
  }
  const double v = in.speed;
  t.velocity = velocity_term(v, in.desired_speed) - w.offset;
  double r = t.velocity;
  if (in.leader) {
    t.gap = w.gap * idm.shortfall(in.leader_gap, v, v - in.leader_speed);
    r -= t.gap;
  }
  if (in.changed_lane && in.follower) {
    t.follower = w.gap * idm.shortfall(in.follower_gap, in.follower_speed, in.follower_speed - v);
    r -= t.follower;
  }
  if (in.failed_lane_change) {
    t.failed_lane_change = w.failed_lane_change;
    r -= t.failed_lane_change;
  }
  t.total = r;
  return t;
}

}  // namespace rapid::driving
