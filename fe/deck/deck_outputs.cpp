// Output requests of ABAQUS 4.8 and what ringcrush does with each (issue 5 item 1): a request
// with a ringcrush counterpart is "mapped" to that output (DESIGN.md "Machine-readable
// outputs": history.csv, frames/*.vtu, *.svg); the rest are accepted and listed as ignored
// with the reason, never silently dropped.
#include <algorithm>
#include <cctype>

#include "fe/deck/deck_builder.hpp"
#include "fe/deck/deck_error.hpp"

namespace ringcrush::fe::deck {

namespace {

bool any_of(const std::vector<std::string>& vars, std::initializer_list<const char*> names) {
  return std::any_of(vars.begin(), vars.end(), [&](const std::string& v) {
    return std::any_of(names.begin(), names.end(), [&](const char* n) { return v == n; });
  });
}

void classify(OutputRequest& r) {
  const std::string& k = r.keyword;
  const auto& v = r.variables;
  auto map = [&](const char* to, const char* why) { r.mapped_to = to, r.reason = why; };
  auto ignore = [&](const char* why) { r.mapped_to.clear(), r.reason = why; };
  if (k == "NODE PRINT" || k == "NODE FILE" || k == "MONITOR") {
    if (k == "MONITOR" || any_of(v, {"U", "V", "A", "RF"}))
      map("history.csv", "plate / impactor displacement, velocity and force per increment");
    else
      ignore("no nodal variable with a ringcrush counterpart (U, V, A, RF)");
  } else if (k == "EL PRINT" || k == "EL FILE") {
    if (any_of(v, {"S", "E", "PE", "PEEQ", "SINV"}))
      map("frames/*.vtu", "Mises stress, PEEQ and contact pressure per field frame");
    else
      ignore("no element variable with a ringcrush counterpart (S, E, PE, PEEQ, SINV)");
  } else if (k == "ENERGY PRINT" || k == "ENERGY FILE") {
    map("history.csv", "energy columns (kinetic, elastic, plastic, contact, external work)");
  } else if (k == "PLOT" || k == "DISPLACED") {
    map("*.svg", "deformed-shape and history plots");
  } else if (k == "CONTOUR") {
    map("frames/*.vtu", "contour variables are fields of the ParaView frames");
  } else if (k == "DRAW" || k == "DETAIL") {
    ignore("undeformed-model drawing with labels: use check-deck or the ParaView frames");
  } else if (k == "PRINT") {
    ignore("printout frequency of the solver log: ringcrush reports progress itself");
  } else if (k == "RESTART") {
    ignore("ringcrush writes no restart files");
  } else {
    ignore("no ringcrush counterpart");
  }
}

}  // namespace

void DeckBuilder::output(const Card& card) {
  OutputRequest r;
  r.keyword = card.keyword;
  r.line = card.line;
  for (const DataLine& d : card.data)
    for (const std::string& f : d.fields) {
      if (f.empty()) continue;
      std::string up = f;
      for (char& c : up) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
      r.variables.push_back(up);
    }
  classify(r);
  (in_step_ ? open_step(card).outputs : m_.outputs).push_back(std::move(r));
}

}  // namespace ringcrush::fe::deck
