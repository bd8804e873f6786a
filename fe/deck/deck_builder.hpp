// Internal to fe/deck: the state machine that turns cards into a DeckModel, one member per
// keyword, spread over deck_mesh_keywords.cpp, deck_property_keywords.cpp and
// deck_step_keywords.cpp. Keywords are applied in deck order, so every reference (node, set,
// element) must already exist when it is used — which also gives each error its line.
#pragma once

#include <initializer_list>
#include <optional>
#include <string>
#include <vector>

#include "fe/deck/deck_fields.hpp"
#include "fe/deck/deck_lexer.hpp"
#include "fe/deck/deck_model.hpp"

namespace ringcrush::fe::deck {

class DeckBuilder {
 public:
  void apply(const Card& card);
  DeckModel finish();

  // Keyword handlers (one per ABAQUS keyword).
  void heading(const Card&);
  void node(const Card&);
  void ngen(const Card&);
  void ncopy(const Card&);
  void element(const Card&);
  void elgen(const Card&);
  void elcopy(const Card&);
  void nset(const Card&);
  void elset(const Card&);
  void solid_section(const Card&);
  void material(const Card&);
  void elastic(const Card&);
  void plastic(const Card&);
  void density(const Card&);
  void rigid_surface(const Card&);
  void interface(const Card&);
  void friction(const Card&);
  void surface_contact(const Card&);
  void slide_line(const Card&);
  void mpc(const Card&);
  void boundary(const Card&);
  void initial_conditions(const Card&);
  void mass(const Card&);
  void step(const Card&);
  void static_procedure(const Card&);
  void dynamic_procedure(const Card&);
  void control_interfaces(const Card&);
  void end_step(const Card&);
  void output(const Card&);

 private:
  void add_node(int label, const Point& x, int line);
  void add_element(int label, Element e);
  // Adds a label to a set, creating the set at `line` if needed.
  void add_to_set(std::map<std::string, LabelSet>& sets, const std::string& name, int label, int line);
  // Counts generated items against max_generated; throws at `line` beyond it.
  void spend(long long items, int line);
  // A data field naming either one node or a node set.
  std::vector<int> nodes_of(const Fields& f, std::size_t i, const char* what) const;
  const LabelSet& nset_named(const Card& card, const std::string& name, int line) const;
  const LabelSet& elset_named(const Card& card, const std::string& name, int line) const;
  Step& open_step(const Card& card);
  Material& current_material(const Card& card);
  Interface& current_interface(const Card& card);

  DeckModel m_;
  std::optional<std::string> material_;   // *MATERIAL whose sub-options are being read
  std::optional<std::size_t> interface_;  // *INTERFACE whose sub-options are being read
  bool in_plot_ = false;                  // after *PLOT: *DRAW, *DISPLACED, *CONTOUR allowed
  bool in_step_ = false;
  long long generated_ = 0;
};

// Checks a card against its allowed parameters and data-line presence.
void allow_parameters(const Card& card, std::initializer_list<const char*> names);
void require_data(const Card& card);
void forbid_data(const Card& card);
// A parameter value as a finite number / integer, with the card line in errors.
double real_parameter(const Card& card, const char* name, double fallback);
long long integer_parameter(const Card& card, const char* name, long long fallback);

}  // namespace ringcrush::fe::deck
