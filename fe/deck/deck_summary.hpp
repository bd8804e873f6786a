// Human-readable summaries of a deck, printed by `ringcrush check-deck`: what the deck
// defines (counts, sets, materials, contact, steps, output requests mapped or ignored) and
// the ringcrush parameters it amounts to.
#pragma once

#include <string>

#include "fe/deck/deck_model.hpp"
#include "fe/deck/deck_parameters.hpp"

namespace ringcrush::fe::deck {

std::string describe(const DeckModel& model);
std::string describe(const DeckParameters& parameters);

}  // namespace ringcrush::fe::deck
