// The Scene equivalent to an ABAQUS deck (issue 5 item 2): the deck's parameters
// (fe/deck/deck_parameters.hpp) written as scene TOML and parsed by the one scene parser, so a
// deck gets exactly the validation and defaults of a TOML scene and can run through the same
// FE path. `ringcrush check-deck --scene` prints the TOML.
#pragma once

#include <filesystem>
#include <string>

#include "compare/scene.hpp"
#include "fe/deck/deck_parameters.hpp"

namespace ringcrush::compare {

// Scene TOML for the deck's problem; `source` names the deck in the title and comments.
std::string scene_toml_from_deck(const fe::deck::DeckParameters& deck, const std::string& source);

// Reads, builds and converts a deck; DeckError / std::invalid_argument / SceneError on failure.
Scene scene_from_deck(const std::filesystem::path& deck_file);

}  // namespace ringcrush::compare
