#include "fe/contact/contact_arrival.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "fe/contact/ring_pair_contact.hpp"

namespace ringcrush::fe {

ContactArrival::ContactArrival(const std::vector<ContactPass>& passes, double arrival_depth)
    : arrival_depth_(arrival_depth) {
  if (!(arrival_depth > 0) || !std::isfinite(arrival_depth))
    throw std::invalid_argument(
        fmt::format("contact arrival depth {} m must be positive and finite (a new contact pair may start acting "
                    "only at a penetration up to it)",
                    arrival_depth));
  committed_.reserve(passes.size());
  neighbours_.reserve(passes.size());
  for (const ContactPass& p : passes) {
    committed_.emplace_back(p.slaves.size());
    // Pieces sharing a node: the piece itself, its neighbours along the chain (a quadratic
    // part and the Hermite junctions at its ends, or a junction and the parts it joins), so a
    // closest point sliding across a junction stays within the pair's neighbourhood.
    // (node, piece) sorted by node: the pieces of each node are adjacent (linear in the mesh).
    std::vector<std::pair<int, int>> at_node;
    for (std::size_t q = 0; q < p.pieces.size(); ++q)
      for (int a = 0; a < p.pieces[q].count; ++a) at_node.emplace_back(p.pieces[q].nodes[a], static_cast<int>(q));
    std::sort(at_node.begin(), at_node.end());
    auto& nb = neighbours_.emplace_back(p.pieces.size());
    for (std::size_t i = 0; i < at_node.size();) {
      std::size_t j = i;
      while (j < at_node.size() && at_node[j].first == at_node[i].first) ++j;
      for (std::size_t a = i; a < j; ++a)
        for (std::size_t b = i; b < j; ++b) nb[at_node[a].second].push_back(at_node[b].second);
      i = j;
    }
    for (auto& list : nb) {
      std::sort(list.begin(), list.end());
      list.erase(std::unique(list.begin(), list.end()), list.end());
    }
  }
}

bool ContactArrival::near(std::size_t pass, int remembered, int piece) const {
  const auto& nb = neighbours_[pass][remembered];
  return std::find(nb.begin(), nb.end(), piece) != nb.end();
}

void ContactArrival::begin() {
  trial_.resize(committed_.size());
  for (Trial& t : trial_) {
    t.held.clear();
    t.refused.clear();
    t.admitted = 0;
    t.deepest_admitted = 0;
  }
}

bool ContactArrival::admit(std::size_t pass, std::size_t slave, int piece, double gap, bool continuing, int node,
                           int master_ring, bool self) {
  Kind kind = Kind::Active;
  const Memory& was = committed_[pass][slave];
  if (continuing && was.kind == Kind::Active && std::abs(gap - was.gap) > arrival_depth_) continuing = false;
  if (continuing) {
    kind = committed_[pass][slave].kind;
  } else if (-gap > arrival_depth_) {
    kind = Kind::Refused;
    trial_[pass].refused.push_back({-gap, node, master_ring, self});
  } else {
    ++trial_[pass].admitted;
    trial_[pass].deepest_admitted = std::max(trial_[pass].deepest_admitted, -gap);
  }
  trial_[pass].held.push_back({pass, slave, {piece, kind, gap}});
  return kind == Kind::Active;
}

void ContactArrival::commit() {
  for (const Entry& e : committed_list_) committed_[e.pass][e.slave] = Memory{};
  committed_list_.clear();
  for (Trial& t : trial_) {
    for (const Entry& e : t.held) committed_[e.pass][e.slave] = e.memory;
    committed_list_.insert(committed_list_.end(), t.held.begin(), t.held.end());
    refused_ += static_cast<long>(t.refused.size());
    for (const RefusedArrival& r : t.refused)
      if (r.depth > deepest_.depth) deepest_ = r;
    t.refused.clear();
    admitted_ += t.admitted;
    deepest_admitted_ = std::max(deepest_admitted_, t.deepest_admitted);
    t.admitted = 0;
    t.deepest_admitted = 0;
  }
}

int ContactArrival::trial_refusals() const {
  int n = 0;
  for (const Trial& t : trial_) n += static_cast<int>(t.refused.size());
  return n;
}

}  // namespace ringcrush::fe
