// The smallest valid dynamic scene (two welded Test 30 rings): scene-parsing tests append or
// edit lines of it, so each test states only the key it is about.
#pragma once

#include <string>

namespace test_scenes {

inline const std::string minimal_dynamic = R"(
title = "unit"
[rings]
count = 2
outer_diameter_m = 0.0508
wall_thickness_m = 0.0016
width_m = 0.0125
[rings.material]
youngs_modulus_Pa = 202e9
poisson_ratio = 0.3
density_kg_m3 = 7850.0
hardening = [[273e6, 0.0], [320e6, 0.02113]]
[joints]
type = "welded"
[impactor]
mass_kg = 0.257
velocity_m_s = 27.7
[far_end]
type = "fixed"
[analysis]
type = "dynamic"
end_time_s = 0.05
)";

}  // namespace test_scenes
