// Internal: not part of the public API.
// "Did you mean ...?" for a misspelt name: the candidate nearest to what the
// user wrote, by edit distance, when it is near enough to be a likely typo.
#pragma once

#include <string>
#include <vector>

namespace deb {

// Levenshtein distance: insertions, deletions and substitutions of bytes.
std::size_t EditDistance(const std::string& a, const std::string& b);

// The candidate nearest to `word` if its distance is at most 1 + |word| / 4
// (1 for short words, 3 for 8..11 letters) and smaller than the word itself;
// ties go to the first. "" if none is near, or `word` is a candidate.
std::string NearestName(const std::string& word, const std::vector<std::string>& candidates);

// " (did you mean 'NEAREST'?)" to follow the quoted word in a message, or ""
// when no candidate is near.
std::string DidYouMean(const std::string& word, const std::vector<std::string>& candidates);

}  // namespace deb
