#include "fe/deck/deck_reader.hpp"

#include <algorithm>
#include <fstream>
#include <map>
#include <sstream>

#include "fe/deck/deck_builder.hpp"
#include "fe/deck/deck_error.hpp"
#include "fe/deck/deck_fields.hpp"
#include "fe/deck/deck_lexer.hpp"

namespace ringcrush::fe::deck {

namespace {

using Handler = void (DeckBuilder::*)(const Card&);
enum class Where { Model, Step, Either };
struct KeywordInfo {
  Handler handler;
  Where where;
};

const std::map<std::string, KeywordInfo>& keyword_table() {
  static const std::map<std::string, KeywordInfo> table = {
      {"HEADING", {&DeckBuilder::heading, Where::Model}},
      {"NODE", {&DeckBuilder::node, Where::Model}},
      {"NGEN", {&DeckBuilder::ngen, Where::Model}},
      {"NCOPY", {&DeckBuilder::ncopy, Where::Model}},
      {"ELEMENT", {&DeckBuilder::element, Where::Model}},
      {"ELGEN", {&DeckBuilder::elgen, Where::Model}},
      {"ELCOPY", {&DeckBuilder::elcopy, Where::Model}},
      {"NSET", {&DeckBuilder::nset, Where::Model}},
      {"ELSET", {&DeckBuilder::elset, Where::Model}},
      {"SOLID SECTION", {&DeckBuilder::solid_section, Where::Model}},
      {"MATERIAL", {&DeckBuilder::material, Where::Model}},
      {"ELASTIC", {&DeckBuilder::elastic, Where::Model}},
      {"PLASTIC", {&DeckBuilder::plastic, Where::Model}},
      {"DENSITY", {&DeckBuilder::density, Where::Model}},
      {"RIGID SURFACE", {&DeckBuilder::rigid_surface, Where::Model}},
      {"INTERFACE", {&DeckBuilder::interface, Where::Model}},
      {"FRICTION", {&DeckBuilder::friction, Where::Model}},
      {"SURFACE CONTACT", {&DeckBuilder::surface_contact, Where::Model}},
      {"SLIDE LINE", {&DeckBuilder::slide_line, Where::Model}},
      {"MPC", {&DeckBuilder::mpc, Where::Model}},
      {"BOUNDARY", {&DeckBuilder::boundary, Where::Either}},
      {"INITIAL CONDITIONS", {&DeckBuilder::initial_conditions, Where::Model}},
      {"MASS", {&DeckBuilder::mass, Where::Model}},
      {"STEP", {&DeckBuilder::step, Where::Model}},
      {"STATIC", {&DeckBuilder::static_procedure, Where::Step}},
      {"DYNAMIC", {&DeckBuilder::dynamic_procedure, Where::Step}},
      {"CONTROL INTERFACES", {&DeckBuilder::control_interfaces, Where::Step}},
      {"END STEP", {&DeckBuilder::end_step, Where::Step}},
      // Output requests: accepted anywhere, mapped or listed as ignored (deck_outputs.cpp).
      {"PRINT", {&DeckBuilder::output, Where::Either}},
      {"PLOT", {&DeckBuilder::output, Where::Either}},
      {"DRAW", {&DeckBuilder::output, Where::Either}},
      {"DISPLACED", {&DeckBuilder::output, Where::Either}},
      {"CONTOUR", {&DeckBuilder::output, Where::Either}},
      {"DETAIL", {&DeckBuilder::output, Where::Either}},
      {"NODE PRINT", {&DeckBuilder::output, Where::Either}},
      {"NODE FILE", {&DeckBuilder::output, Where::Either}},
      {"EL PRINT", {&DeckBuilder::output, Where::Either}},
      {"EL FILE", {&DeckBuilder::output, Where::Either}},
      {"ENERGY PRINT", {&DeckBuilder::output, Where::Either}},
      {"ENERGY FILE", {&DeckBuilder::output, Where::Either}},
      {"MODAL PRINT", {&DeckBuilder::output, Where::Either}},
      {"RESTART", {&DeckBuilder::output, Where::Either}},
      {"MONITOR", {&DeckBuilder::output, Where::Either}},
      {"FILE FORMAT", {&DeckBuilder::output, Where::Either}},
      {"PREPRINT", {&DeckBuilder::output, Where::Either}},
  };
  return table;
}

bool is_one_of(const std::string& k, std::initializer_list<const char*> names) {
  return std::any_of(names.begin(), names.end(), [&](const char* n) { return k == n; });
}

}  // namespace

const std::vector<std::string>& supported_keywords() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> v;
    for (const auto& [k, info] : keyword_table()) v.push_back(k);
    return v;
  }();
  return names;
}

