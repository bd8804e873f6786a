#include "fe/element/cps8_rule_tables.hpp"

namespace ringcrush::fe {

Cps8RuleTables cps8_rule_tables(Integration rule) {
  Cps8RuleTables t;
  t.rule = rule;
  const auto pts = gauss_rule(rule == Integration::Reduced ? 2 : 3);
  t.points = static_cast<int>(pts.size());
  t.reduced = rule == Integration::Selective ? 4 : 0;
  ShapeVec n;
  for (int i = 0; i < t.points; ++i) {
    cps8_shape(pts[i].g, pts[i].h, n, t.dn[i]);
    t.weight[i] = pts[i].weight;
  }
  const auto red = gauss_rule(2);
  for (int r = 0; r < 4; ++r) cps8_shape(red[r].g, red[r].h, n, t.dn_reduced[r]);
  return t;
}

}  // namespace ringcrush::fe
