// Step keywords: *STEP, *STATIC (thesis §3.4: increments controlled by PTOL), *DYNAMIC
// (thesis §3.5: HHT-α with ALPHA, half-step residual tolerance HAFTOL), *CONTROL INTERFACES,
// *END STEP.
#include "fe/deck/deck_builder.hpp"
#include "fe/deck/deck_error.hpp"

namespace ringcrush::fe::deck {

namespace {

std::optional<int> positive_int_parameter(const Card& card, const char* name) {
  if (!card.has(name)) return std::nullopt;
  const long long v = integer_parameter(card, name, 0);
  if (v < 1 || v > max_entities)
    throw DeckError(card.line, "*" + card.keyword + ": " + name + "=" + std::to_string(v) + " outside 1.." +
                                   std::to_string(max_entities));
  return static_cast<int>(v);
}

std::optional<double> positive_real_parameter(const Card& card, const char* name) {
  if (!card.has(name)) return std::nullopt;
  const double v = real_parameter(card, name, 0.0);
  if (!(v > 0.0)) throw DeckError(card.line, "*" + card.keyword + ": " + name + " must be positive");
  return v;
}

// The time-incrementation data line shared by *STATIC and *DYNAMIC:
// initial increment, period, minimum increment, maximum increment.
void read_incrementation(const Card& card, Step& s) {
  require_data(card);
  const std::vector<Record> recs = records(card);
  if (recs.size() != 1) throw DeckError(recs[1].line, "*" + card.keyword + " takes one data line");
  const Fields f(card, recs[0]);
  if (recs[0].size() > 4) f.fail("at most 4 fields (initial, period, minimum, maximum increment)");
  s.initial_increment = f.real(0, "initial increment");
  s.period = f.real_or(1, 1.0, "time period");
  if (!recs[0].empty_at(2)) s.min_increment = f.real(2, "minimum increment");
  if (!recs[0].empty_at(3)) s.max_increment = f.real(3, "maximum increment");
  if (!(*s.initial_increment > 0.0)) f.fail("initial increment must be positive");
  if (!(*s.period >= *s.initial_increment)) f.fail("time period is shorter than the initial increment");
  if (s.min_increment && !(*s.min_increment > 0.0 && *s.min_increment <= *s.initial_increment))
    f.fail("minimum increment must lie in (0, initial increment]");
  if (s.max_increment && !(*s.max_increment >= *s.initial_increment && *s.max_increment <= *s.period))
    f.fail("maximum increment must lie in [initial increment, time period]");
}

void set_procedure(const Card& card, Step& s, Procedure p) {
  if (s.procedure != Procedure::None)
    throw DeckError(card.line, "*" + card.keyword + ": the step already has a procedure (line " +
                                   std::to_string(s.procedure_line) + ")");
  s.procedure = p;
  s.procedure_line = card.line;
}

}  // namespace

void DeckBuilder::step(const Card& card) {
  allow_parameters(card, {"NLGEOM", "INC", "CYCLE", "SUBMAX"});
  if (card.data.size() > 1) throw DeckError(card.data[1].line, "*STEP takes at most one (title) data line");
  Step s;
  s.line = card.line;
  s.nlgeom = card.has("NLGEOM");
  s.submax = card.has("SUBMAX");
  if (card.has("NLGEOM") && card.find("NLGEOM")->has_value)
    throw DeckError(card.line, "*STEP: NLGEOM is a flag");
  s.max_increments = positive_int_parameter(card, "INC");
  s.max_iterations = positive_int_parameter(card, "CYCLE");
  m_.steps.push_back(std::move(s));
  in_step_ = true;
}

void DeckBuilder::static_procedure(const Card& card) {
  allow_parameters(card, {"PTOL"});
  Step& s = open_step(card);
  set_procedure(card, s, Procedure::Static);
  s.ptol = positive_real_parameter(card, "PTOL");
  read_incrementation(card, s);
}

void DeckBuilder::dynamic_procedure(const Card& card) {
  allow_parameters(card, {"PTOL", "HAFTOL", "ALPHA"});
  Step& s = open_step(card);
  set_procedure(card, s, Procedure::Dynamic);
  s.ptol = positive_real_parameter(card, "PTOL");
  s.haftol = positive_real_parameter(card, "HAFTOL");
  if (card.has("ALPHA")) {
    // Hilber's α ∈ [−1/3, 0] (thesis eq. 3.5-2): 0 is the trapezoidal rule, negative values
    // add high-frequency dissipation.
    const double a = real_parameter(card, "ALPHA", 0.0);
    if (!(a >= -1.0 / 3.0 && a <= 0.0))
      throw DeckError(card.line, "*DYNAMIC: ALPHA=" + std::to_string(a) + " outside [-1/3, 0]");
    s.alpha = a;
  }
  read_incrementation(card, s);
}

void DeckBuilder::control_interfaces(const Card& card) {
  allow_parameters(card, {"MAXCHP", "UERRMX"});
  forbid_data(card);
  Step& s = open_step(card);
  s.max_contact_changes = positive_int_parameter(card, "MAXCHP");
  if (card.has("UERRMX")) s.contact_error = positive_real_parameter(card, "UERRMX");
}

void DeckBuilder::end_step(const Card& card) {
  allow_parameters(card, {});
  forbid_data(card);
  Step& s = open_step(card);
  if (s.procedure == Procedure::None)
    throw DeckError(card.line, "*END STEP: the step opened at line " + std::to_string(s.line) +
                                   " has no procedure (*STATIC or *DYNAMIC)");
  s.ended = true;
  in_step_ = false;
}

}  // namespace ringcrush::fe::deck
