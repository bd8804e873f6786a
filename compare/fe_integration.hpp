// The scene's Gauss rule (compare/scene.hpp) as the FE's (fe/fe_input.hpp). The two enums stay
// apart so that the scene parser does not depend on fe/; this is their one mapping, used by the
// static and dynamic FE runs and the through-wall section check.
#pragma once

#include "compare/scene.hpp"
#include "fe/fe_input.hpp"

namespace ringcrush::compare {

inline fe::Integration fe_integration(Integration i) {
  switch (i) {
    case Integration::Full: return fe::Integration::Full;
    case Integration::Reduced: return fe::Integration::Reduced;
    case Integration::Selective: return fe::Integration::Selective;
  }
  return fe::Integration::Selective;
}

}  // namespace ringcrush::compare
