// "Did you mean ...?" suggestions for misspelt keys, link names and symbols.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace dyncc::robot {

/// Optimal-string-alignment distance: insert, delete, substitute and swap of two adjacent
/// characters each cost 1 (a swap is the most common typo: 'thetaa', 'yx' for 'xy').
std::size_t edit_distance(std::string_view a, std::string_view b);

/// The candidate closest to `word`, if it is close enough to be a plausible typo
/// (distance at most 1 for short words, at most a third of the length otherwise);
/// empty when none is. Case is ignored. Among equally close candidates one with the same
/// letters (a reordering) wins, then the earlier one, so results are deterministic.
std::string closest_match(std::string_view word, const std::vector<std::string>& candidates);

}  // namespace dyncc::robot
