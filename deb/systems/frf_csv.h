// Reads a measured frequency response (FRF) from deb's numeric table format
// (core/numeric_table.h). A header row names the frequency column first, then
// two columns per entry H_ij, named OUTPUT/INPUT.PART with the parts
//   re, im                 real and imaginary part
//   mag, phase_deg         magnitude and phase in degrees
//   db, phase_deg          magnitude in dB (20 log10 |H|) and phase in degrees
//
//   f_hz, z/F.mag, z/F.phase_deg
//   1.0,  1.2e-3,  -2.5
//
// The outputs and inputs are the names found, in order of first appearance,
// unless the caller lists them (then the file must hold exactly those). Every
// entry H_ij must be present. A column OUTPUT/INPUT.coherence (as `deb
// spectrum frf` writes) is information for the reader and is skipped. Errors
// quote file:line:column and the rule.
#pragma once

#include <string>
#include <vector>

#include "deb/core/extrapolation.h"
#include "deb/systems/measured_response.h"

namespace deb {

struct FrfCsv {
  std::vector<std::string> outputs, inputs;
  MeasuredResponse response;
};

// @throws InputError (file:line:column) for a missing header, a column name
//   not of the form OUTPUT/INPUT.PART, a part that is unknown or mixes forms
//   for one entry, a missing or repeated entry, a name not in a given list, a
//   frequency <= 0 or not increasing, a negative magnitude, fewer than 2 rows.
FrfCsv ReadFrfCsv(const std::string& path, const std::vector<std::string>& outputs = {},
                  const std::vector<std::string>& inputs = {}, Extrapolation extrapolation = Extrapolation::kError);
FrfCsv ParseFrfCsv(std::istream& in, const std::string& name, const std::vector<std::string>& outputs = {},
                   const std::vector<std::string>& inputs = {}, Extrapolation extrapolation = Extrapolation::kError);

// The responses from one input as a file ReadFrfCsv reads: each line of
// `comments` as "# ...", then f_hz and OUTPUT/INPUT.mag, .phase_deg (and
// .coherence with a non-empty `coherence`) per output, every digit; rows
// at f <= 0 are left out. h and coherence are f_hz.size() x outputs.size().
// DEB_DEMANDs matching sizes.
std::string FrfCsvText(const std::vector<std::string>& comments, const std::vector<double>& f_hz,
                       const std::string& input, const std::vector<std::string>& outputs, const Eigen::MatrixXcd& h,
                       const Eigen::MatrixXd& coherence = {});

}  // namespace deb
