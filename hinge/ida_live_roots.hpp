// IDA on the root functions that can fire before the next event (HybridOptions::ida_live_roots).
// IDA's own per-step root work — the sign test of every g_i at each step's end, the secant
// search over all of them when one has crossed — grows with the number of root functions it
// is given, and a hybrid model may know that some of them are constant between events (Level 3
// with ring inertia: the slots of unavailable mechanisms, a rigid ring's crush rate, a crushing
// ring's tension root — 19 to 29 of 37 read a fixed 1 on Test 30 welded). Every event restarts
// IDA anyway, so at each restart IDA is given the live ones only (IDARootInit), and a root it
// finds is mapped back to the model's index.
//
// A root declared held must keep, within the segment, the sign it had at the restart: the
// model's root functions are still evaluated in full (they share the accelerations), so every
// root evaluation IDA asks for checks the held ones too, and one that changes sign is a named
// error (std::logic_error) instead of a missed event.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace ringcrush::hinge {

class IdaLiveRoots {
 public:
  explicit IdaLiveRoots(std::size_t count = 0) : count_(count) {}

  // Roots `live` (ascending, distinct, below count(); empty: all) are IDA's from now on; the
  // others are held, with the signs of `start` (the model's root values at the restart).
  // Throws std::invalid_argument on a bad list.
  void select(const std::vector<std::size_t>& live, const std::vector<double>& start);
  // Back to the whole set.
  void select_all();

  std::size_t count() const { return count_; }               // the model's root functions
  std::size_t size() const { return all_ ? count_ : live_.size(); }  // IDA's
  bool all() const { return all_; }
  const std::vector<std::size_t>& live() const { return live_; }

  // Throws std::logic_error when a held root of the model's values `g` (count()) at t has
  // left the sign it had at the restart.
  void check_held(double t, const double* g) const;
  // IDA's root values (size()) from the model's (count()).
  void gather(const double* g, double* ida) const;
  // The model's roots-found flags (count()) from IDA's (size()).
  std::vector<int> expand(const std::vector<int>& ida_found) const;

 private:
  std::size_t count_;
  bool all_ = true;
  std::vector<std::size_t> live_;
  std::vector<std::size_t> held_;
  std::vector<int> held_sign_;  // per held root: −1, 0, +1 at the restart
};

}  // namespace ringcrush::hinge
