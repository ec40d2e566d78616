// What the ranks of a distributed certification (certify/detail/world.hpp) send each other, and
// which points each rank analyses.
//
// The byte format is private to one run of one binary (every rank runs the same executable on the
// same machine type): fixed-width integers and doubles are copied as their bytes, rationals as
// base-16 strings, so what rank 0 decodes is bit for bit what the sending rank computed. A
// truncated or overlong message throws (an internal error: nothing is certified).
#pragma once

#include <string>
#include <vector>

#include "certify/tangential/star.hpp"
#include "certify/tangential/theorem.hpp"
#include "exact/filter_stats.hpp"

namespace delcert::certify {

namespace detail {
class PointGrid;
}  // namespace detail

// The points rank `rank` of `size` analyses, in increasing index order: the rank-th of `size`
// near-equal consecutive blocks of the grid's cell order (cells are ordered lexicographically by
// their integer coordinates, so each block is a spatial slab, up to its two boundary cells).
// Every point is in exactly one block.
std::vector<int> owned_points(const detail::PointGrid& grid, int rank, int size);

// A rank's results, one per point of its block `owned` in that order, and back on rank 0: decode
// writes reports[p] for each p of `owned`.
std::string encode(const std::vector<StarReport>& of_owned);
void decode(const std::string& bytes, const std::vector<int>& owned, std::vector<StarReport>& reports);
std::string encode(const std::vector<SecureReport>& of_owned);
void decode(const std::string& bytes, const std::vector<int>& owned, std::vector<SecureReport>& reports);

std::string encode_stats(const exact::FilterStats& stats);
exact::FilterStats decode_stats(const std::string& bytes);
std::string encode_measured(const Measured& m);
Measured decode_measured(const std::string& bytes);

}  // namespace delcert::certify
