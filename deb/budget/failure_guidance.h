// What to fix when an output fails: figures an engineer can act on, from the
// grid variances of the result alone (a pure function of the OutputResult and
// its grid). Contributors are uncorrelated (docs/method.md, convention 6):
// the output variance is V = sum of v_c, and multiplying contributor c's
// amplitude (its source's ASD, or its path's gain) by 1/r divides v_c by r^2.
//
// Every factor below is a reduction of RMS AMPLITUDE ("must drop 6x": the
// contributor's RMS, its ASD or its path gain, divided by 6); the factor on
// a PSD is its square. With L the limit (rms_max):
//
//  - fail factor F = sqrt(V) / L. Dividing every source's amplitude by F
//    meets the limit exactly, so F is also the uniform factor on all sources.
//  - the smallest set of contributors whose removal meets the limit: sort
//    by variance, largest first, and take the fewest m with
//    V - (v_1 + ... + v_m) <= L^2. This greedy set is of the smallest count:
//    any set S of m contributors has sum over S <= v_1 + ... + v_m, so if S
//    meets the limit, so do the m largest; hence no set smaller than the
//    greedy one does.
//  - the uniform factor r on the RMS of a set S that meets the limit,
//    V - v_S + v_S / r^2 = L^2, i.e. r = 1 / sqrt(k) with k the allocation
//    factor of S (allocation.h, SourceAllocationFactor). Among sets of m
//    contributors the m largest need the smallest r (r^2 = v_S / (v_S - (V -
//    L^2)) falls as v_S grows). Given for the smallest set (none when
//    removing it exactly meets the limit: then it must go) and for the set
//    one larger, the trade-off ("A must drop 6x, or A and B 3x each"). When
//    the smallest set is one contributor, that is the single-contributor
//    answer.
//  - where the cumulative RMS sqrt(CPS(f)), accumulated from the bottom of
//    the grid up (convention 7), first reaches L: between two grid points the
//    CPS follows the power-law integral of the PSD between them (the rule
//    integrate.h uses), scaled to the stored CPS at both ends, so the
//    crossing agrees with the stored CPS on Gauss-Lobatto panels as well.
//  - the band (of the output's bands) holding most of the largest
//    contributor's variance.
//  - per failing band requirement: its fail factor, its largest contributor
//    (variance within the band, the engine's band integral) with its share of
//    the band, and the factor on that contributor alone that meets the band's
//    limit, where one exists.
//
// Shared sources: the factors are per contributor (source x path). A
// contributor is reduced through its path, or through its source; where the
// source also feeds other contributors (deb warns), reducing the source
// lowers them too, so the stated factor is then sufficient but may be more
// than needed. The exact factor on a shared source is SourceAllocationFactor,
// reported beside the allocation factors in summary.json.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "deb/budget/result.h"

namespace deb {

// The n largest contributors of an output, reduced together by one factor.
struct ContributorReduction {
  std::vector<std::size_t> contributors;  // indices into OutputResult::contributors, largest first
  // The factor on each one's RMS that meets the limit; none when only their
  // removal does (the others alone sit exactly at the limit).
  std::optional<double> rms_factor;
};

// A whole-grid requirement that fails (rms > rms_max).
struct RequirementGuidance {
  double fail_factor = 0.0;     // rms / rms_max > 1; also the uniform factor on every source's RMS
  std::size_t dominant = 0;     // the contributor with the largest variance
  double dominant_share = 0.0;  // its fraction of the output's variance
  std::optional<Band> dominant_band;  // the output band holding most of its variance
  // The smallest set of largest contributors whose removal meets the limit.
  std::vector<std::size_t> remove;
  // reduce[0]: that set with its uniform factor; reduce[1], where there is a
  // larger set whose contributors add variance: one contributor more.
  std::vector<ContributorReduction> reduce;
  // Where sqrt(CPS) first reaches rms_max.
  std::optional<double> cps_crossing_hz;
};

// A band requirement that fails.
struct BandGuidance {
  BandRequirement requirement;
  double rms = 0.0;
  double fail_factor = 0.0;   // rms / requirement.rms_max > 1
  std::size_t largest = 0;    // the contributor with the largest variance within the band
  double largest_share = 0.0; // its fraction of the band's variance
  std::optional<double> largest_rms_factor;  // on its RMS alone, to meet the band's limit
};

struct FailureGuidance {
  std::optional<RequirementGuidance> overall;  // none when the whole-grid requirement passes or is absent
  std::vector<BandGuidance> bands;             // the failing band requirements, in the budget's order
  std::string sentence;                        // GuidanceSentence with the unit as deb prints it
};

// The smallest set of largest contributors whose removal meets rms_max, with
// the uniform factor on their RMS that meets it (RequirementGuidance::reduce[0]).
// DEB_DEMANDs an output with a requirement that fails.
ContributorReduction SmallestReduction(const OutputResult& output);

// SmallestReduction, then, where a larger set adds variance, the set one
// contributor larger with its factor: the trade-off the guidance sentence
// offers ("A must drop 6x, or A and B 3x each"); RequirementGuidance::reduce.
// DEB_DEMANDs an output with a requirement that fails.
std::vector<ContributorReduction> Reductions(const OutputResult& output);

// Each contributor's variance within [lo_hz, hi_hz] (inside the grid), by the
// engine's band integral: what a band requirement holds of each.
std::vector<double> VarianceWithin(const OutputResult& output, const FrequencyGrid& grid, double lo_hz,
                                   double hi_hz);

// Guidance for an output that fails a requirement (whole-grid or band); none
// when it meets all of them. `grid` is the result's grid (psd and cps of the
// output hold one value per grid point).
std::optional<FailureGuidance> GuideFailure(const OutputResult& output, const FrequencyGrid& grid);

// The first frequency where `cps` (a forward CPS of `psd` on f_hz) reaches
// `variance`; none when it never does (or variance <= 0, where it holds from
// the start). Between grid points: the power-law integral of the PSD from the
// point below, scaled to the stored CPS at both ends.
// DEB_DEMANDs sizes that agree (>= 1).
std::optional<double> CpsCrossingHz(const std::vector<double>& f_hz, const std::vector<double>& psd,
                                    const std::vector<double>& cps, double variance);

// One sentence for the head of the output's section and the console, e.g.
// "position fails by 7.071×: thermal_force (62.1 %, 0.5–2 Hz) must drop
// 6.325×, or thermal_force and cooling_water 3.162× each; the cumulative RMS
// reaches 1 nm at 0.6124 Hz", then a clause per failing band. Factors and
// frequencies to `digits` significant digits; `unit_text` is the output's
// unit as the document prints it.
std::string GuidanceSentence(const OutputResult& output, const FailureGuidance& guidance,
                             const std::string& unit_text, int digits = 4);

}  // namespace deb
