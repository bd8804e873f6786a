// The chain's global mesh from one ring mesh (issue 4 item 1; seed/thesis_dynamic.inp):
// ring i (0-based) is a copy of make_ring_mesh centred at y = −i·pitch. `welded` joints make
// ring i's bottom outer node and ring i+1's top outer node ONE node (the deck's *MPC ties
// 501–1597, 1501–2597, …, which join exactly these coincident points). Rigid bodies follow
// the ring nodes: the impactor node (at ring 1's top, y = R, its lower face) and, for
// `plates`, one node per plate at the plate's centre; their x dofs are fixed.
#pragma once

#include <vector>

#include "fe/chain/chain_model.hpp"

namespace ringcrush::fe {

struct ChainTopology {
  ChainMesh mesh;
  RingMesh ring;                            // the ring every copy is made of (local numbering)
  std::vector<std::vector<int>> ring_node;  // per ring: local node → global node
  std::vector<int> fixed_dofs;              // symmetry / rigid-body restraints, ascending
  double plate_half_thickness = 0;          // plates: faces at plate node y ± this
  double target_y = 0;                      // fixed target plane (reference, under the last ring)
};

// Validates the input (chain_input.hpp) and builds the topology.
ChainTopology make_chain_topology(const ChainInput& input);

}  // namespace ringcrush::fe
