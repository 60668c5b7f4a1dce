// Internal: not part of the public API.
// The path types that are control blocks (deb/systems/control_blocks.h):
// zpk, second_order, mass_spring_damper, pid, lead_lag, notch, lowpass,
// highpass, integrator, each a SISO transfer function from its own keys,
// and the two that are not rational in s, delay and discrete
// (docs/budget_reference.md, "Blocks").
#pragma once

#include <set>
#include <string>

#include "deb/load/yaml_reader.h"
#include "deb/systems/irrational_block.h"
#include "deb/systems/transfer_function.h"

namespace deb::load {

// True for the name of a block path type.
bool IsBlockType(const std::string& type);

// The keys a block of `type` takes besides the common path keys.
std::set<std::string> BlockKeys(const std::string& type);

// True for the blocks that are not rational in s: delay, discrete.
bool IsIrrationalType(const std::string& type);
// The keys a delay or discrete block takes besides the common path keys.
std::set<std::string> IrrationalKeys(const std::string& type);
// delay: {seconds, pade_order}; discrete: {sample_hz, num, den, zoh,
// pade_order} (irrational_block.h).
// @throws InputError located at the offending key.
IrrationalBlock ParseIrrationalBlock(const YamlNode& node, const std::string& type);

// The block's transfer function. A mass_spring_damper is in SI (m/N); its
// caller scales it to the path's units.
// @throws InputError located at the offending key.
TransferFunction ParseBlock(const YamlNode& node, const std::string& type);

}  // namespace deb::load