void allow_parameters(const Card& card, std::initializer_list<const char*> names) {
  for (const Parameter& p : card.parameters)
    if (!is_one_of(p.name, names)) {
      std::string list;
      for (const char* n : names) list += std::string(list.empty() ? "" : ", ") + n;
      throw DeckError(card.line, "*" + card.keyword + ": unknown parameter " + p.name +
                                     (list.empty() ? " (takes none)" : " (expected one of " + list + ")"));
    }
}

void require_data(const Card& card) {
  if (card.data.empty()) throw DeckError(card.line, "*" + card.keyword + ": missing data line");
}

void forbid_data(const Card& card) {
  if (!card.data.empty())
    throw DeckError(card.data.front().line, "*" + card.keyword + " takes no data lines, found '" +
                                                card.data.front().text + "'");
}

double real_parameter(const Card& card, const char* name, double fallback) {
  const auto v = card.value(name);
  if (!v) return fallback;
  double x = 0;
  if (!parse_real(*v, x))
    throw DeckError(card.line, "*" + card.keyword + ": " + name + "=" + *v + " is not a finite number");
  return x;
}

long long integer_parameter(const Card& card, const char* name, long long fallback) {
  const auto v = card.value(name);
  if (!v) return fallback;
  long long x = 0;
  if (!parse_integer(*v, x))
    throw DeckError(card.line, "*" + card.keyword + ": " + name + "=" + *v + " is not an integer");
  return x;
}

void DeckBuilder::apply(const Card& card) {
  const auto it = keyword_table().find(card.keyword);
  if (it == keyword_table().end())
    throw DeckError(card.line, "unknown or unsupported keyword *" + card.keyword);
  const KeywordInfo& info = it->second;
  if (info.where == Where::Model && in_step_)
    throw DeckError(card.line, "*" + card.keyword + " is model data and cannot appear inside a step");
  if (info.where == Where::Step && !in_step_)
    throw DeckError(card.line, "*" + card.keyword + " is only valid inside a *STEP");
  // Sub-option contexts: *ELASTIC etc. belong to the last *MATERIAL, *FRICTION and
  // *SURFACE CONTACT to the last *INTERFACE, *DRAW etc. to the last *PLOT.
  if (!is_one_of(card.keyword, {"ELASTIC", "PLASTIC", "DENSITY"})) material_.reset();
  if (!is_one_of(card.keyword, {"FRICTION", "SURFACE CONTACT"})) interface_.reset();
  const bool plot_option = is_one_of(card.keyword, {"DRAW", "DISPLACED", "CONTOUR", "DETAIL"});
  if (plot_option && !in_plot_)
    throw DeckError(card.line, "*" + card.keyword + " must follow *PLOT");
  if (!plot_option) in_plot_ = false;
  (this->*info.handler)(card);
  if (card.keyword == "PLOT") in_plot_ = true;
}

DeckModel DeckBuilder::finish() {
  if (in_step_)
    throw DeckError(m_.steps.back().line, "*STEP has no *END STEP before the end of the file (truncated deck?)");
  for (const SolidSection& s : m_.sections) {
    const auto mat = m_.materials.find(s.material);
    if (mat == m_.materials.end())
      throw DeckError(s.line, "*SOLID SECTION: material " + s.material + " is never defined (*MATERIAL, NAME=" +
                                  s.material + ")");
    if (!mat->second.youngs_modulus)
      throw DeckError(mat->second.line, "*MATERIAL " + s.material + " has no *ELASTIC");
  }
  for (const RigidSurface& r : m_.rigid_surfaces) {
    const auto set = m_.elsets.find(r.elset);
    if (set == m_.elsets.end())
      throw DeckError(r.line, "*RIGID SURFACE: element set " + r.elset + " is never defined");
    for (int e : set->second.labels)
      if (m_.elements.at(e).type != ElementType::Irs22)
        throw DeckError(r.line, "*RIGID SURFACE: element " + std::to_string(e) + " of set " + r.elset +
                                    " is not an IRS22 interface element");
  }
  return std::move(m_);
}

DeckModel read_deck(std::string_view text) {
  const std::vector<Card> cards = lex_deck(text);
  DeckBuilder builder;
  for (const Card& c : cards) builder.apply(c);
  return builder.finish();
}

DeckModel load_deck(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw std::invalid_argument("cannot open deck " + file.string());
  std::error_code ec;
  const auto bytes = std::filesystem::file_size(file, ec);
  if (!ec && bytes > max_deck_bytes)  // refuse before reading it into memory
    throw DeckError(0, "deck is " + std::to_string(bytes) + " bytes, above the limit of " +
                           std::to_string(max_deck_bytes));
  std::ostringstream ss;
  ss << in.rdbuf();
  return read_deck(ss.str());
}

}  // namespace ringcrush::fe::deck
