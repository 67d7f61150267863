#pragma once
// What a speed report says of the machine it ran on: the CPU's model and the SIMD
// instruction sets the correlator kernels care about.
#include <string>
#include <vector>

namespace deepnav::bench {

/// The CPU's model name as the kernel reports it ("unknown" where it does not).
std::string cpu_model();
/// The SIMD instruction sets the correlator kernels care about that this CPU has.
std::vector<std::string> instruction_sets();

}  // namespace deepnav::bench
