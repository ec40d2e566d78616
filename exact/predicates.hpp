// Umbrella header: every filtered exact predicate of exact/.
//
//   tangent_space.hpp       ImplicitSystem, TangentSpace (exact basis U of ker J_F(p), Gram)
//   tangent_predicates.hpp  TangentChart, TangentCell: orientation and power tests in T_p
//   simplex_predicates.hpp  thickness, squared distances, ambient power of an exact centre
//   filter_stats.hpp        FilterContext / FilterStats (per-predicate filter-failure counts)
//   number_types.hpp        RationalConstant, exact conversions
//   interval.hpp            Interval, Box, UpwardRounding (batch guard)
//   interval_arithmetic.hpp IntervalNumber: interval arithmetic for a consumer's own enclosures
//   linear_algebra.hpp      determinants, Cramer's rule, adjugate, exact rational solve/inverse
// Certified reporting and root isolation live in enclosure.hpp and krawczyk.hpp.
//
// Typical use in a certifier (one FilterContext per thread):
//
//   using namespace delcert::exact;
//   ImplicitSystem F = ImplicitSystem::parse(spec.equations, N);
//   FilterContext ctx;
//   TangentSpace T(F, p);                          // exact U at p (throws at singular points)
//   TangentChart chart(T, neighbour_pointers);     // local index 0 = p, i + 1 = neighbour i
//   UpwardRounding batch;                          // optional: one rounding switch per batch
//   int side = chart.orientation({0, a, b, c}, ctx);          // m = 3: m + 1 indices
//   TangentCell cell = chart.cell({0, a, b, c}, ctx);         // prepare once ...
//   int s = cell.power_sign(q, ctx);                          // ... test many q: -1 inside
//   int protected_ = cell.power_sign(q, RationalConstant(delta2), ctx);  // > 0: protected
//   int thick = thickness_sign(vertex_pointers, N, RationalConstant(gamma0_pow_2j), ctx);
//   // Reports (outside hot loops): exact values and certified bounds
//   Enclosure margin(cell.power_exact(q) - delta2);   // margin.lower_string()
//   ctx.stats[PredicateKind::power].filter_failures;
#pragma once

#include "exact/filter_stats.hpp"
#include "exact/interval.hpp"
#include "exact/number_types.hpp"
#include "exact/simplex_predicates.hpp"
#include "exact/tangent_predicates.hpp"
#include "exact/tangent_space.hpp"
