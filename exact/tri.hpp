// Tri: the answer of a question that a certified computation may fail to decide — yes, no, or
// unknown (CGAL calls the same idea Uncertain<bool>). Used wherever a test can be proven either
// way or left open: star membership and sphere recognition in certify/, the termination
// hypotheses in core/refine. `unknown` is never rounded to yes or no silently: callers map it to
// UNDECIDED (certify) or "not evaluable" (refine), by name.
#pragma once

namespace delcert::exact {

enum class Tri { no, yes, unknown };

// yes/no from a decided boolean.
constexpr Tri tri(bool b) { return b ? Tri::yes : Tri::no; }

// Three-valued conjunction (Kleene): no if either is no, yes if both are yes, else unknown.
constexpr Tri operator&&(Tri a, Tri b) {
  if (a == Tri::no || b == Tri::no) return Tri::no;
  return a == Tri::yes && b == Tri::yes ? Tri::yes : Tri::unknown;
}

// Three-valued negation.
constexpr Tri operator!(Tri a) { return a == Tri::unknown ? a : tri(a == Tri::no); }

}  // namespace delcert::exact
