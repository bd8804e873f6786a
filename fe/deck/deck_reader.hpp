// ABAQUS 4.8 deck reader for the keywords of the thesis decks (Anexo I; issue 5 item 1):
// *HEADING, *NODE, *NGEN (LINE=L, LINE=C), *ELEMENT (CPS8, IRS22, ISL22, MASS), *ELGEN,
// *NCOPY (SHIFT, REFLECT=LINE), *ELCOPY, *NSET, *ELSET (GENERATE), *SOLID SECTION,
// *MATERIAL, *ELASTIC, *PLASTIC, *DENSITY, *RIGID SURFACE, *INTERFACE, *FRICTION,
// *SURFACE CONTACT, *SLIDE LINE, *MPC, *BOUNDARY, *INITIAL CONDITIONS, *MASS, *STEP, *STATIC,
// *DYNAMIC, *CONTROL INTERFACES, *END STEP, and the output requests (deck_outputs.hpp).
// Anything else, and any inconsistency (undefined set, duplicate label, NaN...), is a
// DeckError naming the line and the reason. Sample:
//   DeckModel m = load_deck("data/thesis/thesis_static.inp");  // 332 nodes, 22 CPS8
#pragma once

#include <filesystem>
#include <string_view>

#include "fe/deck/deck_error.hpp"
#include "fe/deck/deck_model.hpp"

namespace ringcrush::fe::deck {

DeckModel read_deck(std::string_view text);
// Reads the file; a file that cannot be opened is a std::invalid_argument naming the path.
DeckModel load_deck(const std::filesystem::path& file);

// The keywords read_deck accepts (upper case), for help texts and tests.
const std::vector<std::string>& supported_keywords();

}  // namespace ringcrush::fe::deck
